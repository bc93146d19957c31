#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "harbour/machines/parts/DrivingCab.h"
#include "harbour/machines/parts/SpreaderHoist.h"
#include "harbour/machines/parts/WheeledChassis.h"
#include "harbour/sim/Machine.h"
#include "harbour/sim/MachineSetup.h"

namespace harbour::sim {

const MachineType& straddle_carrier_machine_type();  ///< machines/straddle_carrier/Type.cpp

/// A straddle carrier (settings, from data/machines/straddle_carrier.yaml): a four-leg portal on eight wheels
/// that drives over a row of boxes and lifts one between its legs. Frame: the portal's centre of mass, x
/// forward, z up; heights of the structure are given above the ground under it.
struct StraddleCarrierSettings {
  double mass_kg = 62000.0;                  ///< [kg] portal, power pack and cab (the spreader apart)
  core::Vec3 half_extents_m{4.8, 2.4, 7.0};  ///< the portal as a box about its centre of mass (its inertia)
  double leg_x_m = 3.9;                      ///< [m] the legs stand at ±this along it ...
  double leg_y_m = 2.05;                     ///< ... and, with the sills, at ±this across
  double leg_width_m = 0.5;                  ///< [m] the legs' and sills' width
  double sill_bottom_m = 1.0;                ///< [m] the sill beams' underside above the ground
  double sill_top_m = 1.9;                   ///< [m] ... and their top, where the legs start
  double top_frame_m = 14.3;                 ///< [m] the top frame's underside, where the legs end
  /// [m²] the portal's area the wind meets: blowing along it (its x) and across it
  double wind_area_front_m2 = 40.0, wind_area_side_m2 = 70.0;
  WheeledChassisSettings chassis;  ///< its eight wheels, four along each sill, every one steered
  double steer_rate_per_s = 0.5;   ///< steering command travel per second
  SpreaderHoistSettings rig;       ///< the hoist's reeving's bodies: [portal, headblock]
  scene::ControlTable controls;
  core::Vec3 cab_position_m{3.9, 1.6, 6.5};  ///< [m] the cab's centre on the portal
  core::Vec3 eye_m{0.3, 0.0, 0.5};           ///< [m] the eye in the cab (x the way the driver faces)
  scene::CabSight sight{0.0, -0.5, 0.9};

  /// The ground's height in the portal's frame at rest on unloaded tyres [m] (below its centre of mass).
  double ground_z_m() const { return chassis.axles.front().hub_z_m - chassis.tyre.radius_m; }
};

/// Where the straddle carrier stands at the start.
struct StraddleCarrierStart {
  core::Vec3 position_m;       ///< [m] the ground under its centre
  double heading_rad = 0.0;    ///< its x from world x, about z
  double spreader_z_m = 10.0;  ///< [m] the spreader's centre above the ground
};

/// The straddle carrier's controls, read by label from its table.
struct StraddleCarrierSlots {
  int hoist, lock, unlock, spreader_20, spreader_40, spreader_45;
  explicit StraddleCarrierSlots(const scene::ControlTable& table);
};

/// A straddle carrier on the physics world: its portal one body on the shared wheeled chassis (eight tyres,
/// Ackermann steering of every wheel about its middle, the drivetrain, brakes and the driving cab's
/// steering wheel, pedals and direction selector), touching the world by its sills, legs and top frame; the
/// shared spreader hoist hangs between its legs from sheaves in the top frame, the spreader's length along
/// the portal's x, so it lifts a box of the row it straddles and carries it over the others.
class StraddleCarrier final : public Machine {
 public:
  StraddleCarrier(physics::PhysicsWorld& world, const StraddleCarrierSettings& settings,
                  const StraddleCarrierStart& start);

  // Machine
  const MachineType& type() const override { return straddle_carrier_machine_type(); }
  const scene::ControlTable& control_table() const override { return settings_.controls; }
  void step(const scene::Controls& controls, std::span<const ContainerRef> liftables, double dt_s) override;
  std::optional<physics::BodyId> held_item() const override { return rig_->locked_container(); }
  std::optional<physics::BodyId> gripper_body() const override { return rig_->spreader_body(); }
  void stand_on(const Ground& ground) override { ground_ = &ground; }
  double attachment_bottom_z_m() const override { return rig_->attachment_bottom_z_m(); }
  double pendulum_length_m() const override { return rig_->pendulum_length_m(); }
  double lowering_speed_mps() const override { return rig_->lowering_speed_mps(); }
  std::span<const WindArea> wind_areas() const override { return wind_areas_; }
  physics::BodyId cab_body() const override { return body_; }
  core::Vec3 eye_on_cab_body_m() const override { return settings_.cab_position_m + settings_.eye_m; }
  core::Pose cab_pose() const override;
  core::Vec3 eye_m() const override { return settings_.eye_m; }
  scene::CabSight cab_sight() const override { return settings_.sight; }
  void describe(scene::SceneDescription& scene) const override;
  int publish(scene::Snapshot& snapshot, int entities) const override;
  MachineTally tally() const override;
  Telemetry telemetry() const override;
  void settle_ropes() override { rig_->settle_ropes(); }
  void settle_at_rest() override;
  void drain_events(StepEvents& events) override;
  void inject_fault(MachineFault fault, int detail) override;
  void clear_faults() override { rig_->clear_faults(); }
  bool fault_active(MachineFault fault) const override;
  void hash_into(core::StateHash& hash) const override;
  void save_state(core::StateWriter& out) const override;
  void restore_state(core::StateReader& in) override;

  const StraddleCarrierSettings& settings() const { return settings_; }
  physics::BodyId body() const { return body_; }
  const WheeledChassis& chassis() const { return chassis_; }
  const SpreaderHoist& spreader_hoist() const { return *rig_; }
  /// Speed along its heading where its wheels touch the ground [m/s] (+ forward; its speedometer's).
  double forward_mps() const;
  /// The steering as it stands [-1, 1] (+ left).
  double steering() const { return cab_.steering(); }
  core::Pose spreader_pose() const { return world_.pose(rig_->spreader_body()); }
  /// Where the top frame's sheaves hang the spreader: the portal's middle (world, on the ground plane) [m].
  core::Vec3 plumb_m() const;

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  physics::PhysicsWorld& world_;
  StraddleCarrierSettings settings_;
  StraddleCarrierSlots slots_;
  FlatGround yard_;
  const Ground* ground_ = &yard_;
  DrivingCab cab_;
  physics::BodyId body_;
  WheeledChassis chassis_;
  std::unique_ptr<SpreaderHoist> rig_;
  std::array<WindArea, 2> wind_areas_;  // the spreader, the portal
};

/// A straddle carrier and where it stands (settings).
struct StraddleCarrierSetup {
  StraddleCarrierSettings vehicle;
  StraddleCarrierStart start;

  static const MachineType& type() { return straddle_carrier_machine_type(); }
  const scene::ControlTable& controls() const { return vehicle.controls; }
  std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const;
  std::vector<cable::ReevingSettings*> reevings() { return {&vehicle.rig.hoist}; }
};

}  // namespace harbour::sim
