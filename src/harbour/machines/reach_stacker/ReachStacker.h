#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "harbour/machines/parts/Drive.h"
#include "harbour/machines/parts/DrivingCab.h"
#include "harbour/machines/parts/Spreader.h"
#include "harbour/machines/parts/SpreaderLocks.h"
#include "harbour/machines/parts/WheeledChassis.h"
#include "harbour/machines/reach_stacker/ReachStackerStability.h"
#include "harbour/sim/Machine.h"
#include "harbour/sim/MachineSetup.h"

namespace harbour::sim {

const MachineType& reach_stacker_machine_type();  ///< machines/reach_stacker/Type.cpp

/// Where the reach stacker stands and how its boom is set at the start.
struct ReachStackerStart {
  core::Vec3 position_m;     ///< [m] the point under its centre of mass on the ground
  double heading_rad = 0.0;  ///< its x from world x, about z
  double boom_rad = 0.2;     ///< the boom's angle above the chassis's x
  double extension_m = 0.0;  ///< the telescope out
};

/// A reach stacker on the physics world: a chassis body on the shared wheeled chassis (the front axle drives,
/// the rear one steers), the boom's outer section on a hinge at its pivot (the lift cylinders as the hinge's
/// speed-controlled motor), the inner section on a slider in it (the extension cylinder), and at its head a
/// rotator hanging free on the head pin (damped in pitch), turning the spreader about the vertical and
/// shifting it along its length. The twistlocks hold a container to the spreader (SpreaderLocks). The
/// load-moment indicator reads the load on the head pin against the load chart at the head's reach: it
/// warns from warn_from and stops the boom lowering and extending at the chart (the limiter fault leaves
/// them free); the machine can then tip forward in the physics, counted when its chassis tilts past
/// tip_over_rad.
class ReachStacker final : public Machine {
 public:
  ReachStacker(physics::PhysicsWorld& world, const ReachStackerSettings& settings,
               const ReachStackerStart& start);

  // Machine
  const MachineType& type() const override { return reach_stacker_machine_type(); }
  const scene::ControlTable& control_table() const override { return settings_.controls; }
  void step(const scene::Controls& controls, std::span<const ContainerRef> liftables, double dt_s) override;
  std::optional<physics::BodyId> held_item() const override { return locks_.locked_container(); }
  std::optional<physics::BodyId> gripper_body() const override { return spreader_; }
  void stand_on(const Ground& ground) override { ground_ = &ground; }
  double attachment_bottom_z_m() const override;
  double pendulum_length_m() const override { return settings_.head_drop_m; }
  double lowering_speed_mps() const override;
  std::span<const WindArea> wind_areas() const override { return wind_areas_; }
  physics::BodyId cab_body() const override { return body_; }
  core::Vec3 eye_on_cab_body_m() const override { return settings_.cab_position_m + settings_.eye_m; }
  core::Pose cab_pose() const override;
  core::Vec3 eye_m() const override { return settings_.eye_m; }
  scene::CabSight cab_sight() const override { return settings_.sight; }
  void describe(scene::SceneDescription& scene) const override;
  int publish(scene::Snapshot& snapshot, int entities) const override;
  MachineTally tally() const override;
  void drain_events(StepEvents& events) override { locks_.twistlocks().drain_events(events.twistlocks); }
  void inject_fault(MachineFault fault, int detail) override;
  void clear_faults() override;
  bool fault_active(MachineFault fault) const override;
  void hash_into(core::StateHash& hash) const override;
  void save_state(core::StateWriter& out) const override;
  void restore_state(core::StateReader& in) override;

