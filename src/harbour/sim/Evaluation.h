#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "harbour/scene/RadioScript.h"
#include "harbour/sim/Simulation.h"

namespace harbour::sim {

/// One move to make: a container to a target position (e.g. a truck's chassis under the crane).
struct MoveGoal {
  std::string container_id;
  core::Vec3 target_m;                ///< [m] container centre when correctly set down
  double tolerance_m = 0.3;           ///< [m] horizontal distance from target still counted as done
  bool on_wheels = false;             ///< a trailer: its height is its wheels' business, not checked
  std::optional<double> heading_rad;  ///< the heading it is set down at (a box either way round), if checked
  double heading_tolerance_rad = 0.05;  ///< its skew still counted as done
  /// Onto the truck waiting under the crane: target_m is where the lane's stop puts it, and a team lane's
  /// truck stands where its tractor stopped (move_target).
  bool to_truck = false;
};

/// Where `goal`'s item is to be set down now: its target, or, for a move to the truck, the chassis of the
/// truck waiting under the crane (nullopt while none waits: a team's tractor still on its way).
std::optional<core::Vec3> move_target(const MoveGoal& goal, const Simulation& simulation);

/// Trigger values and per-occurrence deductions (points of 100); defined in docs/evaluation.md.
struct EvaluationRules {
  double time_limit_s = 600.0;
  double overtime_s = 600.0;  ///< [s] a run still unfinished this long after its time limit is stopped
  double pass_score = 70.0;
  double collision_speed_mps = 0.1;  ///< [m/s] impacts at least this fast that are not landings count
  /// [N s] a machine's body (a vehicle's chassis, a gantry's legs) meeting something with at least this
  /// impulse counts however slowly it closed: a heavy machine steering into a stack
  double body_contact_impulse_ns = 1000.0;
  double hard_landing_mps = 0.3;  ///< [m/s] landing a container faster than this is a hard landing
  double sway_limit_m = 0.25;  ///< [m] spreader offset from its rest position at a landing counted as swaying
  double horn_warning_s = 5.0;   ///< [s] gantry travel must start within this long after the horn sounded
  double gantry_travel_m = 1.0;  ///< [m] a gantry motion longer than this is a travel (needs the horn)
  /// [m/s] the load-handling attachment sinking faster than this over 0.1 s, its hoist lowering it that
  /// fast, is falling (no hoist drives it this fast: an emergency stop with the hoist brake failed lets the
  /// drum run free)
  double load_drop_mps = 4.0;
  double points_collision = 10.0;
  double points_hard_landing = 5.0;
  double points_sway = 2.0;
  double points_twistlock_misuse = 10.0;
  double points_overload = 15.0;
  double points_limit_hit = 2.0;
  double points_emergency_stop = 5.0;
  double points_unwarned_travel = 2.0;
  /// [s] a signaller's signal is to be followed at the controls within this long (2.5 s: the design
  /// perception-reaction time of AASHTO's Green Book for drivers; assumed for an operator watching a
  /// signaller)
  double signal_reaction_s = 2.5;
  double points_late_stop_signal = 10.0;  ///< a stop or emergency-stop signal not followed in time
  double points_load_drop = 30.0;
  double points_lift_under_fault = 20.0;  ///< lifting again with the hoist brake failed
  double points_per_move_missing = 20.0;
  double points_per_minute_over = 5.0;
  // bulk handling
  double poor_bite_fill = 0.4;    ///< [-] a bite filling less of the grab than this is a poor bite
  double harsh_jerk_mps3 = 10.0;  ///< [m/s^3] a slew or luff jerking harder than this is a harsh move
  double points_per_spilled_t = 2.0;
  double points_per_missing_t = 1.0;  ///< per tonne short of the delivery goal
  double points_poor_bite = 1.0;
  double points_limiter_trip = 5.0;
  double points_pad_lift_off = 20.0;
  double points_harsh_move = 1.0;
  double points_per_trim_dm = 2.0;  ///< per decimetre a trimmed pile still stands above its goal
  // vehicles
  double overspeed_margin_kmh = 1.0;  ///< [km/h] over a zone's limit by more than this is speeding
  double points_jackknife = 10.0;
  double points_tip_over = 50.0;
  double points_overspeed = 5.0;
};

/// A bulk delivery goal: this many tonnes dropped into a grid (a hopper).
struct BulkGoal {
  std::string grid;  ///< its name in the exercise's bulk section
  int grid_index = 0;
  double tonnes = 0.0;
};

/// A trim goal: a pile's top brought down to a height (the material moved onto its low parts).
struct TrimGoal {
  std::string grid;  ///< the pile's name in the exercise's bulk section
  int grid_index = 0;
  double top_m = 0.0;  ///< [m] world height its surface may reach at most
};

/// An area of the site with a speed limit for the vehicle (a ramp, a deck, a yard lane).
struct SpeedZone {
  std::string name;
  double min_x_m = 0.0, min_y_m = 0.0, max_x_m = 0.0, max_y_m = 0.0;  ///< [m] the area on the ground
  double limit_kmh = 10.0;
};

/// An exercise: a scenario, the moves to make and the rules that score them (settings).
/// Where a tractor waits under a team's crane for a box before its moves: its trailer's centre (ground) and
/// heading there.
struct LoadStop {
  core::Vec3 trailer_at_m;
  double heading_rad = 0.0;
};

/// What people read of an exercise in the console's lists and the designer (the simulation does not use it).
struct ExerciseAbout {
  std::string title;          ///< unique among a centre's exercises, as people pick it
  std::string objective;      ///< one sentence: what the trainee is to do
  std::string difficulty;     ///< beginner, intermediate or advanced
  double expected_min = 0.0;  ///< [min] how long a trained operator takes
};

struct ExerciseSettings {
  std::string name;
  std::optional<ExerciseAbout> about;  ///< unset: the file says nothing of itself
  ScenarioSettings scenario;
  std::string
      machine_file;  ///< the machine's data file it names (what the station reads its motion cues from)
  std::optional<LoadStop> load_stop;  ///< a team's tractor collects its box here first
  std::vector<MoveGoal> moves;
  std::vector<SpeedZone> speed_zones;
  /// [m] ground points a vehicle is to pass in order with its load, from where it picks it up to its
  /// target's line (a slalom's gates); empty: straight on
  std::vector<core::Vec3> route_m;
  std::optional<BulkGoal> deliver;
  std::optional<TrimGoal> trim;
  EvaluationRules rules;
  scene::RadioScript radio;  ///< the signaller's calls on the cab's radio
};

/// What a team session's member measured of the team (its station: station::NearMissWatch and the hand-offs).
struct TeamFigures {
  int near_misses = 0, contacts = 0;  ///< with the other members' machines
  double closest_m = -1.0;            ///< the closest any came [m] (-1: none measured)
  int hand_offs = 0;                  ///< boxes that changed owner, to or from this member, settled
  double worst_hand_off_ms = -1.0;    ///< [ms] the longest from offer to both sides agreeing (-1: none)
  double waited_s =
      -1.0;  ///< [s] a tractor standing at its load stop until its box was on (-1: it never did)
};

/// Everything measured during an attempt (docs/evaluation.md defines each).
struct Metrics {
  double time_s = 0.0;
  int moves_completed = 0;
  std::vector<double> cycle_times_s;  ///< per completed move
  double moves_per_hour = 0.0;
  int collisions = 0;
  double worst_collision_mps = 0.0;
  double collision_impulse_ns = 0.0;        ///< [N s] summed over the collisions
  double worst_collision_impulse_ns = 0.0;  ///< [N s]
  int container_collisions = 0;   ///< of them: carried box or spreader against another box or hatch cover
  int cell_guide_collisions = 0;  ///< spreader or box against a cell guide
  int ship_collisions = 0;        ///< against the hull or a coaming
  int vehicle_collisions = 0;     ///< against a truck, a vehicle or a trailer (not a stack)
  int other_collisions = 0;       ///< quay, ground
  int hard_landings = 0;
  double worst_landing_mps = 0.0;
  std::vector<double> landing_sway_m;  ///< at every landing (pick-up and set-down)
  int sway_landings = 0;
  int twistlock_misuse = 0;
  int overloads = 0;
  int limit_hits = 0;
  int emergency_stops = 0;
  int unwarned_gantry_travel = 0;  ///< gantry travel started without the horn first
  int load_drops = 0;              ///< onsets of the load (or the empty attachment) falling
  /// A hoist brake fault: in force during the attempt; lifts (a box taken, a bite closed on) while it was;
  /// the seconds from its onset to the load set down (-1: no load hung then); the machine stopped with its
  /// emergency stop once the load was down (the procedure: the attempt ends, the moves left are excused)
  bool hoist_fault = false;
  int lifts_under_fault = 0;
  double fault_set_down_s = -1.0;
  bool stopped_after_fault = false;
  /// Onsets of what the instructor did to the machine that the exercise does not script: a fault injected,
  /// the instructor's emergency stop, a power failure. An attempt they end with goals left is the
  /// instructor's doing, not the trainee's (Outcome::kEndedByInstructor).
  int instructor_disruptions = 0;
  double hoist_energy_j = 0.0;   ///< [J] mechanical work at the hoist drum (positive part)
  double travel_energy_j = 0.0;  ///< [J] mechanical work of the gantry and trolley drives (positive parts)
  // bulk handling (exercises with bulk material)
  bool bulk = false;
  double delivered_t = 0.0;       ///< [t] dropped into the goal's hopper
  double handled_t = 0.0;         ///< [t] discharged from the grab anywhere
  double spilled_t = 0.0;         ///< [t] lost outside every grid (into the water, onto the quay)
  double spilled_percent = 0.0;   ///< [%] of handled
  double tonnes_per_hour = 0.0;   ///< delivered over the time so far
  std::vector<double> bite_fill;  ///< per bite: the load the grab closed on over its capacity
  int poor_bites = 0;
  std::vector<double> release_swing_m;  ///< per discharge: the grab's swing as it opened
  int swinging_releases = 0;
  int limiter_trips = 0;
  int pad_lift_offs = 0;
  bool trim = false;        ///< a trim goal's pile is measured
  double pile_top_m = 0.0;  ///< [m] a trim goal's pile: its highest surface (measured every 0.5 s)
  /// Each completed move's placement: the item's horizontal offset from its target and, where the goal
  /// gives a heading, its skew from it.
  std::vector<double> placement_offset_m, placement_skew_deg;
  bool vehicle = false;  ///< a vehicle's figures are measured
  int jackknifes = 0;
  int tip_overs = 0;                 ///< the machine tipped over on its wheels (Machine::tally)
  int overspeeds = 0;                ///< onsets of speeding in a speed zone
  double worst_overspeed_kmh = 0.0;  ///< [km/h] the most over a zone's limit
  /// How smoothly each of the machine's named motions was driven (jerk from its speed sampled every 0.1 s).
  struct Smoothness {
    std::string axis;
    double rms_jerk_mps3 = 0.0;  ///< [m/s^3] over the samples while it moved
    int harsh_moves = 0;         ///< onsets of a jerk above rules.harsh_jerk_mps3
  };
  std::vector<Smoothness> smoothness;
  /// A signaller's hand signals: how many were given, the time from each to the operator's controls
  /// following it (rules.signal_reaction_s), those not followed in that time (or at all), and of them the
  /// stop and emergency-stop signals.
  int signals = 0;
  std::vector<double> signal_delays_s;
  int late_signals = 0;
  int late_stop_signals = 0;
  /// A team session's member: its team figures (measured by its station).
  std::optional<TeamFigures> team;
  /// The machine measured: of the figures that depend on a machine's parts, its type's `figures` are stored
  /// (nullptr: all of them).
  const MachineType* machine = nullptr;
  /// Every figure by name (the records store them as rows): those every machine's attempt has, the machine's
  /// own (MachineType::figures), and the bulk ones for a bulk exercise.
  std::vector<std::pair<std::string, double>> rows() const;
};

/// The skills a deduction counts against (docs/evaluation.md).
enum class Skill : std::uint8_t { kSafety, kPrecision, kProductivity };
const char* skill_name(Skill skill);

/// What an attempt's result says of the trainee.
enum class Outcome : std::uint8_t {
  kPassed,  ///< its goals met at the pass score (or a fault exercise's procedure followed at it)
  kFailed,
  /// The instructor ended it, or disrupted it (a fault, an emergency stop, a power failure the exercise
  /// does not script) and it ended with goals left: neither passed nor failed, and not counted as either.
  kEndedByInstructor,
};
const char* outcome_name(Outcome outcome);

/// The score: 100 minus deductions, with the reasons, and a sub-score per skill (100 minus that skill's
/// deductions, floor 0).
struct Score {
  double total = 100.0;
  bool passed = false;  ///< outcome == kPassed
  Outcome outcome = Outcome::kFailed;
  struct Deduction {
    std::string reason;
    int count = 0;
    double points = 0.0;
    Skill skill = Skill::kSafety;
  };
  std::vector<Deduction> deductions;
  std::array<double, 3> skills{100.0, 100.0, 100.0};  ///< indexed by Skill
};

/// Something the evaluator counted between two looks at the metrics (a collision, a hard landing, ...),
/// by the name the records and the console use, with its figure (the impact speed, the overspeed).
struct CountedEvent {
  const char* kind = "";
  double value = 0.0;
};
/// The kinds of counted events, in the order Progress keeps them.
inline constexpr std::size_t kCountedEventKinds = 18;
/// What the records store the moment it grows, at the time it happened: the completed moves (with the
/// newest cycle times) and every counted event with its figure. Plain and fixed-size: a station's step
/// thread hands it to the record keeper without allocating.
struct Progress {
  static constexpr std::size_t kRecentMoves = 4;
  double time_s = 0.0;
  int moves_completed = 0;
  std::array<double, kRecentMoves> recent_cycle_times_s{};  ///< of the newest moves, the newest last
  std::array<int, kCountedEventKinds> counts{};             ///< per kind (counted_event_kind)
  std::array<double, kCountedEventKinds> values{};          ///< the figure stored with each kind's event
  /// Something to store since `earlier`: a move done or an event counted.
  bool grew_since(const Progress& earlier) const {
    return moves_completed != earlier.moves_completed || counts != earlier.counts;
  }
};
/// The name the records and the console use for counted event kind `n`.
const char* counted_event_kind(std::size_t n);
Progress progress(const Metrics& metrics);
/// The score of `metrics` by `exercise`'s rules (what Evaluator::score gives); `goals_met` as it says;
/// `stopped_by_instructor`: the instructor ended the attempt before the exercise did.
Score score_of(const ExerciseSettings& exercise, const Metrics& metrics, bool goals_met,
               bool stopped_by_instructor = false);
/// The exercise scripts this fault itself (a fault exercise): its procedure is what is trained.
bool scripts_fault(const ExerciseSettings& exercise, MachineFault fault);
/// Room in every per-move, per-landing, per-bite and per-signal list of `metrics` for a long attempt (256 of
/// each), so that filling them, or copying a metrics into one with this room, allocates nothing.
void reserve_lists(Metrics& metrics);
/// Every event counted between `before` and `now`, one per count (moves are not events: see
/// Metrics::moves_completed).
std::vector<CountedEvent> counted_events(const Progress& before, const Progress& now);
std::vector<CountedEvent> counted_events(const Metrics& before, const Metrics& now);

/// The highest point of bulk grid `grid`'s surface, in the world [m].
double pile_top_m(const bulk::BulkWorld& bulk, int grid);

/// Watches an attempt step by step and measures it.
class Evaluator {
 public:
  explicit Evaluator(const ExerciseSettings& exercise);

