#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "harbour/bulk/Grab.h"
#include "harbour/cable/HoistSystem.h"
#include "harbour/machines/parts/Drive.h"
#include "harbour/machines/parts/LimitSwitches.h"
#include "harbour/machines/parts/OdeCableBodies.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/sim/Machine.h"
#include "harbour/sim/MachineSetup.h"

namespace harbour::sim {

const MachineType& mhc_machine_type();  ///< machines/mhc/Type.cpp

/// One point of the load-moment limiter's capacity chart: what may hang at a radius.
struct CapacityPoint {
  double radius_m = 0.0;
  double capacity_t = 0.0;
};

/// The hook block the MHC works general cargo with instead of its grab (the grab taken off, the holding and
/// closing ropes reeved to the block; settings): both winches hoist it together, and a slinger on the ground
/// slings a load onto it or off it when the operator asks (the `sling` button).
struct MhcHookSettings {
  cable::ReevingSettings hoist;  ///< bodies [house, boom, hook]; the holding drum, then the closing drum
  double block_mass_kg = 3500.0;
  core::Vec3 block_half_extents_m{0.5, 0.8, 0.9};
  double slinger_reach_m = 1.0;  ///< [m] the hook this near plumb over a load's centre can be slung to it
  double sling_length_m = 5.0;   ///< [m] the longest slings: the hook at most this far above the load's top
  /// [-] the slinger's tag lines and the slings' friction on the hook damp a slung load's rocking about the
  /// hook, as a share of its rocking mode's critical damping
  double tag_line_damping_ratio = 0.1;
  std::vector<CapacityPoint> capacity_chart{{12.0, 63.0}, {25.0, 50.0}, {48.0, 22.0}};
};

/// A mobile harbour crane with a 4-rope grab (settings, from data/machines/mhc.yaml). Frames: the machine's
/// frame has its origin on the slewing axis at quay level, z up; the house's frame has its origin there too
/// and turns with it (x towards the boom); the boom's frame has its origin at the boom head, x along the
/// boom (from foot to head). The reevings' bodies are [house, boom] (luffing) and [house, boom, grab_head,
/// grab_lower] (hoist), mounts given in those frames; grab bodies from their centres.
struct MhcSettings {
  // undercarriage on four outriggers (fixed to the quay while working)
  double undercarriage_mass_kg = 180e3;
  double pad_half_spread_x_m = 6.5;  ///< [m] outrigger pads at (+-x, +-y) in the machine's frame
  double pad_half_spread_y_m = 6.5;
  // slewing house: tower, machinery, counterweight, cab (a box about its centre of mass)
  double house_mass_kg = 190e3;
  core::Vec3 house_com_m{-2.5, 0.0, 9.0};  ///< [m] house frame
  core::Vec3 house_half_extents_m{5.0, 3.0, 6.0};
  DriveSettings slew_drive;  ///< in rad, rad/s, N m (position limits unused: it turns round)
  // boom, hinged at its foot, luffed by ropes
  double boom_mass_kg = 40e3;
  double boom_length_m = 48.0;             ///< [m] foot pivot to head sheaves
  double boom_half_width_m = 1.2;          ///< [m] box section for inertia and looks
  core::Vec3 boom_foot_m{2.0, 0.0, 14.0};  ///< [m] pivot, house frame
  double boom_min_angle_rad = 0.26;        ///< [rad] limit switches of the luffing
  double boom_max_angle_rad = 1.40;
  cable::ReevingSettings luffing;  ///< one drum: reeling in raises the boom
  // grab and its hoist: holding drum first, then closing drum
  cable::ReevingSettings hoist;
  double grab_head_mass_kg = 3000.0;
  double grab_lower_mass_kg = 12000.0;  ///< [kg] shells and their hinge block
  core::Vec3 grab_head_half_extents_m{1.0, 1.2, 0.6};
  core::Vec3 grab_lower_half_extents_m{1.6, 1.2, 0.8};  ///< shells' box when closed
  double grab_closed_gap_m = 1.6;  ///< [m] head centre to lower centre when the shells are shut
  double grab_open_gap_m = 3.4;    ///< [m] ... and when they are fully open
  bulk::GrabSettings grab;
  double hoist_upper_limit_m = 40.0;  ///< [m] grab head centre height the upper limit switch stops
  double hoist_lower_limit_m = -25.0;
  std::optional<MhcHookSettings> hook;  ///< a machine without one works only with its grab
  // load-moment limiter (the grab curve)
  std::vector<CapacityPoint> capacity_chart{{12.0, 64.0}, {30.0, 64.0}, {48.0, 40.0}};
  double limiter_slow_from = 0.9;  ///< [-] share of the chart above which moment-raising moves slow down
  double limiter_filter_s = 0.5;   ///< [s] time constant of the load signal's low-pass (rope bounce)
  // the cab on the tower
  core::Vec3 cab_position_m{1.5, -2.5, 24.0};  ///< [m] house frame
  core::Vec3 eye_m{0.3, 0.0, 0.6};             ///< [m] cab frame (x along the house's x)
  scene::CabSight sight{0.0, -0.35, 0.9};      ///< out along the boom and down to the grab
  scene::ControlTable controls;                ///< the cab's controls, by label (its machine file's)
};

/// Where the MHC stands and how it starts.
struct MhcStart {
  core::Vec3 position_m;      ///< [m] slewing axis at quay level
  double slew_rad = 0.0;      ///< house x from world x, about z
  double boom_rad = 0.8;      ///< boom angle above horizontal
  double hanging_z_m = 10.0;  ///< [m] centre height of the grab's head or the hook block
  bool on_hook = false;       ///< the hook block instead of the grab (MhcSettings::hook)
};

/// The vertical forces on the four outrigger pads [N] (pads in order (+x,+y), (-x,+y), (-x,-y), (+x,-y) of
/// the machine's frame), as a rigid undercarriage on four equal pad springs shares them.
using PadForces = std::array<double, 4>;

/// Shares a vertical load `down_n` and a moment `moment_nm` (about the machine's origin on the quay, world
/// frame, x and y used) onto pads at (+-a, +-b) rotated by `yaw_rad`: equilibrium plus the least-squares
/// (plane) share.
PadForces pad_forces(double down_n, const core::Vec3& moment_nm, double a_m, double b_m, double yaw_rad);

/// A mobile harbour crane on the physics world: the house slews on a hinge on the fixed undercarriage, the
/// boom luffs on a hinge at its foot held by the luffing ropes, the 4-rope grab hangs on its holding and
/// closing ropes (cable model); its shells open and shut as the closing ropes pull the lower block towards
/// the head against the holding ropes. On its hook (MhcStart::on_hook) the ropes carry the hook block and a
/// load slung to it hangs from the hook on a pivot (its slings).
class MobileHarbourCrane final : public Machine {
 public:
  MobileHarbourCrane(physics::PhysicsWorld& world, const MhcSettings& settings, const MhcStart& start);

