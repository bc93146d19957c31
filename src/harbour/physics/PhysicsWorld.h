#pragma once

#include <array>
#include <cstdarg>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "harbour/core/StateArchive.h"
#include "harbour/core/Units.h"
#include "harbour/core/Vec3.h"

namespace harbour::physics {

/// The index of one kind of thing a PhysicsWorld hands out (a rigid body, a body's collision shape, a slider,
/// a hinge, an attachment): a type of its own per kind, so a hinge's cannot be passed where a slider's is
/// meant, nor a body where a number is. -1: none (for a body, the fixed world). Its bytes are its index's
/// (saved states hold it as they held the index).
template <typename Kind>
struct Handle {
  int index = -1;
  constexpr bool valid() const { return index >= 0; }
  friend constexpr bool operator==(Handle, Handle) = default;
  friend constexpr auto operator<=>(Handle, Handle) = default;
};
using BodyId = Handle<struct BodyKind>;
inline constexpr BodyId kWorld{};
using ShapeId = Handle<struct ShapeKind>;
using SliderId = Handle<struct SliderKind>;
using HingeId = Handle<struct HingeKind>;
using AttachmentId = Handle<struct AttachmentKind>;

/// Settings of the multibody world (ODE).
struct WorldSettings {
  core::Vec3 gravity{0, 0, -core::kStandardGravity};  ///< [m/s^2]
  double erp = 0.2;                                   ///< [-] joint error reduction per step
  double cfm = 1e-9;                                  ///< [-] constraint force mixing (softness)
  double contact_friction = 0.6;  ///< [-] Coulomb friction coefficient (steel on steel, dry: assumed)
  double contact_erp = 0.2;       ///< [-]
  double contact_cfm = 1e-7;      ///< [-]
  double contact_max_correcting_mps = 0.1;  ///< [m/s] penetration is resolved no faster (no popping bounces)
  double contact_surface_layer_m = 0.001;   ///< [m] allowed resting penetration (stable stacking)
  int max_contacts_per_pair = 8;
  double impact_rearm_s = 1.0;  ///< [s] a pair must have been apart this long for a new contact to be an
                                ///< impact (a box landing one end first, then the other, is one landing)
};

/// The first contact of two bodies (or a body and static geometry: other = kWorld) after being apart for a
/// while, reported kImpulseWindowSteps after it began, with the impulse of that window.
struct ImpactEvent {
  BodyId body = kWorld;
  BodyId other = kWorld;
  int surface = 0, other_surface = 0;  ///< the touching geometries' surface tags (the caller's categories)
  double normal_speed_mps = 0.0;       ///< [m/s] closing speed along the contact normal
  double impulse_ns = 0.0;  ///< [N s] normal contact impulse over the impact window (the first steps)
  core::Vec3 point;         ///< [m] world
};

/// A box body (settings).
struct BoxSettings {
  core::Vec3 half_extents_m{0.5, 0.5, 0.5};  ///< [m]
  double mass_kg = 1.0;                      ///< [kg] uniform density
  core::Pose pose;                           ///< initial pose in the world
  bool collides = true;                      ///< has a collision geometry
  int surface = 0;                           ///< tag reported with its impacts
  core::Vec3 center_of_mass_m;  ///< [m] box frame: off-centre gravity (a container's uneven cargo)
  bool kinematic = false;       ///< starts moved by the caller (secured cargo) until set_kinematic(false)
};

/// Thin adapter over ODE 0.16 (double precision): bodies, joints, contacts, forces at points, and a
/// deterministic fixed step (dWorldStep; contacts sorted by geometry before they become joints, so the order
/// never depends on the collision space's history and a restored state steps exactly as the original). A
/// body's pose is its shape's centre even when its centre of mass is elsewhere. One instance owns its ODE
/// world; ODE itself is initialised once per process.
class PhysicsWorld {
 public:
  explicit PhysicsWorld(const WorldSettings& settings);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  static constexpr int kImpulseWindowSteps = 5;

