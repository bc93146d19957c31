#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "harbour/cable/HoistSystem.h"
#include "harbour/machines/GantryCrane.h"
#include "harbour/machines/parts/Drive.h"
#include "harbour/machines/parts/SpreaderHoist.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/scene/Controls.h"
#include "harbour/sim/Machine.h"
#include "harbour/sim/MachineSetup.h"

namespace harbour::sim {

const MachineType& sts_machine_type();  ///< machines/sts/Type.cpp

/// The STS boom's luffing (settings): raised out of the vessel's way at berthing, lowered and latched to
/// work. Its angle is driven kinematically by a Drive in radians.
struct BoomSettings {
  DriveSettings drive{0.0046, 0.002, 0.002, 0.01, 1.0, 1.0, 0.0, 1.396};  ///< [rad]: 80 deg in ~5 min
  double trolley_park_x_m = 10.0;  ///< [m] the trolley must stand landside of this for the boom to luff,
                                   ///< and cannot pass it while the boom is not down
};

/// A ship-to-shore crane (settings, from data/machines/sts.yaml). Frames: the gantry travels along world y on
/// the quay rails; the trolley along the gantry's x (waterside +x); the hoist reeving's bodies are
/// [gantry, trolley, headblock].
struct StsCraneSettings {
  DriveSettings gantry_drive;
  DriveSettings trolley_drive;
  double gantry_mass_kg = 1.2e6;
  double trolley_mass_kg = 30000.0;
  double trolley_rail_height_m = 49.0;  ///< [m] trolley body centre above the quay
  double hoist_upper_limit_m =
      44.0;  ///< [m] spreader centre height where the upper limit switch stops hoisting
  double hoist_lower_limit_m = -20.0;  ///< [m] ... and the lower one stops lowering (into a hold)
  SpreaderSettings spreader;
  BoomSettings boom;
  TwistlockSettings twistlocks;
  cable::ReevingSettings hoist;
  scene::ControlTable controls;  ///< the cab's controls, by label (its machine file's)
  /// The operator's cab hangs under the trolley: its centre in the trolley's frame [m], and the design eye
  /// point in the cab's frame (x waterside, the way the operator faces; z up) [m].
  core::Vec3 cab_position_m{3.0, -3.2, -3.5};
  core::Vec3 eye_m{0.3, 0.0, 0.6};
  scene::CabSight sight{0.0, -1.3,
                        0.75};  ///< the operator looks down through the cab's floor onto the spreader
  /// The spreader on its hoist, as the shared part takes it.
  SpreaderHoistSettings spreader_hoist() const {
    return {spreader, twistlocks, hoist, hoist_upper_limit_m, hoist_lower_limit_m};
  }
};

/// The operator's controls, normalised (cab joysticks and buttons).
struct StsControls {
  double gantry = 0.0;   ///< [-1, 1] +: along +y
  double trolley = 0.0;  ///< [-1, 1] +: waterside
  double hoist = 0.0;    ///< [-1, 1] +: raise
  double boom = 0.0;     ///< [-1, 1] +: raise the boom
  bool lock = false;
  bool unlock = false;
  bool emergency_stop = false;
  bool horn = false;
  std::uint8_t spreader_size_ft = 0;   ///< a size button held: 20, 40 or 45 (0: none)
  std::array<bool, 4> flipper_down{};  ///< flipper switches per twistlock corner (true: lowered)
  friend bool operator==(const StsControls&, const StsControls&) = default;
};

/// Where the STS reads each of its controls in a Controls (slots of its control table, found by label).
struct StsControlSlots {
  int gantry, trolley, hoist, boom, lock, unlock, emergency_stop, horn, spreader_20, spreader_40, spreader_45;
  std::array<int, 4> flipper;
  /// Throws std::invalid_argument naming a control the table lacks or has of another kind.
  explicit StsControlSlots(const scene::ControlTable& table);
  /// The cab's controls read from `controls` (in range).
  StsControls read(const scene::Controls& controls) const;
  /// `sts` written into `controls` (the other slots kept).
  void write(const StsControls& sts, scene::Controls& controls) const;
};

/// The STS crane on the physics world: gantry and trolley on motorised sliders driven by Drives, the spreader
/// hanging from the 4-rope hoist (cable model), twistlocks that lock a landed container to the spreader.
class StsCrane final : public Machine, public GantryCrane {
 public:
  StsCrane(physics::PhysicsWorld& world, const StsCraneSettings& settings, double gantry_y_m,
           double trolley_x_m, double spreader_z_m);

  /// Drives, hoist ropes (forces onto the bodies) and twistlocks; the caller then steps the physics world.
  void step(const StsControls& controls, std::span<const ContainerRef> containers, double dt_s);