  // Machine
  const MachineType& type() const override { return mhc_machine_type(); }
  const scene::ControlTable& control_table() const override { return settings_.controls; }
  void step(const scene::Controls& controls, std::span<const ContainerRef> liftables, double dt_s) override;
  std::optional<physics::BodyId> held_item() const override;
  double attachment_bottom_z_m() const override;
  double pendulum_length_m() const override;
  double lowering_speed_mps() const override;
  std::span<const WindArea> wind_areas() const override { return wind_areas_; }
  physics::BodyId cab_body() const override { return house_; }
  core::Vec3 eye_on_cab_body_m() const override;
  core::Pose cab_pose() const override;
  core::Vec3 eye_m() const override { return settings_.eye_m; }
  scene::CabSight cab_sight() const override { return settings_.sight; }
  void describe(scene::SceneDescription& scene) const override;
  int publish(scene::Snapshot& snapshot, int entities) const override;
  void drain_events(StepEvents& events) override;
  const BulkTool* bulk_tool() const override { return on_hook() ? nullptr : &tool_; }
  void carry_bulk(double mass_kg) override { carried_kg_ = mass_kg; }
  double carried_bulk_kg() const { return carried_kg_; }
  void inject_fault(MachineFault fault, int detail) override;
  void clear_faults() override { hoist_brake_fault_ = limiter_fault_ = false; }
  bool fault_active(MachineFault fault) const override {
    return (fault == MachineFault::kHoistBrake && hoist_brake_fault_) ||
           (fault == MachineFault::kLoadMomentLimiter && limiter_fault_);
  }
  void hash_into(core::StateHash& hash) const override;
  void save_state(core::StateWriter& out) const override;
  void restore_state(core::StateReader& in) override;