  BodyId add_box(const BoxSettings& box);
  /// A body moved by the caller (set_kinematic_motion): a vessel, a truck. It pushes dynamic bodies and is
  /// not pushed; its shapes come from add_box_shape.
  BodyId add_kinematic_body(const core::Pose& pose);
  /// The same, its shapes in one space with kinematic body `beside`'s (a group searched as one: bodies that
  /// come and go together, as another station's machines, cost the broad phase one entry).
  BodyId add_kinematic_body(const core::Pose& pose, BodyId beside);
  /// A box shape on `body` at a pose in the body's frame (kWorld: a static box at a world pose); returns
  /// its index for set_box_shape / set_shape_enabled.
  ShapeId add_box_shape(BodyId body, const core::Vec3& half_extents_m, const core::Pose& local, int surface);
  /// Resizes and moves a body's box shape (a telescoping spreader, its flippers).
  void set_box_shape(ShapeId shape, const core::Vec3& half_extents_m, const core::Pose& local);
  /// A disabled shape touches nothing (a flipper folded up).
  void set_shape_enabled(ShapeId shape, bool enabled);
  /// A static horizontal ground plane at height `z_m`.
  void add_ground(double z_m, int surface = 0);
  /// A static box (quay furniture, a vessel's deck or hatch cover) at a world pose.
  void add_static_box(const core::Vec3& half_extents_m, const core::Pose& pose, int surface = 0);
  /// Switches a body between kinematic (moved by the caller, pushes others, costs no solver rows) and
  /// dynamic (keeps its velocity and its mass).
  void set_kinematic(BodyId body, bool kinematic);
  /// Gives a box body `mass_kg` spread evenly through its box of `half_extents_m` (kinematic or not).
  void set_box_mass(BodyId body, double mass_kg, const core::Vec3& half_extents_m);
  bool is_kinematic(BodyId body) const;
  /// Places a kinematic body and sets the velocities it moves with through the next step.
  void set_kinematic_motion(BodyId body, const core::Pose& pose, const core::Vec3& velocity,
                            const core::Vec3& angular_velocity);
  /// Rigidly joins two bodies as they are now (twistlocks locked); returns a handle for detach().
  /// ODE allocates the fixed joint: one allocation per attachment made (an event, not every step).
  AttachmentId attach(BodyId a, BodyId b);
  /// Joins two bodies at the world point `anchor_m` as they are now, free to turn about it (a load in its
  /// slings on a crane hook); returns a handle for detach().
  AttachmentId attach_pivot(BodyId a, BodyId b, const core::Vec3& anchor_m);
  void detach(AttachmentId attachment);
  /// Bodies `a` and `b` never touch each other (parts of one machine whose boxes overlap: a trailer's front
  /// over its tractor); set once when the scene is built, like the bodies themselves.
  void exclude_contacts(BodyId a, BodyId b);
  /// Attachments made so far (including detached ones).
  int attachments_made() const;
  /// A prismatic joint letting `b` slide along world `axis` relative to `a` (kWorld: the ground); returns its
  /// index.
  SliderId add_slider(BodyId a, BodyId b, const core::Vec3& axis);
  /// Drives a slider at `velocity_mps` with at most `max_force_n` (0 frees it).
  void set_slider_motor(SliderId slider, double velocity_mps, double max_force_n);
  /// Slider displacement [m] along its axis from where it was created, and its rate [m/s].
  double slider_position(SliderId slider) const;
  double slider_rate(SliderId slider) const;
  /// Force the joint (motor, brake) put on the slider's moving body along +axis in the last step [N]:
  /// times slider_rate, the power the drive delivered.
  double slider_force(SliderId slider) const;

  /// A revolute joint letting `b` turn relative to `a` (kWorld: the ground) about the world `axis` through
  /// the world point `anchor_m` (a slewing superstructure, a luffing boom, a wheel); returns its index.
  HingeId add_hinge(BodyId a, BodyId b, const core::Vec3& anchor_m, const core::Vec3& axis);
  /// Drives a hinge at `rate_radps` with at most `max_torque_nm` (0 frees it).
  void set_hinge_motor(HingeId hinge, double rate_radps, double max_torque_nm);
  /// Hinge angle [rad] of `b` relative to `a` about +axis from where it was created, in (-pi, pi] (a machine
  /// that turns further counts the turns), and its rate [rad/s].
  double hinge_angle(HingeId hinge) const;
  double hinge_rate(HingeId hinge) const;
  /// Torque the joint (motor, brake) put on `b` about +axis in the last step [N m]: times hinge_rate, the
  /// power the drive delivered.
  double hinge_torque(HingeId hinge) const;
  /// Force the hinge put on `b` in the last step and its moment about the world point `about_m` [N, N m]
  /// (what `a` carries is the opposite: the load a slewing house puts on its undercarriage).
  struct Wrench {
    core::Vec3 force, moment;
  };
  Wrench hinge_reaction(HingeId hinge, const core::Vec3& about_m) const;
  /// Limits a slider's travel to [low_m, high_m] about where it was created (hard stops).
  void set_slider_limits(SliderId slider, double low_m, double high_m);