  physics::BodyId body() const { return body_; }
  physics::BodyId spreader_body() const { return spreader_; }
  const WheeledChassis& chassis() const { return chassis_; }
  const ReachStackerSettings& settings() const { return settings_; }
  /// Speed along its heading where its wheels touch the ground [m/s] (+ forward; its speedometer's).
  double forward_mps() const;
  double steering() const { return cab_.steering(); }
  /// The boom's angle above the chassis's x [rad] and the telescope's extension [m].
  double boom_angle_rad() const { return start_boom_rad_ + world_.hinge_angle(luff_hinge_); }
  double extension_m() const { return start_extension_m_ + world_.slider_position(telescope_slider_); }
  /// The spreader's rotation from square to the boom [rad] and its side-shift [m].
  double rotation_rad() const { return world_.hinge_angle(rotate_hinge_); }
  double side_shift_m() const { return world_.slider_position(shift_slider_); }
  /// The boom's head pin (world) [m] and its reach: how far ahead of the front axle it is (chassis frame).
  core::Vec3 head_m() const;
  double reach_m() const;
  /// The load on the head pin beyond the spreader and rotator, low-passed [kg] (what the indicator reads).
  double measured_load_kg() const { return measured_load_kg_; }
  /// The load-moment indicator: the load's share of the chart at the head's reach.
  double load_moment_share() const;
  /// The limiter holds the boom from lowering and extending.
  bool limiter_stopping() const { return limiter_stopping_; }
  /// The chassis's tilt from level [rad] (pitch and roll together).
  double tilt_rad() const;
  std::uint32_t tip_overs() const { return tip_overs_; }
  core::Pose spreader_pose() const { return world_.pose(spreader_); }
  TwistlockLamps lamps() const { return locks_.twistlocks().lamps(); }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  struct StartPoses {
    core::Pose chassis, outer, inner, rotator, slew, spreader;
    core::Vec3 pivot, head;
  };
  ReachStacker(physics::PhysicsWorld& world, const ReachStackerSettings& settings,
               const ReachStackerStart& start, const StartPoses& poses);
  static StartPoses start_poses(const ReachStackerSettings& settings, const ReachStackerStart& start);
  void step_limiter(double dt_s);
  /// The head pin's upward force on the rotator in the world's last step [N].
  double pin_force_n() const;

  physics::PhysicsWorld& world_;
  ReachStackerSettings settings_;
  FlatGround quay_;
  const Ground* ground_ = &quay_;
  DrivingCab cab_;
  int boom_slot_, telescope_slot_, rotate_slot_, shift_slot_, lock_slot_, unlock_slot_, size_20_slot_,
      size_40_slot_;
  physics::BodyId body_, outer_, inner_, rotator_, slew_, spreader_;
  WheeledChassis chassis_;
  physics::HingeId luff_hinge_, tilt_hinge_, rotate_hinge_;
  physics::SliderId telescope_slider_, shift_slider_;
  double start_boom_rad_, start_extension_m_;
  HydraulicDrive luff_, telescope_, rotate_, side_shift_;
  std::unique_ptr<Spreader> frame_;
  SpreaderLocks locks_;
  std::array<WindArea, 3> wind_areas_;
  double measured_load_kg_ = 0.0;
  bool limiter_stopping_ = false, limiter_armed_ = true, limiter_fault_ = false, tipped_ = false;
  int landed_sensor_fault_ = -1;
  std::uint32_t limiter_trips_ = 0, tip_overs_ = 0;
  std::optional<double> restored_pin_n_;  // a keyframe's pin force, read by the first step after it
};

/// A reach stacker and where it stands (settings).
struct ReachStackerSetup {
  ReachStackerSettings vehicle;
  ReachStackerStart start;

  static const MachineType& type() { return reach_stacker_machine_type(); }
  const scene::ControlTable& controls() const { return vehicle.controls; }
  std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const;
  std::vector<cable::ReevingSettings*> reevings() { return {}; }
  /// Its telescope runs to its end stops (as runs recorded before the margin was kept were built).
  void end_stops_at_travel() { vehicle.telescope_end_stop_margin_m = 0.0; }
};

}  // namespace harbour::sim
