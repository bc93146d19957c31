#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "harbour/bulk/BulkScene.h"
#include "harbour/core/FixedStepClock.h"
#include "harbour/core/Units.h"
#include "harbour/core/Warnings.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/scene/Controls.h"
#include "harbour/scene/Snapshot.h"
#include "harbour/sim/MachineSetup.h"
#include "harbour/sim/RoRoRamp.h"
#include "harbour/sim/TeamInput.h"
#include "harbour/sim/TeamObstacles.h"
#include "harbour/sim/Trucks.h"
#include "harbour/sim/Vessel.h"
#include "harbour/sim/Weather.h"
#include "harbour/sim/YardBlock.h"

namespace harbour::sim {

/// A container (ISO 668 sizes), a hatch cover or a general cargo piece placed in the scenario: anything a
/// spreader or a hook lifts.
struct ContainerPlacement {
  enum class Kind : std::uint8_t { kContainer, kHatchCover, kGeneralCargo };
  std::string id;
  Kind kind = Kind::kContainer;
  core::Vec3 half_extents_m;    ///< [m] x along its length
  double gross_mass_kg = 0.0;   ///< [kg] tare + cargo
  core::Pose pose;              ///< centre, world
  core::Vec3 center_of_mass_m;  ///< [m] from its centre, its frame (unevenly stowed cargo)
  double pocket_half_length_m = 0.0, pocket_half_width_m = 0.0;  ///< [m] corner castings / lifting pockets
  double end_pocket_half_length_m = 0.0;                         ///< [m] a 45 ft box's end castings (0: none)
  bool on_vessel = false;  ///< stowed on the vessel (moves with it while secured)
  bool in_cell = false;    ///< stowed in a hold cell (between cell guides)
};

/// A static block the containers stand on (vessel deck, hatch cover, quay furniture).
struct StaticBlock {
  core::Vec3 half_extents_m;
  core::Vec3 position_m;
};

/// A bay painted on the ground (a trailer's parking place): a rectangle about its centre, long along its
/// heading; it lies on whatever ground is there (the quay, a vessel's deck).
struct GroundMarking {
  std::string name;
  core::Vec3 centre_m;  ///< [m] x and y; z is the ground's
  double heading_rad = 0.0;
  double half_length_m = 1.0, half_width_m = 1.0;
};

/// Something the exercise makes happen at a time (a gust, a fault).
struct ScriptedEvent {
  enum class Kind { kGust, kHoistBrakeFault, kLandedSensorFault, kLimiterFault };
  Kind kind = Kind::kGust;
  double at_s = 0.0;  ///< [s] exercise time (for ScenarioSettings::lift_events: since the first lift)
  Gust gust;          ///< kGust (it starts at at_s)
  int corner = 0;     ///< kLandedSensorFault: which twistlock corner (0-3)
};

/// A command from the instructor to a running exercise, applied before the next step (the console sends
/// them; recordings keep them with their step so a replay applies them again).
struct InstructorCommand {
  enum class Kind : std::uint8_t {
    kGust,               ///< a 1-cosine gust starting now (gust)
    kHoistBrakeFault,    ///< the hoist's holding brake stops setting
    kLandedSensorFault,  ///< one corner's landed sensor reads "not landed" (corner)
    kClearFaults,        ///< every fault repaired
    kSetWind,            ///< mean wind, direction and turbulence (wind_mean_mps, wind_from_rad, turbulence)
    kSetVisibility,      ///< [m] (value)
    kSetRain,            ///< [mm/h] (value)
    kSetTimeOfDay,       ///< [h] (value): the clock jumps there and runs on
    kLimiterFault,       ///< the load-moment limiter stops nothing (it still warns)
    kEmergencyStop,      ///< the instructor stops the machine: its emergency stop held pressed until released
    kReleaseEmergencyStop,
    kPowerFailure,  ///< the machine's supply fails: every drive dead, every brake set (as its emergency stop)
    kPowerRestored,  ///< the supply is back: the drives start once every lever has been back at zero
    kSignal,    ///< a signaller's hand signal to the operator (value: its index in scene::hand_signals())
    kSetCloud,  ///< [oktas] (value): eighths of the sky under cloud
  };
  static constexpr std::uint8_t kKinds = 15;
  Kind kind = Kind::kGust;
  Gust gust;  ///< kGust: duration and amplitude (its start is now)
  int corner = 0;
  double value = 0.0;
  double wind_mean_mps = 0.0, wind_from_rad = 0.0, turbulence = 0.0;
  friend bool operator==(const InstructorCommand&, const InstructorCommand&) = default;
};

/// The ranges of an instructor command's values (why_invalid keeps them; the command table shows them).
inline constexpr double kMaxGustDuration_s = 600.0;
inline constexpr double kMaxVisibility_m = 1e5;
inline constexpr double kMaxRain_mm_per_h = 500.0;
inline constexpr double kHoursPerDay = 24.0;
inline constexpr int kTwistlockCorners = 4;

/// Why a command's values are out of range ("" when they are not).
std::string why_invalid(const InstructorCommand& command);

/// The initial state of an exercise world (settings).
struct ScenarioSettings {
  std::string name;
  MachineSetup machine;  ///< the machine, as its file and the exercise set it up (none: nothing to build)
  std::vector<StaticBlock> blocks;
  /// The quay's waterside edge [m]: with a vessel the quay is a block up to it and the harbour bed lies
  /// below the water; without one the ground is a plane at the quay's level.
  double quay_edge_x_m = 18.0;
  std::optional<VesselPlacement> vessel;
  std::optional<RampSettings> ramp;  ///< a ro-ro vessel's stern ramp and deck, the ground vehicles drive on
  std::vector<GroundMarking> markings;
  TruckLaneSettings trucks;
  std::optional<YardBlock> yard_block;  ///< a container block's ground slots (bay, row, tier)
  std::vector<ContainerPlacement> containers;
  WeatherSettings weather;
  std::vector<ScriptedEvent> events;  ///< in time order
  /// Events timed from the machine's first lift (the step it first holds an item), in time order: a fault
  /// that is to come with a load hanging, however long the trainee took to pick it up.
  std::vector<ScriptedEvent> lift_events;
  std::optional<bulk::BulkScene> bulk;  ///< bulk material: piles, hoppers, holds
  double drag_coefficient =
      1.0;                 ///< [-] boxes and spreader (published 0.6-1.2 by face and stacking; assumed)
  std::uint64_t seed = 1;  ///< seeds the turbulence
  /// The hoist ropes start unstretched, the load dropping onto them (as every run before recording version
  /// 8 started: their replays start so); otherwise stretched under it, at rest.
  bool ropes_start_unstretched = false;
  /// The ropes stretch along their chords (cable::ReevingSettings::stretch_along_chord), as in every run
  /// recorded before the curved length counted: their replays run so.
  bool ropes_stretch_along_chord = false;
  /// The machine's end stops sit at its drives' travel limits (MachineSetup::end_stops_at_travel: a reach
  /// stacker's telescope), as in every run recorded before they cleared it:
  /// their replays run so.
  bool end_stops_at_travel = false;
  /// The machine starts as built, not brought to rest first (Machine::settle_at_rest), as in every run
  /// recorded before it was: their replays start so.
  bool start_unsettled = false;
  /// The ropes' transverse damping acts against the ground (cable::ReevingSettings::damping_against_ground),
  /// as in every run recorded before it acted between the rope and its ends: their replays run so.
  bool rope_damping_against_ground = false;
  /// No bending hysteresis where the ropes turn on sheaves and drums
  /// (cable::ReevingSettings::sheaves_without_bending_loss), as in every run recorded before it was
  /// modelled: their replays run so.
  bool sheaves_without_bending_loss = false;
  /// The sheaves, the ropes' strain rate and overloads as before recording header flag bit 7
  /// (cable::ReevingSettings::simple_sheaves): the replays of runs recorded without it run so.
  bool simple_sheaves = false;
  /// A slack rope straightens to its chord (cable::ReevingSettings::slack_ropes_straighten), as in every run
  /// recorded without recording header flag bit 8: their replays run so.
  bool slack_ropes_straighten = false;
  /// The state hash takes the machine's hand-picked figures (Machine::hash_into), as in every run recorded
  /// before it took everything the machine saves: their replays check their hashes so.
  bool machine_hashed_by_hand = false;
};

/// The executive: a pure function of its inputs at a fixed 1 kHz step (no clocks, files or threads). The
/// instructor's freeze is hold()/resume()/single_step().
class Simulation {
 public:
  static constexpr double kStep_s = 0.001;