  core::Pose pose(BodyId body) const;
  core::Vec3 linear_velocity(BodyId body) const;
  core::Vec3 angular_velocity(BodyId body) const;
  double mass_kg(BodyId body) const;
  /// Kinetic energy of every body the solver moves (kinematic ones left out), translation and rotation [J].
  double kinetic_energy_j() const;
  core::Vec3 point_position(BodyId body, const core::Vec3& local) const;
  core::Vec3 point_velocity(BodyId body, const core::Vec3& local) const;
  /// A world force at a world point for the next step (cleared by the step).
  void add_force_at(BodyId body, const core::Vec3& world_point, const core::Vec3& force);
  /// A world torque for the next step (cleared by the step).
  void add_torque(BodyId body, const core::Vec3& torque);
  /// Static friction at a world point of `body` against the ground for the next step (cleared by the step):
  /// the point's velocity along `along` and across it in the plane normal to `normal` is held at zero by a
  /// constraint, as long as that takes no more than `along_limit_n` and `across_limit_n`; at the limit it
  /// slides against that force (Coulomb). It neither pushes nor pulls along the normal.
  void hold_point(BodyId body, const core::Vec3& world_point, const core::Vec3& normal,
                  const core::Vec3& along, double along_limit_n, double across_limit_n);
  void set_position(BodyId body, const core::Vec3& position);
  void set_linear_velocity(BodyId body, const core::Vec3& velocity);
  /// Stops a body: no linear or angular velocity.
  void stop_body(BodyId body);

  /// Collides, steps the world by `dt_s` with dWorldStep, and clears contacts and forces. A world whose state
  /// or applied forces are not finite or run away (diverged()) is not stepped: ODE is never handed a state
  /// that would trip its internal asserts, and an error ODE reports anyway stops the world instead of the
  /// program.
  void step(double dt_s);
  /// The world stopped because its state diverged; why() names the body and the value.
  bool diverged() const { return !divergence_.empty(); }
  const std::string& divergence() const { return divergence_; }
  /// Contacts generated in the last step.
  int contact_count() const { return contact_count_; }
  /// Messages ODE reported while this world stepped (e.g. "LCP internal error"), since the last call; the
  /// last one's text stays in last_solver_message().
  int take_solver_messages();
  const std::string& last_solver_message() const { return last_solver_message_; }
  /// Impacts (pairs that touch after being apart for impact_rearm_s) since the last call.
  std::vector<ImpactEvent> take_impacts();
  /// Appends the impacts closed since the last call to `into` (its capacity reused: no allocation).
  void drain_impacts(std::vector<ImpactEvent>& into);
  /// Hash of every body's position, orientation and velocities (bit-exact).
  std::uint64_t state_hash() const;
  /// Bodies, attachments and impact bookkeeping; restore into a world built the same way continues exactly.
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  struct Ode;
  std::unique_ptr<Ode> ode_;
  WorldSettings settings_;
  /// Who touches whom, for impacts: a body (or a static shape as -2 - shape index) and its surface, twice.
  using TouchKey = std::array<int, 4>;
  struct OpenImpact {
    TouchKey key{};
    ImpactEvent event;
    int steps_left = 0;
  };
  void collide();
  void close_impact_windows(double dt_s);
  /// "" when every body's state (and, with `forces`, the forces applied to it) is finite and within the
  /// bounds of anything in a harbour; else what is not.
  std::string find_divergence(bool forces) const;

  int contact_count_ = 0;
  std::vector<std::pair<TouchKey, std::int64_t>> last_touch_;  // last step each pair touched, by key
  std::vector<OpenImpact> open_impacts_;
  std::int64_t step_count_ = 0;
  double step_s_ = 0.001;
  std::vector<ImpactEvent> impacts_;
  std::string divergence_;
  int solver_messages_ = 0;
  std::string last_solver_message_;
  friend void record_solver_message(int, const char*, va_list);
};

}  // namespace harbour::physics
