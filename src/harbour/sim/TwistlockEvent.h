#pragma once

#include <cstdint>

namespace harbour::sim {

/// Twistlock misuse and interlock events, for evaluation.
enum class TwistlockEvent : std::uint8_t {
  kLockRefusedNotLanded,    ///< lock pressed with fewer than four corners landed (interlock refuses it)
  kUnlockRefusedSuspended,  ///< unlock pressed with the load hanging (interlock refuses it)
  kHoistedUnlocked,         ///< the spreader arrived empty on a container and lifted off without locking
};

}  // namespace harbour::sim