  explicit Simulation(const ScenarioSettings& scenario);

  /// One physics step with these controls (read through the machine's control table); does nothing while
  /// held. Never throws; allocates nothing once warmed up.
  void step(const scene::Controls& controls);
  void hold() { held_ = true; }
  void resume() { held_ = false; }
  bool held() const { return held_; }
  /// One step even while held (the instructor steps a frozen exercise).
  void single_step(const scene::Controls& controls);
  /// Why `command` would be refused ("" when it would not): values out of range, or a fault of a part this
  /// machine lacks. Reads only what a machine has, not its state (any thread).
  std::string why_refused(const InstructorCommand& command) const;
  /// Applies an instructor's command now (before the next step); throws std::invalid_argument when
  /// why_refused says why (a corner other than 0-3, a negative visibility, a part the machine lacks),
  /// changing nothing.
  void command(const InstructorCommand& command);
  /// Why `input` from a team session's other stations would be refused ("" when it would not): values out of
  /// range, a truck this scene has no team lane for, a box that is not on that truck, a load this machine
  /// cannot take. Reads only what the scene has and the state of its team trucks and load.
  std::string why_refused(const TeamInput& input) const;
  /// Applies a team input now (before the next step); throws std::invalid_argument when why_refused says why,
  /// changing nothing.
  void team_input(const TeamInput& input);
  /// The machine's supply has failed (kPowerFailure): its drives read the emergency stop pressed.
  bool power_off() const { return power_off_; }
  /// The instructor holds the machine's emergency stop pressed (kEmergencyStop).
  bool instructor_stopped() const { return instructor_stop_; }
  /// The signaller's latest hand signal: its index in scene::hand_signals() and when it was given (it moves
  /// nothing; the operator sees and hears it and the evaluator times the answer at the controls).
  struct GivenSignal {
    int signal = -1;  ///< -1: none yet
    double at_s = 0.0;
    int count = 0;  ///< signals given so far
  };
  const GivenSignal& signal() const { return signal_; }
  /// The supply is back but a lever has not been at zero since: the drives stay off until every axis control
  /// reads within kLeverZeroBand of its neutral (zero-voltage protection).
  bool awaiting_zero() const { return awaiting_zero_; }
  /// How near its neutral an axis counts as at zero, as a share of its half range.
  static constexpr double kLeverZeroBand = 0.05;