  /// Call after every simulation step with the inputs that drove it.
  void observe(const Simulation& simulation, const scene::Controls& controls);
  /// All goals done (an exercise without goals, a free practice, runs to its time limit and overtime).
  bool finished() const;
  const Metrics& metrics() const { return metrics_; }
  /// `stopped_by_instructor`: the instructor ended the attempt before the exercise did.
  Score score(bool stopped_by_instructor = false) const;
  /// Every goal met (the moves, the tonnes delivered, the pile trimmed).
  bool goals_met() const;

 private:
  int hand_offs_pending_ = 0;  // boxes set on a team's trucks not yet taken over by their stations
  /// Impacts (landings, set-downs, collisions), moves, twistlock misuse, rope overloads, limit hits,
  /// emergency stops, the energy the drives delivered and gantry travel without the horn: the machine's
  /// tally says what it has of each.
  void observe_machine(const Simulation& simulation, const scene::Controls& controls,
                       const MachineTally& tally, bool emergency_stop);
  /// Gantry travel (people walk under the portal) starts only after a warning on the horn: one motion from
  /// standstill covering more than the rules' gantry_travel_m (positioning creeps are not travels).
  void observe_gantry_warning(bool horn, bool gantry_moving, double gantry_position_m);
  void observe_bulk(const Simulation& simulation, const MachineTally& tally);
  /// Counts a goal item let go of at its target as a completed move (`held`: what the machine holds now).
  void observe_moves(const Simulation& simulation, std::optional<physics::BodyId> held);
  void observe_smoothness(const Simulation& simulation, const MachineTally& tally);
  void observe_speed_zones(const Simulation& simulation);
  /// A falling load, and the hoist brake fault procedure: land the load under power, lift nothing more,
  /// then stop the machine (docs/evaluation.md).
  void observe_hoist_fault(const Simulation& simulation, bool emergency_stop);
  /// Onsets of an instructor's disruption the exercise does not script (Metrics::instructor_disruptions).
  void observe_instructor(const Simulation& simulation);
  /// The signaller's signals and how long the operator took to follow each at the controls.
  void observe_signals(const Simulation& simulation, const scene::Controls& controls);
  int goal_of(physics::BodyId body, const Simulation& simulation) const;
  double sway_m(const Simulation& simulation, std::optional<physics::BodyId> hanging_box) const;
  bool near_target(physics::BodyId box, const Simulation& simulation) const;
  void count_collision(const physics::ImpactEvent& e);
  void record_landing(const Simulation& simulation, std::optional<physics::BodyId> hanging_box);

