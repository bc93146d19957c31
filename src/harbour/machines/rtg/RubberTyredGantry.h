#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "harbour/machines/GantryCrane.h"
#include "harbour/machines/parts/Drive.h"
#include "harbour/machines/parts/SpreaderHoist.h"
#include "harbour/machines/parts/Tyre.h"
#include "harbour/sim/Machine.h"
#include "harbour/sim/MachineSetup.h"

namespace harbour::sim {

const MachineType& rtg_machine_type();  ///< machines/rtg/Type.cpp

/// A rubber-tyred gantry crane (settings, from data/machines/rtg.yaml). Its frame: x across the yard block
/// (the trolley's travel), y along it (the gantry's travel), z up, the origin at the structure's centre of
/// mass above the middle of its wheels.
struct RtgSettings {
  double frame_mass_kg = 130000.0;      ///< [kg] structure and machinery (the trolley apart)
  double frame_centre_height_m = 12.0;  ///< [m] its centre of mass above the ground
  double span_m = 23.47;                ///< [m] wheel span across the block (tyre centre lines)
  double wheelbase_m = 6.4;             ///< [m] between the corners' bogies along the block
  double bogie_tyre_spacing_m = 1.6;    ///< [m] a corner's two tyres apart along the block
  double sill_height_m = 1.8;           ///< [m] the sill beams' underside above the ground
  double leg_width_m = 1.2;             ///< [m] the legs' and sills' width across
  /// [m²] the structure's area the wind meets (legs, sills, girders, trolley and machinery, a member behind
  /// another counted in part): blowing across the block (along x) and along it (along y)
  double wind_area_across_m2 = 100.0, wind_area_along_m2 = 160.0;
  TyreSettings tyre;
  /// Gantry travel: the drive's speed reference (its max speed empty), the tractive force limit in
  /// max_force_n; the speed controller shares it out over the eight tyres.
  DriveSettings gantry_drive;
  double gantry_loaded_speed_mps = 1.5;  ///< [m/s] the most with a box on the spreader
  double max_steer_rad = 0.05;      ///< the bogies' steering at full lever (front one way, rear the other)
  double wheel_turn_time_s = 60.0;  ///< [s] the wheels' 90° turn for a block change
  DriveSettings trolley_drive;
  double trolley_mass_kg = 20000.0;
  double trolley_rail_height_m = 22.0;  ///< [m] the trolley's centre above the ground
  SpreaderHoistSettings rig;            ///< its reeving's bodies: [trolley, headblock]
  scene::ControlTable controls;
  core::Vec3 cab_position_m{0.0, -3.0, -2.5};  ///< [m] the cab's centre in the trolley's frame; the operator
                                               ///< faces along the trolley's +y, towards the spreader
  core::Vec3 eye_m{0.3, 0.0, 0.6};             ///< [m] the eye in the cab's frame (x the way it faces)
  scene::CabSight sight{0.0, -1.0, 0.75};
};

/// Where the RTG stands at the start.
struct RtgStart {
  core::Vec3 position_m;        ///< [m] the ground under the middle of its wheels
  double heading_rad = 0.0;     ///< its frame's x from world x, about z (0: the block along world y)
  double trolley_x_m = 0.0;     ///< [m] on the frame, from its middle
  double spreader_z_m = 15.0;   ///< [m] above the ground
  double steer_bias_rad = 0.0;  ///< an auto-steer deviation: a bias in the bogies' steering the
                                ///< operator corrects
};

/// The RTG's controls, read by label from its table.
struct RtgControlSlots {
  int gantry, trolley, hoist, steer, wheel_turn, lock, unlock, emergency_stop, horn, spreader_20, spreader_40,
      spreader_45;
  explicit RtgControlSlots(const scene::ControlTable& table);
};

/// A rubber-tyred gantry crane on the physics world: its frame on eight tyres (the shared tyre model: the
/// ground's push, rolling resistance, cornering and the friction circle), two to a corner bogie; gantry
/// travel by a speed controller sharing the tractive force over them, the bogies steered (front against
/// rear) to correct its line; the wheels' 90° turn for a block change, only at a standstill; the trolley
/// on a motorised slider across the frame and the shared spreader hoist (ropes on the cable model,
/// twistlocks) under it; the cab rides on the trolley.
class RubberTyredGantry final : public Machine, public GantryCrane {
 public:
  RubberTyredGantry(physics::PhysicsWorld& world, const RtgSettings& settings, const RtgStart& start);

