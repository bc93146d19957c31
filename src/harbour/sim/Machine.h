#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "harbour/bulk/Grab.h"
#include "harbour/cable/HoistSystem.h"
#include "harbour/core/StateArchive.h"
#include "harbour/core/StateHash.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/scene/Controls.h"
#include "harbour/scene/Snapshot.h"
#include "harbour/sim/Ground.h"
#include "harbour/sim/MachineType.h"
#include "harbour/sim/TwistlockEvent.h"

namespace harbour::sim {

/// Something a machine may land on and lift (a container, a hatch cover): its body, its shape's half extents
/// (body frame, x along its length) and where its corner castings or lifting pockets are. The world owns
/// them; the machine is handed them each step.
struct ContainerRef {
  physics::BodyId body = physics::kWorld;
  core::Vec3 half_extents_m;
  double pocket_half_length_m = 0.0, pocket_half_width_m = 0.0;  ///< [m] casting centres from its centre
  double end_pocket_half_length_m = 0.0;                         ///< [m] a 45 ft box's end castings (0: none)
};

/// What happened during the last step, for evaluation and the instructor (buffers reused step to step).
struct StepEvents {
  std::vector<physics::ImpactEvent> impacts;
  std::vector<TwistlockEvent> twistlocks;
  std::vector<cable::CableEvent> ropes;
};

/// A body of the machine the wind pushes on, as a box (drag by face, see Weather.h).
struct WindArea {
  physics::BodyId body = physics::kWorld;
  core::Vec3 half_extents_m;
  bool swings = false;  ///< hangs from the ropes or the boom head: the wind leans it out (a load's rest)
};

/// A tool that works bulk material (a grab), as the machine leaves it after its step: the body its contact
/// points ride on, where its jaw tips are and how far its shells are open.
struct BulkTool {
  physics::BodyId body = physics::kWorld;
  std::span<const core::Vec3> contact_points_m;  ///< [m] on `body`, its frame: pressed into the material
  bulk::GrabSettings grab;                       ///< jaw width, opening, capacity, bite and spill figures
  core::Pose jaws;                               ///< jaw-tip centre: x across the jaws, y along the hinge
  core::Vec3 jaws_velocity_mps;
  double opening_m = 0.0;  ///< [m] between the jaw tips now
};

/// The speed a machine's drive is commanded along one of its named motions (after its ramps), for the
/// evaluation of how smoothly it is driven.
struct AxisSpeed {
  const char* name = nullptr;  ///< e.g. "slew"; nullptr: unused
  double speed_mps = 0.0;      ///< [m/s] a slew as the speed its boom head travels round
};

/// What a machine's safety systems counted since the start, how its hanging load swings and how fast its
/// motions are driven now: the evaluation reads it without knowing the machine (what a machine lacks stays
/// zero).
struct MachineTally {
  std::uint32_t limiter_trips = 0;  ///< load-moment limiter stops
  std::uint32_t pad_lift_offs = 0;  ///< outrigger pads lifting off
  std::uint32_t limit_hits = 0;     ///< motions driven into their end limit switches
  core::Vec3 swing_m;               ///< [m] the hanging tool's horizontal offset from plumb under its sheaves
  std::array<AxisSpeed, 3> axes{};  ///< the motions an operator drives smoothly or not
  double hoist_power_w = 0.0;       ///< [W] what its hoist drums' motors deliver now (lowering ones: 0)
  double travel_power_w = 0.0;  ///< [W] what its travel drives (gantry, trolley, wheels) deliver (braking: 0)
  /// A gantry crane sounds its horn before it travels: whether its gantry is driven now and where it is
  /// along its track [m].
  bool warns_before_travel = false;
  bool travelling = false;
  double travel_position_m = 0.0;
  bool vehicle = false;          ///< driven about the site (its jack-knives and speeding are measured)
  std::uint32_t jackknifes = 0;  ///< a towed trailer folded past its hitch angle limit
  std::uint32_t tip_overs = 0;   ///< the machine tipped over on its wheels
};

/// What the instructor's telemetry plots of any machine, whichever it is: how its load hangs, what its
/// ropes carry and how fast its motions go (what a machine lacks stays zero).
struct Telemetry {
  double swing_m = 0.0;             ///< [m] the hanging load's (or tool's) horizontal offset from plumb
  double rope_tension_n = 0.0;      ///< [N] the highest tension in its hoist's ropes
  std::array<AxisSpeed, 3> axes{};  ///< its motions' speeds, named
};

/// A fault the instructor injects into a machine.
enum class MachineFault : std::uint8_t {
  kHoistBrake,         ///< the hoist's holding brake does not set
  kLandedSensor,       ///< one twistlock corner's landed sensor reads "not landed" (detail: the corner, 0-3)
  kLoadMomentLimiter,  ///< the load-moment limiter no longer stops moment-raising motions (it still warns)
};

/// One machine on the executive: what the simulation, the recorder, the station and the image generator need
/// of it without knowing which machine it is. The world (quay, vessel, cargo, bulk, weather, trucks) stays
/// outside; the machine pushes on the physics world's bodies in step() and the executive then steps it.
class Machine {
 public:
  virtual ~Machine() = default;

  /// What kind of machine it is: its kind as files name it, what it handles, the faults it has.
  virtual const MachineType& type() const = 0;
  /// Its kind as exercise and machine files name it ("sts", "mhc").
  const char* kind() const { return type().kind; }
  /// Its controls, by label (Controls carry one value per slot of this table).
  virtual const scene::ControlTable& control_table() const = 0;
  /// Drives, ropes and tools for one step with these controls (any values: the machine reads them in range);
  /// `liftables` are the items it may pick up.
  virtual void step(const scene::Controls& controls, std::span<const ContainerRef> liftables,
                    double dt_s) = 0;