  /// Slew angle [rad], counted through full turns; boom angle above horizontal [rad].
  double slew_rad() const { return slew_; }
  const Drive& slew_drive() const { return slew_drive_; }
  double boom_angle_rad() const;
  /// Horizontal distance from the slewing axis to the boom head's sheaves [m].
  double radius_m() const;
  core::Vec3 boom_head_m() const;
  /// Where the hoist's falls leave the boom head's sheaves (their mean, horizontally; the highest): what the
  /// grab or hook hangs plumb under at rest [m].
  core::Vec3 suspension_point_m() const;
  /// What hangs on the ropes below the boom head [N, vertical] and the chart's capacity at this radius [t].
  double hoisted_load_n() const;
  double capacity_t() const;
  /// Load over capacity [-] (1: the chart's limit), from the limiter's filtered load signal.
  double utilisation() const;
  /// The limiter's load signal [N]: hoisted_load_n() low-passed over limiter_filter_s.
  double limiter_load_n() const { return limiter_load_n_; }
  std::uint32_t limiter_trips() const { return limiter_trips_; }
  /// Working on the hook block instead of the grab.
  bool on_hook() const { return settings_.hook && start_on_hook_; }
  /// Where the load hangs in the world [m]: the grab's lower block (its shells' hinge), or on the hook what
  /// is slung to it (the hook block when nothing is).
  core::Vec3 load_position_m() const;
  /// Slings refused since the start: the hook not over a load within the slinger's reach, or a slung load
  /// not yet resting when asked to unsling it.
  std::uint32_t slings_refused() const { return slings_refused_; }
  /// Shell opening [0 shut, 1 fully open].
  double grab_opening() const;
  /// Pad forces from the last physics step; lift-offs counted when a pad's force first goes below zero.
  PadForces pad_forces_n() const;
  std::uint32_t pad_lift_offs() const { return pad_lift_offs_; }
  MachineTally tally() const override;
  /// Lets the hanging load swing down to plumb and stops it there (the constructor's settling leaves it where
  /// it was built, some 0.2 m off), then settles the ropes again.
  void settle_at_rest() override;
  Telemetry telemetry() const override;
  /// Luffing rope reeled in per radian of boom raising [m/rad], and the boom head's radius rate at full
  /// luffing speed [m/s], from the falls' geometry now.
  double luffing_rope_per_rad() const;
  double luffing_radius_rate_mps() const;
  /// Tension in the luffing ropes' falls [N] (the first fall off the A-frame).
  double luffing_tension_n() const;
  const cable::HoistSystem& hoist() const { return *hoist_; }
  const cable::HoistSystem& luffing() const { return *luffing_; }
  physics::BodyId house_body() const { return house_; }
  physics::BodyId boom_body() const { return boom_; }
  /// The body hanging on the ropes under the boom head: the grab's head or the hook block.
  physics::BodyId block_body() const { return block_; }
  /// What is set down first: the hook block, or the grab's lower block (its shells' hinge).
  std::optional<physics::BodyId> gripper_body() const override { return on_hook() ? block_ : grab_lower_; }
  /// The grab's lower block (kWorld on the hook).
  physics::BodyId grab_lower_body() const { return grab_lower_; }
  physics::HingeId slew_hinge() const { return slew_hinge_; }
  physics::HingeId boom_hinge() const { return boom_hinge_; }
  const MhcSettings& settings() const { return settings_; }
  const core::Vec3& position_m() const { return position_; }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  double track_slew();
  /// Brings the machine to rest on its ropes before the exercise starts (kSettleSteps of the world).
  void settle();
  /// One step of the machine at rest: slewing ring, luffing and hoist drums braked.
  void step_braked(double dt_s);
  /// The bodies the settling moves and stops: house, boom, block and the grab's lower part on the grab.
  std::vector<physics::BodyId> settled_bodies() const;
  /// Stops the ropes' transverse motion (the settling stops the bodies with it).
  void stop_rope_waves();
  void update_tool();
  /// The slinger slings a load within reach under the hook, or takes a resting one off.
  void sling(std::span<const ContainerRef> liftables);
  /// The hoist's reeving: to the grab, or to the hook block.
  const cable::ReevingSettings& hoisting() const {
    return on_hook() ? settings_.hook->hoist : settings_.hoist;
  }
  /// Half extents of the body hanging on the ropes (grab head or hook block).
  const core::Vec3& block_half_extents_m() const;
  /// The vertical pull of the falls below the boom head [N], and the holding ropes' part of it.
  struct FallPulls {
    double holding_n = 0.0, total_n = 0.0;
    double holding_share() const { return total_n > 0.0 ? holding_n / total_n : 0.5; }
  };
  FallPulls fall_pulls() const;
  static constexpr int kSettleSteps = 4000;
  static constexpr int kPlumbSteps = 8000;   // the longest the load may take to swing down to plumb
  static constexpr double kPastPeak = 0.95;  // its swing's energy this far below its highest: past plumb
  physics::PhysicsWorld& world_;
  MhcSettings settings_;
  bool start_on_hook_;
  int slew_slot_, luff_slot_, hoist_slot_, grab_slot_, sling_slot_, stop_slot_, horn_slot_;
  core::Vec3 position_;
  physics::BodyId house_, boom_, block_, grab_lower_ = physics::kWorld;
  physics::HingeId slew_hinge_, boom_hinge_;
  physics::SliderId grab_slider_;
  Drive slew_drive_;
  LimitSwitches luff_limits_, hoist_limits_;
  LimitSwitches grab_limits_;  // on the shells' shut share: 0 fully open, 1 shut
  std::unique_ptr<OdeCableBodies> luffing_bodies_, hoist_bodies_;
  std::unique_ptr<cable::HoistSystem> luffing_, hoist_;
  std::vector<std::pair<int, int>> grab_falls_;  // (rope, segment) from the boom head down to the grab
  std::vector<bool> closing_rope_;               // per hoist rope: reeved through the shells' tackle
  struct LuffFall {
    int rope, segment;
    bool end_on_boom;  // the segment's far end (towards the dead end) rides on the boom
  };
  std::vector<LuffFall> luff_falls_;
  core::Vec3 house_origin_in_body_m_, boom_head_in_body_m_;
  double slew_ = 0.0, last_hinge_angle_ = 0.0;
  int tackle_falls_ = 1;  // closing-rope falls between the grab's head and its lower block, per rope
  double holding_falls_per_rope_ = 1.0;  // falls below the boom head per rope not through the shells' tackle
  double limiter_load_n_ = 0.0;
  bool horn_ = false, hoist_brake_fault_ = false, limiter_stopping_ = false, limiter_armed_ = true;
  bool limiter_fault_ = false;  // the limiter warns but no longer cuts moment-raising motions
  static constexpr std::uint8_t kHoistBrakeFaultBit = 1, kLimiterFaultBit = 2;
  std::uint8_t fault_mask() const;
  bool pad_lifted_ = false;
  std::uint32_t limiter_trips_ = 0, pad_lift_offs_ = 0;
  std::vector<WindArea> wind_areas_;
  std::array<core::Vec3, 9> shell_points_;  // contact points on the shells' underside, lower block frame
  BulkTool tool_;
  double carried_kg_ = 0.0;      // material in the grab: its weight hangs on the lower block
  double holding_share_ = 0.5;   // the holding ropes' share of the load, low-passed like the limiter's load
  double luff_speed_mps_ = 0.0;  // the boom head's radial speed the luffing winch was last commanded
  // on the hook: what is slung to it (its body, its pivot attachment), the sling button's last state
  physics::BodyId slung_ = physics::kWorld;
  physics::AttachmentId sling_attachment_;
  double rocking_damping_nms_ = 0.0;  // [N m s] on the slung load's rocking relative to the hook
  core::Vec3 slung_half_extents_m_;   // the slung load's shape (its slings are drawn to its corners)
  bool sling_pressed_ = false;
  std::uint32_t slings_refused_ = 0;
};

/// A mobile harbour crane and where it stands (settings).
struct MhcSetup {
  MhcSettings crane;
  MhcStart start;

  static const MachineType& type() { return mhc_machine_type(); }
  const scene::ControlTable& controls() const { return crane.controls; }
  std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const;
  std::vector<cable::ReevingSettings*> reevings();
  bool slings_cargo() const { return start.on_hook; }
};

}  // namespace harbour::sim