  // Machine
  const MachineType& type() const override { return rtg_machine_type(); }
  const scene::ControlTable& control_table() const override { return settings_.controls; }
  void step(const scene::Controls& controls, std::span<const ContainerRef> liftables, double dt_s) override;
  std::optional<physics::BodyId> held_item() const override { return rig_->locked_container(); }
  std::optional<physics::BodyId> gripper_body() const override { return rig_->spreader_body(); }
  void stand_on(const Ground& ground) override { ground_ = &ground; }
  double attachment_bottom_z_m() const override { return rig_->attachment_bottom_z_m(); }
  double pendulum_length_m() const override { return rig_->pendulum_length_m(); }
  double lowering_speed_mps() const override { return rig_->lowering_speed_mps(); }
  std::span<const WindArea> wind_areas() const override { return wind_areas_; }
  physics::BodyId cab_body() const override { return trolley_; }
  core::Vec3 eye_on_cab_body_m() const override;
  core::Pose cab_pose() const override;
  core::Vec3 eye_m() const override { return settings_.eye_m; }
  scene::CabSight cab_sight() const override { return settings_.sight; }
  void describe(scene::SceneDescription& scene) const override;
  int publish(scene::Snapshot& snapshot, int entities) const override;
  MachineTally tally() const override;
  Telemetry telemetry() const override;
  void settle_ropes() override { rig_->settle_ropes(); }
  void settle_at_rest() override {
    const physics::BodyId bodies[] = {frame_, trolley_, rig_->spreader_body()};
    settle_gantry_crane(*this, world_, bodies, *rig_);
  }
  void drain_events(StepEvents& events) override;
  void inject_fault(MachineFault fault, int detail) override;
  void clear_faults() override { rig_->clear_faults(); }
  bool fault_active(MachineFault fault) const override {
    return fault == MachineFault::kHoistBrake     ? rig_->brake_fault()
           : fault == MachineFault::kLandedSensor ? rig_->landed_sensor_fault()
                                                  : false;
  }
  void hash_into(core::StateHash& hash) const override;
  void save_state(core::StateWriter& out) const override;
  void restore_state(core::StateReader& in) override;

  // GantryCrane (the frame square to the world: its y along world y)
  double gantry_y_m() const override { return world_.pose(frame_).position.y; }
  double trolley_x_m() const override { return world_.pose(trolley_).position.x; }
  double gantry_reference_mps() const override { return gantry_.reference_mps(); }
  double trolley_reference_mps() const override { return trolley_drive_.reference_mps(); }
  double gantry_max_speed_mps() const override;
  double trolley_max_speed_mps() const override { return settings_.trolley_drive.max_speed_mps; }
  const SpreaderHoist& spreader_hoist() const override { return *rig_; }
  scene::Controls crane_controls(const GantryLevers& levers) const override;
  /// The frame's centre off the line it started on, across the block [m] (+ towards its +x).
  double lane_offset_m() const override;
  /// The frame's yaw from its start heading [rad].
  double yaw_rad() const override;
  double steer_lever(double yaw_rate_radps) const override;

  const RtgSettings& settings() const { return settings_; }
  physics::BodyId frame_body() const { return frame_; }
  physics::BodyId trolley_body() const { return trolley_; }
  /// The frame's speed along the way its wheels roll [m/s] (its y in travel, its x once turned).
  double travel_speed_mps() const;
  /// How far the wheels are turned: 0 along the block, 1 across it (a block change).
  double wheel_turn() const { return wheel_turn_; }
  /// Turns asked for while the crane moved (each refused, counted once per switch movement).
  std::uint32_t wheel_turn_refusals() const { return turn_refusals_; }
  double trolley_position_m() const { return trolley_start_x_ + world_.slider_position(trolley_slider_); }
  core::Pose spreader_pose() const { return world_.pose(rig_->spreader_body()); }
  /// Where the trolley's sheaves hang the spreader (world, horizontal) [m].
  core::Vec3 plumb_m() const;
  bool horn() const { return horn_; }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  /// The bogies' steering angle for a steering lever, the auto-steer's bias added [rad].
  double steer_angle_rad(double steer) const;
  /// Each corner tyre's heading from the frame's x for a steering lever [rad].
  double tyre_heading_rad(double y_m, double steer) const;

  physics::PhysicsWorld& world_;
  RtgSettings settings_;
  RtgControlSlots slots_;
  RtgStart start_;
  FlatGround yard_;
  const Ground* ground_ = &yard_;
  physics::BodyId frame_, trolley_;
  physics::SliderId trolley_slider_;
  double trolley_start_x_;
  Drive gantry_, trolley_drive_;
  bool gantry_braked_ = true;                // the holding brakes are set (it starts parked)
  std::array<double, 2> travel_integral_{};  // [m] each side's speed controller's integral of its error
  double gantry_force_n_ = 0.0;  // the travel drives' force in the last step (published: not state)
  double gantry_power_w_ = 0.0;  // what they delivered at the tyres' contacts in it (measured: not state)
  double wheel_turn_ = 0.0;      // 0: along the block, 1: across
  bool turn_refused_ = false;    // the switch asks a turn that was refused (until it goes back)
  std::uint32_t turn_refusals_ = 0;
  bool horn_ = false;
  std::unique_ptr<SpreaderHoist> rig_;
  std::array<WindArea, 2> wind_areas_;  // the spreader, the structure
};

/// A rubber-tyred gantry and where it stands (settings).
struct RtgSetup {
  RtgSettings crane;
  RtgStart start;

  static const MachineType& type() { return rtg_machine_type(); }
  const scene::ControlTable& controls() const { return crane.controls; }
  std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const;
  std::vector<cable::ReevingSettings*> reevings() { return {&crane.rig.hoist}; }
};

}  // namespace harbour::sim
