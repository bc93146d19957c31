#pragma once

#include <cstdint>

#include "harbour/core/Assert.h"

namespace harbour::core {

/// Simulated time as an integer count of fixed steps: no drift, exact rate dividers.
class FixedStepClock {
 public:
  /// `step_s` [s] is the physics step, e.g. 0.001 for 1 kHz.
  explicit FixedStepClock(double step_s) : step_s_(step_s) {
    HARBOUR_ASSERT(step_s > 0.0, "step must be positive");
  }

  void advance() { ++steps_; }
  std::int64_t steps() const { return steps_; }
  double step_s() const { return step_s_; }
  /// Simulated time [s].
  double time_s() const { return static_cast<double>(steps_) * step_s_; }
  /// True on the steps where a subsystem running every `divider` steps is due.
  bool due(std::int64_t divider) const { return steps_ % divider == 0; }
  void reset(std::int64_t steps = 0) { steps_ = steps; }

 private:
  double step_s_;
  std::int64_t steps_ = 0;
};

}  // namespace harbour::core
