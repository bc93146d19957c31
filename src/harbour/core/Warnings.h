#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace harbour::core {

/// Physics anomalies the simulation counts instead of throwing (MuJoCo style); tests fail on any.
enum class Warning : std::uint8_t {
  kNonFinite,       ///< a NaN, infinity or runaway value appeared in a state: the physics diverged
  kMassDrift,       ///< a conservation check failed beyond rounding
  kNegativeHeight,  ///< a bulk cell went below its base
  kSolverLimit,     ///< an iterative solver hit its iteration limit
  kSolverMessage,   ///< the rigid-body solver reported a numerical problem (an ODE message)
  kCount
};

std::string_view to_string(Warning w);

/// Counts per warning kind; part of the simulation state.
class Warnings {
 public:
  void raise(Warning w) { ++counts_[static_cast<std::size_t>(w)]; }
  std::uint32_t count(Warning w) const { return counts_[static_cast<std::size_t>(w)]; }
  std::uint32_t total() const {
    std::uint32_t sum = 0;
    for (auto c : counts_)
      sum += c;
    return sum;
  }
  void clear() { counts_.fill(0); }

 private:
  std::array<std::uint32_t, static_cast<std::size_t>(Warning::kCount)> counts_{};
};

}  // namespace harbour::core