  ExerciseSettings exercise_;
  Metrics metrics_;
  std::vector<bool> done_;
  std::optional<physics::BodyId> carried_;
  bool was_estop_ = false;
  bool gantry_was_moving_ = false, travel_warned_ = false, travel_counted_ = false;
  double travel_start_y_ = 0.0;
  double last_horn_s_ = -1e9;
  std::uint32_t limit_hits_seen_ = 0;
  double last_completion_s_ = 0.0;
  double bite_peak_m3_ = 0.0;  // the grab's load since it last closed on material
  bool discharging_ = false;
  struct AxisTrack {  // the last samples of one motion's speed and acceleration
    double speed_mps = 0.0, acceleration_mps2 = 0.0, jerk_squares = 0.0;
    int samples = 0, moving_samples = 0;
    bool harsh = false;
  };
  std::vector<AxisTrack> axes_;
  double next_axis_sample_s_ = 0.0;
  double next_pile_measure_s_ = 0.0;
  bool trimmed_ = false;  // the trim goal's pile measured down to its goal with the material placed
  bool speeding_ = false;
  double next_drop_sample_s_ = 0.0, drop_sample_z_m_ = 0.0;
  bool drop_primed_ = false, dropping_ = false;
  bool suspended_ = false;        // a load hung on the machine at the last step
  double fault_since_s_ = -1.0;   // when the hoist brake fault came with a load hanging
  bool stopping_safely_ = false;  // the brake failed with the load down: an emergency stop is the procedure
  bool disrupted_ = false;        // an instructor's disruption was in force at the last step
  int signals_seen_ = 0;          // Simulation::GivenSignal::count at the last step
  bool signal_pending_ = false;   // the latest signal not yet followed
  bool signal_late_ = false;      // ... and already counted late
};

}  // namespace harbour::sim
