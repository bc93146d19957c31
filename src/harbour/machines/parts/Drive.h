#pragma once

#include "harbour/core/StateArchive.h"

#include <cstdint>

namespace harbour::sim {

/// One motorised axis of a machine (gantry, trolley, boom, slew, telescope): settings from the machine file.
struct DriveSettings {
  double max_speed_mps = 1.0;                ///< [m/s] (or [rad/s] for rotary axes) at full lever
  double acceleration_mps2 = 0.5;            ///< [m/s^2] ramp up
  double deceleration_mps2 = 0.5;            ///< [m/s^2] ramp down (service)
  double emergency_deceleration_mps2 = 1.0;  ///< [m/s^2] e-stop
  double max_force_n = 1e5;                  ///< [N] motor force (torque) limit
  double brake_force_n = 2e5;                ///< [N] holding brake
  double min_position_m = -1e9;              ///< [m] limit switch
  double max_position_m = 1e9;               ///< [m] limit switch
};

/// What the drive asks of the joint this step: a velocity with a force limit (ODE motor semantics).
struct DriveOutput {
  double velocity_mps = 0.0;
  double max_force_n = 0.0;
  bool brake = false;  ///< holding brake set (velocity 0, brake force)
};

/// A speed-controlled drive: the lever sets a speed reference that ramps within the acceleration limits,
/// slows down ahead of the limit switches so it stops on them, stops at an e-stop, and sets its brake at
/// rest. Shared by every machine's axes (parameterised by data).
class Drive {
 public:
  explicit Drive(const DriveSettings& settings) : settings_(settings) {}

  /// `lever` in [-1, 1]; `position_m` measured on the axis. `brake_fault` keeps the brake from setting.
  DriveOutput step(double lever, double position_m, double dt_s, bool emergency_stop,
                   bool brake_fault = false);

  double reference_mps() const { return reference_; }
  /// Times the operator drove into a limit switch (counted when the limit is first reached while pushing).
  std::uint32_t limit_hits() const { return limit_hits_; }
  bool at_limit() const { return at_limit_; }
  const DriveSettings& settings() const { return settings_; }
  void save_state(core::StateWriter& out) const { archive(*this, out); }
  void restore_state(core::StateReader& in) { archive(*this, in); }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar(self.reference_, self.at_limit_, self.limit_hits_);
  }

  DriveSettings settings_;
  double reference_ = 0.0;
  bool at_limit_ = false;
  std::uint32_t limit_hits_ = 0;
};

/// A hydraulic cylinder's drive: the valve's flow sets the cylinder's speed whatever its load (up to its
/// relief force), so its position is the integral of the Drive's speed, and a stopped cylinder holds on its
/// valves. The joint's motor follows that position (the solver's constraint softness would otherwise let a
/// motor lag its speed under a large steady load: about 1e-3 m/s per MN at the world's default softness).
class HydraulicDrive {
 public:
  explicit HydraulicDrive(const DriveSettings& settings) : drive_(settings) {}

  DriveOutput step(double lever, double position_m, double dt_s, bool emergency_stop);
  const Drive& drive() const { return drive_; }
  double reference_mps() const { return drive_.reference_mps(); }
  void save_state(core::StateWriter& out) const { archive(*this, out); }
  void restore_state(core::StateReader& in) { archive(*this, in); }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar.part(self.drive_);
    ar(self.tracking_, self.target_m_);
  }

  static constexpr double kFollow_s = 0.2;  ///< [s] the time constant the joint follows its position with
  static constexpr double kSlack_m = 0.01;  ///< [m] the most the position runs ahead of a stalled cylinder
  Drive drive_;
  bool tracking_ = false;
  double target_m_ = 0.0;
};

}  // namespace harbour::sim