  // Machine
  const MachineType& type() const override { return sts_machine_type(); }
  const scene::ControlTable& control_table() const override { return settings_.controls; }
  void step(const scene::Controls& controls, std::span<const ContainerRef> liftables, double dt_s) override {
    step(read(controls), liftables, dt_s);
  }
  std::optional<physics::BodyId> held_item() const override { return rig_->locked_container(); }
  std::optional<physics::BodyId> gripper_body() const override { return rig_->spreader_body(); }
  double attachment_bottom_z_m() const override;
  std::span<const WindArea> wind_areas() const override { return wind_areas_; }
  physics::BodyId cab_body() const override { return trolley_body_; }
  core::Vec3 eye_on_cab_body_m() const override { return settings_.cab_position_m + settings_.eye_m; }
  void describe(scene::SceneDescription& scene) const override;
  int publish(scene::Snapshot& snapshot, int entities) const override;
  /// Its spreader's swing from plumb under the trolley, its gantry's, trolley's and hoist's speeds, the end
  /// limits they were driven into, what their motors deliver; its gantry warns before it travels.
  MachineTally tally() const override;
  /// The tally's swing and speeds (the hoist's as the spreader's) and its hoist ropes' tension.
  Telemetry telemetry() const override;
  void settle_ropes() override { rig_->settle_ropes(); }
  void settle_at_rest() override {
    const physics::BodyId bodies[] = {gantry_body_, trolley_body_, rig_->spreader_body()};
    settle_gantry_crane(*this, world_, bodies, *rig_);
  }
  void drain_events(StepEvents& events) override;
  void inject_fault(MachineFault fault, int detail) override;
  void clear_faults() override;
  bool fault_active(MachineFault fault) const override;
  void hash_into(core::StateHash& hash) const override;
  // GantryCrane (the gantry's slider starts at x = 0)
  double gantry_y_m() const override { return gantry_position_m(); }
  double trolley_x_m() const override { return trolley_position_m(); }
  double gantry_reference_mps() const override { return gantry_.reference_mps(); }
  double trolley_reference_mps() const override { return trolley_.reference_mps(); }
  double gantry_max_speed_mps() const override { return settings_.gantry_drive.max_speed_mps; }
  double trolley_max_speed_mps() const override { return settings_.trolley_drive.max_speed_mps; }
  const SpreaderHoist& spreader_hoist() const override { return *rig_; }
  scene::Controls crane_controls(const GantryLevers& levers) const override;

  const StsControlSlots& control_slots() const { return slots_; }
  /// The cab's controls as labelled Controls (the other slots neutral), and back.
  scene::Controls controls(const StsControls& sts) const;
  StsControls read(const scene::Controls& controls) const { return slots_.read(controls); }

  double gantry_position_m() const { return gantry_start_y_ + world_.slider_position(gantry_slider_); }
  double trolley_position_m() const { return trolley_start_x_ + world_.slider_position(trolley_slider_); }
  /// Mechanical power the travel drives delivered in the last step [W] (negative while braking).
  double gantry_power_w() const {
    return world_.slider_force(gantry_slider_) * world_.slider_rate(gantry_slider_);
  }
  double trolley_power_w() const {
    return world_.slider_force(trolley_slider_) * world_.slider_rate(trolley_slider_);
  }
  core::Pose spreader_pose() const { return world_.pose(rig_->spreader_body()); }
  core::Vec3 spreader_half_extents_m() const { return rig_->spreader().half_extents_m(); }
  SpreaderState spreader_state() const { return rig_->spreader_state(); }
  /// Boom angle above horizontal [rad]; the boom is latched for work only at 0.
  double boom_angle_rad() const { return boom_angle_; }
  bool horn() const { return horn_; }
  physics::BodyId spreader_body() const { return rig_->spreader_body(); }
  physics::BodyId gantry_body() const { return gantry_body_; }
  physics::BodyId trolley_body() const { return trolley_body_; }
  /// The cab's frame in the world (it rides on the trolley) and its design eye point in that frame.
  core::Pose cab_pose() const override;
  core::Vec3 eye_m() const override { return settings_.eye_m; }
  scene::CabSight cab_sight() const override { return settings_.sight; }
  /// The container locked to the spreader, if any.
  std::optional<physics::BodyId> locked_container() const { return rig_->locked_container(); }
  TwistlockLamps lamps() const { return rig_->locks().twistlocks().lamps(); }
  std::vector<TwistlockEvent> take_twistlock_events() { return rig_->locks().twistlocks().take_events(); }
  const Drive& gantry_drive() const { return gantry_; }
  const Drive& trolley_drive() const { return trolley_; }
  const cable::HoistSystem& hoist() const { return rig_->hoist(); }
  cable::HoistSystem& hoist() { return rig_->hoist(); }
  /// Vertical rope pull on the headblock [N] (the load the hoist carries, spreader included).
  double hoisted_load_n() const { return rig_->hoisted_load_n(); }
  /// Length of the pendulum the load hangs on [m]: from the trolley's sheaves down to the headblock's (the
  /// mean heights of the reeving's sheaves on each).
  double pendulum_length_m() const override { return rig_->pendulum_length_m(); }
  double lowering_speed_mps() const override { return rig_->lowering_speed_mps(); }
  /// Drives, ropes, twistlocks, faults and the locked box for a keyframe (the physics world saves itself).
  void save_state(core::StateWriter& out) const override;
  void restore_state(core::StateReader& in) override;

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  physics::PhysicsWorld& world_;
  StsCraneSettings settings_;
  StsControlSlots slots_;
  physics::BodyId gantry_body_, trolley_body_;
  physics::SliderId gantry_slider_, trolley_slider_;
  double gantry_start_y_, trolley_start_x_;
  Drive gantry_, trolley_, boom_;
  double boom_angle_ = 0.0;
  bool horn_ = false;
  std::unique_ptr<SpreaderHoist> rig_;  // the spreader on its hoist ropes
  std::array<WindArea, 1> wind_areas_;
};

/// An STS and where it starts (settings).
struct StsSetup {
  StsCraneSettings crane;
  double gantry_y_m = 0.0, trolley_x_m = 20.0, spreader_z_m = 20.0;  ///< [m] crane pose at the start

  static const MachineType& type() { return sts_machine_type(); }
  const scene::ControlTable& controls() const { return crane.controls; }
  std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const;
  std::vector<cable::ReevingSettings*> reevings() { return {&crane.hoist}; }
};

}  // namespace harbour::sim