  std::int64_t steps() const { return clock_.steps(); }
  double time_s() const { return clock_.time_s(); }
  /// The machine's controls, by label.
  const scene::ControlTable& control_table() const { return machine_->control_table(); }
  /// What is in the scene (fixed for this simulation): entities and indicator names, by snapshot index.
  scene::SceneDescription scene() const;
  /// Writes the published state into `out` without allocating.
  void write_snapshot(scene::Snapshot& out) const;
  /// The published state (allocated: tests and tools; a station writes into its buffers).
  std::unique_ptr<scene::Snapshot> snapshot() const;
  /// Hash of the whole dynamic state: bodies, ropes, drives, twistlocks, clock.
  std::uint64_t state_hash() const;
  /// The whole dynamic state as bytes (a keyframe). Restoring it into a Simulation built from the same
  /// scenario continues bit for bit; a state from another scenario throws core::StateError.
  std::vector<std::uint8_t> save_state() const;
  void restore_state(const std::vector<std::uint8_t>& state);
  const core::Warnings& warnings() const { return warnings_; }
  /// The physics diverged (a non-finite or runaway state, counted as a kNonFinite warning): the simulation
  /// stopped there and steps no more; divergence() says where.
  bool diverged() const { return world_->diverged(); }
  const std::string& divergence() const { return world_->divergence(); }
  /// Events of the last step.
  const StepEvents& events() const { return events_; }
  /// Body of scenario container `index`.
  physics::BodyId container_body(std::size_t index) const { return containers_[index].body; }
  const physics::PhysicsWorld& world() const { return *world_; }
  const Weather& weather() const { return weather_; }
  /// The scene's bulk material, if it has any, and the machine's tool in it (-1: none).
  const bulk::BulkWorld* bulk() const { return bulk_.get(); }
  int bulk_grab() const { return bulk_grab_; }
  /// The machine carries a load: it holds an item (a locked box, a slung piece), or its grab holds material.
  /// The first lift (events timed `after_lift_s`) is when it first does.
  bool carrying() const;
  /// Where the machine's load would hang at rest in a steady `wind` [m/s], from plumb under its sheaves [m]
  /// (horizontal): the pendulum's equilibrium L F / (m g), F the wind's drag on the areas that swing and on
  /// `box` if it hangs from them.
  core::Vec3 wind_rest_offset_m(const core::Vec3& wind, std::optional<physics::BodyId> box) const;
  const Vessel* vessel() const { return vessel_.get(); }
  const TruckLane* trucks() const { return trucks_.get(); }
  const TeamObstacles& obstacles() const { return *obstacles_; }
  /// Frees secured item `index` and what is stacked on it (the spreader locking onto it does this).
  void release(std::size_t index);
  bool secured(std::size_t index) const { return secured_[index]; }
  /// Everything the spreader can lift (containers, then hatch covers), in scenario order.
  std::span<const ContainerRef> liftables() const { return containers_; }
  Machine& machine() { return *machine_; }
  const Machine& machine() const { return *machine_; }
  /// The machine as a `MachineT` (tests and tools that know which it is); throws std::logic_error naming
  /// its kind when it is another.
  template <typename MachineT>
  const MachineT& machine_as() const {
    if (const auto* machine = dynamic_cast<const MachineT*>(machine_.get())) return *machine;
    throw std::logic_error(std::string("the simulation's machine is an ") + machine_->kind() +
                           ", not the machine asked for");
  }
  template <typename MachineT>
  MachineT& machine_as() {
    return const_cast<MachineT&>(std::as_const(*this).template machine_as<MachineT>());
  }
  const ScenarioSettings& scenario() const { return scenario_; }