  /// The item it holds (a container locked to its spreader), if any.
  virtual std::optional<physics::BodyId> held_item() const = 0;
  /// The body that takes hold of items (a spreader), if it has one: setting it down on the item it is to
  /// pick up is a landing, not a collision.
  virtual std::optional<physics::BodyId> gripper_body() const { return std::nullopt; }
  /// The ground its wheels stand on from now on (the world's; it outlives the machine). Machines on rails or
  /// outriggers ignore it.
  virtual void stand_on(const Ground&) {}
  /// Items the machine brings with it, by the exercise's names (a tractor's trailer); goals may name them.
  virtual std::vector<std::pair<std::string, physics::BodyId>> own_items() const { return {}; }
  /// Height of the lowest point of its load-handling attachment (spreader, grab, hook) [m].
  virtual double attachment_bottom_z_m() const = 0;
  /// Length of the pendulum its load hangs on [m] (0 when nothing hangs).
  virtual double pendulum_length_m() const = 0;
  /// How fast its hoist lowers its load-handling attachment now [m/s], positive down: on ropes, the rope its
  /// holding drum pays out over the falls (a swing or a bounce on the ropes does not turn the drum; a drum
  /// running free does); on a rigid boom, the attachment's sinking against the chassis. 0 with none.
  virtual double lowering_speed_mps() const = 0;
  /// Its bodies the wind pushes on (a carried item is the executive's to add).
  virtual std::span<const WindArea> wind_areas() const = 0;

  /// The operator's cab: the body it rides on, the design eye point on that body, the cab's frame in the
  /// world and the eye point in the cab's frame (x the way the operator faces, z up).
  virtual physics::BodyId cab_body() const = 0;
  virtual core::Vec3 eye_on_cab_body_m() const = 0;
  virtual core::Pose cab_pose() const = 0;
  virtual core::Vec3 eye_m() const = 0;
  /// The operator's design view from the cab (line of sight and field of view).
  virtual scene::CabSight cab_sight() const = 0;

  /// Appends its entities (first in the scene), names its indicators and counts its ropes.
  virtual void describe(scene::SceneDescription& scene) const = 0;
  /// Writes its entities' poses from `entities` on (in describe()'s order; returns how many), its ropes and
  /// its indicators. Allocates nothing.
  virtual int publish(scene::Snapshot& snapshot, int entities) const = 0;
  /// Its tool for bulk material, if it has one (updated by step()).
  virtual const BulkTool* bulk_tool() const { return nullptr; }
  /// The material its tool holds [kg] (its weight hangs on the tool until the next call).
  virtual void carry_bulk(double /*mass_kg*/) {}
  /// Why it cannot take a box handed over by a team's crane ("" when it can): a trailer that receives one.
  virtual std::string why_no_load() const {
    return std::string("the ") + kind() + " takes no load handed over";
  }
  /// A box of `mass_kg` handed over onto it (a team's crane set it down): `on_trailer` its centre in its
  /// trailer's frame. Only where why_no_load() is "".
  virtual void take_load(const core::Pose& /*on_trailer*/, double /*mass_kg*/) {}
  /// The box handed over onto it, if one has been (its body).
  virtual std::optional<physics::BodyId> load() const { return std::nullopt; }
  /// What its safety systems counted since the start and how its load swings now (for the evaluation).
  virtual MachineTally tally() const { return {}; }
  /// Before the first step: its hoist ropes stretched under what hangs on them, at rest (built unstretched).
  virtual void settle_ropes() {}
  /// Brings the machine to rest in its static equilibrium (ropes, joints, the load plumb) before the first
  /// step, where it would otherwise start away from it (a gantry crane on its joints' compliance).
  virtual void settle_at_rest() {}
  /// Its telemetry now; by default what its tally says (the swing, the motions) and no ropes.
  virtual Telemetry telemetry() const;
  /// Moves this step's events (twistlocks, ropes) into `events`.
  virtual void drain_events(StepEvents& events) = 0;

  /// Whether it has the part this fault breaks (its type's faults); inject_fault() is called only for those.
  bool has_fault(MachineFault fault) const { return type().has_fault(fault); }
  virtual void inject_fault(MachineFault fault, int detail) = 0;
  virtual void clear_faults() = 0;
  /// Whether `fault` is in force now (its lamp in the cab is lit: the machines monitor their brakes).
  virtual bool fault_active(MachineFault fault) const = 0;

  /// Its dynamic state beyond the physics world's bodies (drives, ropes, latches, faults).
  virtual void hash_into(core::StateHash& hash) const = 0;
  virtual void save_state(core::StateWriter& out) const = 0;
  virtual void restore_state(core::StateReader& in) = 0;
};

/// Appends `hoist`'s ropes to the snapshot's rope polylines (after those already there; what does not fit in
/// kMaxRopes ropes or kMaxRopePoints points is left out).
void publish_ropes(const cable::HoistSystem& hoist, scene::Snapshot& snapshot);
/// Appends one polyline (a sling) to the snapshot's ropes; with no points it draws nothing but keeps its
/// place among them.
void publish_polyline(std::span<const core::Vec3> points, scene::Snapshot& snapshot);

}  // namespace harbour::sim