 private:
  void advance(const scene::Controls& controls);
  void update_cab_cues();
  void move_secured_cargo();
  void apply_due_events();
  void apply_event(const ScriptedEvent& event, double at_s);
  void apply_wind();
  void step_bulk();
  bulk::CarrierMotion vessel_motion() const;
  const ContainerRef* liftable(physics::BodyId body) const;

  ScenarioSettings scenario_;
  core::FixedStepClock clock_{kStep_s};
  std::unique_ptr<physics::PhysicsWorld> world_;
  std::unique_ptr<Machine> machine_;
  std::vector<ContainerRef> containers_;
  /// Cargo at rest is secured (deck boxes twistlocked to the hatch covers and to each other, hold boxes in
  /// their cells, hatch covers cleated, quay boxes on the ground): kinematic, carried with the vessel, no
  /// contacts to solve. The spreader locking onto a box releases it and everything stacked on it.
  std::vector<bool> secured_;
  std::vector<core::Pose> stowed_;  // secured pose in the vessel frame (on the vessel) or the world
  Weather weather_;
  std::unique_ptr<Vessel> vessel_;
  std::unique_ptr<RoRoRamp> ramp_;
  std::unique_ptr<TruckLane> trucks_;
  std::unique_ptr<TeamObstacles> obstacles_;  // the other members' machines (none outside a team session)
  std::unique_ptr<bulk::BulkWorld> bulk_;
  int bulk_grab_ = -1;  // the machine's tool in the bulk world
  std::size_t next_event_ = 0;
  std::int64_t first_lift_step_ = -1;  // the step the machine first held an item (with lift events only)
  std::size_t next_lift_event_ = 0;
  bool held_ = false;
  bool instructor_stop_ = false;  // the instructor holds the machine's emergency stop pressed
  GivenSignal signal_;  // not state: it changes nothing simulated (a restored run shows none until the next)
  bool power_off_ = false;       // the supply has failed
  bool roped_ = false;           // the machine hangs its load on ropes (it publishes their telemetry)
  bool awaiting_zero_ = false;   // restored, but no lever has been at zero since
  bool emergency_stop_ = false;  // the machine's stop was in force at the last step (published, not state)
  bool levers_at_zero(const scene::Controls& controls) const;
  core::Warnings warnings_;
  StepEvents events_;
  // the latest impacts as the snapshot publishes them (output, not state)
  std::array<scene::Snapshot::Knock, scene::kMaxKnocks> knocks_{};
  std::int64_t knocks_total_ = 0;
  core::Vec3 cab_velocity_, cab_specific_force_{0.0, 0.0, core::kStandardGravity};  // world
};

}  // namespace harbour::sim
