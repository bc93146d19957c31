#include "harbour/physics/PhysicsWorld.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>

#include "harbour/core/Assert.h"
#include "harbour/core/StateHash.h"

namespace harbour::physics {
namespace {

using core::Vec3;

}  // namespace

void record_solver_message(int number, const char* format, va_list args);

namespace {

// the world stepping on this thread, which ODE's messages are about
thread_local PhysicsWorld* g_stepping = nullptr;

void on_ode_message(int number, const char* format, va_list args) {
  if (g_stepping != nullptr) {
    record_solver_message(number, format, args);
    return;
  }
  std::fprintf(stderr, "ODE message %d: ", number);
  std::vfprintf(stderr, format, args);
  std::fprintf(stderr, "\n");
}

// ODE's errors and internal asserts (e.g. "dxNormalize4") abort the process once their handler returns;
// thrown instead, they unwind out of dWorldStep to PhysicsWorld::step, which stops that world
struct OdeFatal : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void on_ode_fatal(int number, const char* format, va_list args) {
  char text[256];
  std::vsnprintf(text, sizeof text, format, args);
  throw OdeFatal("ODE error " + std::to_string(number) + ": " + text);
}

// bounds of anything that moves in a harbour, far above the fastest real motion (a box falling 60 m reaches
// 34 m/s); a body beyond them has diverged (docs/reliability.md)
constexpr double kMaxSpeed_mps = 300.0;
constexpr double kMaxAngularSpeed_rad_s = 200.0;
constexpr double kMaxDistance_m = 1e5;
constexpr double kMaxForce_n = 1e9;
constexpr double kMaxTorque_n_m = 1e10;

double norm_squared(const dReal* v) {
  return v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
}
double norm(const dReal* v) {
  return std::sqrt(norm_squared(v));
}

void init_ode_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    dInitODE2(0);
    dSetMessageHandler(&on_ode_message);
    dSetErrorHandler(&on_ode_fatal);
    dSetDebugHandler(&on_ode_fatal);
    HARBOUR_ASSERT(dCheckConfiguration("ODE_double_precision"), "ODE must be built in double precision");
  });
}

Vec3 to_vec(const dReal* v) {
  return {v[0], v[1], v[2]};
}

void to_ode(const core::Mat3& m, dMatrix3 r) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      r[4 * i + j] = m.m[i][j];
    r[4 * i + 3] = 0.0;
  }
}

core::Mat3 to_mat(const dReal* r) {
  core::Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m.m[i][j] = r[4 * i + j];
  return m;
}

}  // namespace

struct PhysicsWorld::Ode {
  struct Body {
    dBodyID id = nullptr;
    Vec3 shape_offset;          // shape centre relative to the centre of mass, body frame
    dSpaceID shapes = nullptr;  // a kinematic body's own space (a vessel has hundreds of shapes)
  };
  struct Shape {
    dGeomID id = nullptr;
    BodyId body = kWorld;
    int surface = 0;
  };
  struct Attachment {
    dJointID id = nullptr;
    BodyId a = kWorld, b = kWorld;
    std::array<double, 19> pose_a{}, pose_b{};  // each body's raw pose when attached
    bool pivot = false;                         // a ball joint at `anchor` (world, when attached), not fixed
    Vec3 anchor;
  };
  // the joint an attachment's record describes, made between its bodies (at their poses of the moment)
  dJointID make_joint(const Attachment& a) const {
    dJointID j = a.pivot ? dJointCreateBall(world, nullptr) : dJointCreateFixed(world, nullptr);
    dJointAttach(j, bodies[a.a.index].id, bodies[a.b.index].id);
    if (a.pivot)
      dJointSetBallAnchor(j, a.anchor.x, a.anchor.y, a.anchor.z);
    else
      dJointSetFixed(j);
    return j;
  }
  struct PendingContact {
    int shape1 = 0, shape2 = 0;  // shape1 < shape2
    int impact = -1;             // index into open impacts, if this pair's touch is being measured
    dContact contact;
    int order = 0;  // as found (the sort's tie-break: contacts of a pair keep dCollide's order)
  };
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  std::vector<std::pair<dBodyID, dBodyID>> excluded;  // pairs that never touch (few: a linear search)
  bool is_excluded(dBodyID a, dBodyID b) const {
    return std::any_of(excluded.begin(), excluded.end(), [&](const auto& pair) {
      return (pair.first == a && pair.second == b) || (pair.first == b && pair.second == a);
    });
  }
  dJointGroupID contacts = nullptr;
  std::vector<Body> bodies;
  std::vector<Shape> shapes;
  std::vector<dJointID> sliders;
  std::vector<double> slider_sign;             // +1 or -1: ODE's slider sign against ours
  std::deque<dJointFeedback> slider_feedback;  // forces of the last step (stable addresses)
  std::vector<Vec3> slider_axis;
  struct Hinge {
    dJointID id = nullptr;
    BodyId body = kWorld;  // the turning body b (ODE's body 1)
    Vec3 axis;             // unit, world at creation
  };
  std::vector<Hinge> hinges;
  std::deque<dJointFeedback> hinge_feedback;  // torques of the last step (stable addresses)
  std::vector<Attachment> attachments;
  dThreadingImplementationID threading = nullptr;
  std::vector<dContact> contact_buffer;
  std::vector<PendingContact> pending;
  std::vector<std::pair<dBodyID, dContact>> holds;  // hold_point()'s, for the next step
  std::vector<dJointFeedback> feedback;
  PhysicsWorld* owner = nullptr;

  int add_shape(dGeomID g, BodyId body, int surface) {
    shapes.push_back({g, body, surface});
    const int index = static_cast<int>(shapes.size()) - 1;
    dGeomSetData(g, reinterpret_cast<void*>(static_cast<std::intptr_t>(index)));
    return index;
  }
  static int shape_index(dGeomID g) {
    return static_cast<int>(reinterpret_cast<std::intptr_t>(dGeomGetData(g)));
  }
  using RawPose = std::array<double, 19>;  // position, quaternion, rotation matrix (ODE's 3x4)
  RawPose raw_pose(BodyId b) const {
    RawPose pose;
    std::memcpy(pose.data(), dBodyGetPosition(bodies[b.index].id), 3 * sizeof(dReal));
    std::memcpy(pose.data() + 3, dBodyGetQuaternion(bodies[b.index].id), 4 * sizeof(dReal));
    std::memcpy(pose.data() + 7, dBodyGetRotation(bodies[b.index].id), 12 * sizeof(dReal));
    return pose;
  }
  // Exact restore: dBodySetQuaternion renormalises (measured: the last bit changes in 2 of 5 steps), so the
  // saved quaternion and matrix are copied into the body's own storage, which ODE 0.16's getters return;
  // dBodySetPosition then moves the body's shapes.
  void set_raw_pose(BodyId b, const RawPose& pose) const {
    std::memcpy(const_cast<dReal*>(dBodyGetQuaternion(bodies[b.index].id)), pose.data() + 3,
                4 * sizeof(dReal));
    std::memcpy(const_cast<dReal*>(dBodyGetRotation(bodies[b.index].id)), pose.data() + 7,
                12 * sizeof(dReal));
    dBodySetPosition(bodies[b.index].id, pose[0], pose[1], pose[2]);
  }
  // the shape centre's offset from the centre of mass, world frame
  Vec3 world_offset(BodyId b) const {
    return to_mat(dBodyGetRotation(bodies[b.index].id)) * bodies[b.index].shape_offset;
  }
};

PhysicsWorld::PhysicsWorld(const WorldSettings& settings)
    : ode_(std::make_unique<Ode>()), settings_(settings) {
  init_ode_once();
  ode_->world = dWorldCreate();
  // a simple space; a kinematic body's shapes sit in a space of their own inside it, only searched for
  // dynamic bodies that come near (measured: a hash space spent 55 % of an exercise step on the vessel's
  // moving cell guides). The pair order is made canonical in collide().
  ode_->space = dSimpleSpaceCreate(nullptr);
  ode_->contacts = dJointGroupCreate(0);
  ode_->owner = this;
  // buffers a step reuses, sized for a busy scene: stepping allocates only if one is outgrown
  ode_->pending.reserve(1024);
  ode_->holds.reserve(64);
  ode_->feedback.reserve(1024);
  last_touch_.reserve(1024);
  ode_->contact_buffer.resize(static_cast<std::size_t>(std::max(settings.max_contacts_per_pair, 1)));
  ode_->attachments.reserve(256);
  // the contact joint group's arena grown once to a busy scene's contacts (ODE keeps its blocks when the
  // group is emptied): a step with more contacts than any before does not allocate
  for (int n = 0; n < 2048; ++n) {
    dContact c{};
    dJointCreateContact(ode_->world, ode_->contacts, &c);
  }
  dJointGroupEmpty(ode_->contacts);

  open_impacts_.reserve(256);
  impacts_.reserve(256);
  // a threading implementation of its own: worlds stepping on different threads (the station's live world
  // and its recorder's shadow) share no job list
  ode_->threading = dThreadingAllocateSelfThreadedImplementation();
  dWorldSetStepThreadingImplementation(ode_->world, dThreadingImplementationGetFunctions(ode_->threading),
                                       ode_->threading);
  dWorldSetGravity(ode_->world, settings.gravity.x, settings.gravity.y, settings.gravity.z);
  dWorldSetERP(ode_->world, settings.erp);
  dWorldSetCFM(ode_->world, settings.cfm);
  dWorldSetContactMaxCorrectingVel(ode_->world, settings.contact_max_correcting_mps);
  dWorldSetContactSurfaceLayer(ode_->world, settings.contact_surface_layer_m);
}

PhysicsWorld::~PhysicsWorld() {
  dJointGroupDestroy(ode_->contacts);
  dSpaceDestroy(ode_->space);
  dWorldDestroy(ode_->world);
  dThreadingFreeImplementation(ode_->threading);
}

BodyId PhysicsWorld::add_box(const BoxSettings& box) {
  dBodyID b = dBodyCreate(ode_->world);
  dMass mass;
  const Vec3 size = box.half_extents_m * 2.0;
  dMassSetBoxTotal(&mass, box.mass_kg, size.x, size.y, size.z);
  dBodySetMass(b, &mass);
  // ODE keeps the centre of mass at the body origin: the body sits there and its box is offset
  const Vec3 com = box.pose.to_parent(box.center_of_mass_m);
  dBodySetPosition(b, com.x, com.y, com.z);
  dMatrix3 r;
  to_ode(box.pose.rotation, r);
  dBodySetRotation(b, r);
  ode_->bodies.push_back({b, box.center_of_mass_m * -1.0});
  const BodyId id{static_cast<int>(ode_->bodies.size()) - 1};
  if (box.kinematic) dBodySetKinematic(b);
  dBodySetData(b, reinterpret_cast<void*>(static_cast<std::intptr_t>(id.index)));
  if (box.collides) {
    dGeomID g = dCreateBox(ode_->space, size.x, size.y, size.z);
    dGeomSetBody(g, b);
    if (box.center_of_mass_m.x != 0.0 || box.center_of_mass_m.y != 0.0 || box.center_of_mass_m.z != 0.0)
      dGeomSetOffsetPosition(g, -box.center_of_mass_m.x, -box.center_of_mass_m.y, -box.center_of_mass_m.z);
    ode_->add_shape(g, id, box.surface);
  }
  return id;
}

BodyId PhysicsWorld::add_kinematic_body(const core::Pose& pose) {
  return add_kinematic_body(pose, kWorld);
}

BodyId PhysicsWorld::add_kinematic_body(const core::Pose& pose, BodyId beside) {
  dBodyID b = dBodyCreate(ode_->world);
  dBodySetKinematic(b);
  dBodySetPosition(b, pose.position.x, pose.position.y, pose.position.z);
  dMatrix3 r;
  to_ode(pose.rotation, r);
  dBodySetRotation(b, r);
  dSpaceID shapes = beside != kWorld ? ode_->bodies[static_cast<std::size_t>(beside.index)].shapes : nullptr;
  if (!shapes) {
    shapes = dSimpleSpaceCreate(ode_->space);
    dSpaceSetCleanup(shapes, 1);
  }
  ode_->bodies.push_back({b, {}, shapes});
  const BodyId id{static_cast<int>(ode_->bodies.size()) - 1};
  dBodySetData(b, reinterpret_cast<void*>(static_cast<std::intptr_t>(id.index)));
  return id;
}

ShapeId PhysicsWorld::add_box_shape(BodyId body, const Vec3& half_extents_m, const core::Pose& local,
                                    int surface) {
  const dSpaceID space =
      body != kWorld && ode_->bodies[body.index].shapes ? ode_->bodies[body.index].shapes : ode_->space;
  dGeomID g = dCreateBox(space, 2 * half_extents_m.x, 2 * half_extents_m.y, 2 * half_extents_m.z);
  dMatrix3 r;
  to_ode(local.rotation, r);
  if (body == kWorld) {
    dGeomSetPosition(g, local.position.x, local.position.y, local.position.z);
    dGeomSetRotation(g, r);
  } else {
    dGeomSetBody(g, ode_->bodies[body.index].id);
    const Vec3 at = local.position + ode_->bodies[body.index].shape_offset;
    dGeomSetOffsetPosition(g, at.x, at.y, at.z);
    dGeomSetOffsetRotation(g, r);
  }
  return ShapeId{ode_->add_shape(g, body, surface)};
}

void PhysicsWorld::set_box_shape(ShapeId shape, const Vec3& half_extents_m, const core::Pose& local) {
  const Ode::Shape& s = ode_->shapes[static_cast<std::size_t>(shape.index)];
  dGeomBoxSetLengths(s.id, 2 * half_extents_m.x, 2 * half_extents_m.y, 2 * half_extents_m.z);
  dMatrix3 r;
  to_ode(local.rotation, r);
  const Vec3 at = local.position + ode_->bodies[s.body.index].shape_offset;
  dGeomSetOffsetPosition(s.id, at.x, at.y, at.z);
  dGeomSetOffsetRotation(s.id, r);
}

void PhysicsWorld::set_shape_enabled(ShapeId shape, bool enabled) {
  const dGeomID g = ode_->shapes[static_cast<std::size_t>(shape.index)].id;
  if (enabled) {
    dGeomEnable(g);
  } else {
    dGeomDisable(g);
  }
}

void PhysicsWorld::add_ground(double z_m, int surface) {
  ode_->add_shape(dCreatePlane(ode_->space, 0, 0, 1, z_m), kWorld, surface);
}

void PhysicsWorld::add_static_box(const Vec3& half_extents_m, const core::Pose& pose, int surface) {
  add_box_shape(kWorld, half_extents_m, pose, surface);
}

void PhysicsWorld::set_kinematic(BodyId body, bool kinematic) {
  if (kinematic) {
    dBodySetKinematic(ode_->bodies[body.index].id);
  } else {
    dBodySetDynamic(ode_->bodies[body.index].id);
  }
}

void PhysicsWorld::set_box_mass(BodyId body, double mass_kg, const Vec3& half_extents_m) {
  dBodyID b = ode_->bodies[body.index].id;
  const bool kinematic = dBodyIsKinematic(b) != 0;
  dMass mass;
  const Vec3 size = half_extents_m * 2.0;
  dMassSetBoxTotal(&mass, mass_kg, size.x, size.y, size.z);
  dBodySetMass(b, &mass);  // (a kinematic body's mass is kept for when it turns dynamic)
  if (kinematic) dBodySetKinematic(b);
}

bool PhysicsWorld::is_kinematic(BodyId body) const {
  return dBodyIsKinematic(ode_->bodies[body.index].id) != 0;
}

void PhysicsWorld::set_kinematic_motion(BodyId body, const core::Pose& pose, const Vec3& velocity,
                                        const Vec3& angular_velocity) {
  dBodyID b = ode_->bodies[body.index].id;
  dBodySetPosition(b, pose.position.x, pose.position.y, pose.position.z);
  dMatrix3 r;
  to_ode(pose.rotation, r);
  dBodySetRotation(b, r);
  dBodySetLinearVel(b, velocity.x, velocity.y, velocity.z);
  dBodySetAngularVel(b, angular_velocity.x, angular_velocity.y, angular_velocity.z);
}

AttachmentId PhysicsWorld::attach(BodyId a, BodyId b) {
  Ode::Attachment made{nullptr, a, b, ode_->raw_pose(a), ode_->raw_pose(b)};
  made.id = ode_->make_joint(made);
  ode_->attachments.push_back(made);
  return AttachmentId{static_cast<int>(ode_->attachments.size()) - 1};
}

AttachmentId PhysicsWorld::attach_pivot(BodyId a, BodyId b, const Vec3& anchor_m) {
  Ode::Attachment made{nullptr, a, b, ode_->raw_pose(a), ode_->raw_pose(b), true, anchor_m};
  made.id = ode_->make_joint(made);
  ode_->attachments.push_back(made);
  return AttachmentId{static_cast<int>(ode_->attachments.size()) - 1};
}

int PhysicsWorld::attachments_made() const {
  return static_cast<int>(ode_->attachments.size());
}

void PhysicsWorld::detach(AttachmentId attachment) {
  Ode::Attachment& a = ode_->attachments[static_cast<std::size_t>(attachment.index)];
  if (a.id) dJointDestroy(a.id);
  a.id = nullptr;
}

SliderId PhysicsWorld::add_slider(BodyId a, BodyId b, const Vec3& axis) {
  dJointID j = dJointCreateSlider(ode_->world, nullptr);
  // ODE measures a slider as body 1 relative to body 2. On the world, attach b alone. Between two bodies the
  // (a, b) attachment is the numerically stable one (measured: (b, a) diverged under the STS trolley), so the
  // adapter flips its sign: our position and motor speed are b relative to a along +axis.
  if (a == kWorld) {
    dJointAttach(j, ode_->bodies[b.index].id, nullptr);
  } else {
    dJointAttach(j, ode_->bodies[a.index].id, ode_->bodies[b.index].id);
  }
  dJointSetSliderAxis(j, axis.x, axis.y, axis.z);
  ode_->slider_sign.push_back(a == kWorld ? 1.0 : -1.0);
  dJointSetFeedback(j, &ode_->slider_feedback.emplace_back());
  ode_->slider_axis.push_back(axis * (1.0 / std::sqrt(dot(axis, axis))));
  ode_->sliders.push_back(j);
  return SliderId{static_cast<int>(ode_->sliders.size()) - 1};
}

void PhysicsWorld::set_slider_motor(SliderId slider, double velocity_mps, double max_force_n) {
  dJointSetSliderParam(ode_->sliders[slider.index], dParamVel,
                       ode_->slider_sign[slider.index] * velocity_mps);
  dJointSetSliderParam(ode_->sliders[slider.index], dParamFMax, max_force_n);
}

double PhysicsWorld::slider_position(SliderId slider) const {
  return ode_->slider_sign[slider.index] * dJointGetSliderPosition(ode_->sliders[slider.index]);
}

double PhysicsWorld::slider_rate(SliderId slider) const {
  return ode_->slider_sign[slider.index] * dJointGetSliderPositionRate(ode_->sliders[slider.index]);
}

double PhysicsWorld::slider_force(SliderId slider) const {
  // the force on the moving body b along the axis: on the world b is ODE's body 1; between two bodies ODE's
  // body 1 is a, which feels the reaction
  const dJointFeedback& f = ode_->slider_feedback[static_cast<std::size_t>(slider.index)];
  const bool on_world = ode_->slider_sign[slider.index] > 0.0;
  return on_world ? dot(to_vec(f.f1), ode_->slider_axis[static_cast<std::size_t>(slider.index)])
                  : -dot(to_vec(f.f1), ode_->slider_axis[static_cast<std::size_t>(slider.index)]);
}

HingeId PhysicsWorld::add_hinge(BodyId a, BodyId b, const Vec3& anchor_m, const Vec3& axis) {
  dJointID j = dJointCreateHinge(ode_->world, nullptr);
  // b is ODE's body 1, so ODE's angle and rate are b relative to a directly
  dJointAttach(j, ode_->bodies[b.index].id, a == kWorld ? nullptr : ode_->bodies[a.index].id);
  dJointSetHingeAnchor(j, anchor_m.x, anchor_m.y, anchor_m.z);  // world coordinates
  dJointSetHingeAxis(j, axis.x, axis.y, axis.z);
  dJointSetFeedback(j, &ode_->hinge_feedback.emplace_back());
  ode_->hinges.push_back({j, b, axis * (1.0 / std::sqrt(dot(axis, axis)))});
  return HingeId{static_cast<int>(ode_->hinges.size()) - 1};
}

void PhysicsWorld::set_hinge_motor(HingeId hinge, double rate_radps, double max_torque_nm) {
  dJointSetHingeParam(ode_->hinges[static_cast<std::size_t>(hinge.index)].id, dParamVel, rate_radps);
  dJointSetHingeParam(ode_->hinges[static_cast<std::size_t>(hinge.index)].id, dParamFMax, max_torque_nm);
}

double PhysicsWorld::hinge_angle(HingeId hinge) const {
  return dJointGetHingeAngle(ode_->hinges[static_cast<std::size_t>(hinge.index)].id);
}

double PhysicsWorld::hinge_rate(HingeId hinge) const {
  return dJointGetHingeAngleRate(ode_->hinges[static_cast<std::size_t>(hinge.index)].id);
}

PhysicsWorld::Wrench PhysicsWorld::hinge_reaction(HingeId hinge, const Vec3& about_m) const {
  const Ode::Hinge& h = ode_->hinges[static_cast<std::size_t>(hinge.index)];
  const dJointFeedback& f = ode_->hinge_feedback[static_cast<std::size_t>(hinge.index)];
  const Vec3 com = to_vec(dBodyGetPosition(ode_->bodies[h.body.index].id));
  const Vec3 force = to_vec(f.f1);
  return {force, to_vec(f.t1) + cross(com - about_m, force)};
}

void PhysicsWorld::set_slider_limits(SliderId slider, double low_m, double high_m) {
  // ODE's position is ours times the sign: flip the stops with it (high first keeps lo <= hi on the way)
  const double sign = ode_->slider_sign[slider.index];
  const double lo = sign > 0 ? low_m : -high_m, hi = sign > 0 ? high_m : -low_m;
  dJointSetSliderParam(ode_->sliders[slider.index], dParamLoStop, -dInfinity);
  dJointSetSliderParam(ode_->sliders[slider.index], dParamHiStop, hi);
  dJointSetSliderParam(ode_->sliders[slider.index], dParamLoStop, lo);
}

double PhysicsWorld::hinge_torque(HingeId hinge) const {
  // ODE reports the joint's force and torque on b at its centre of mass; about the anchor the force has no
  // moment, so the torque left about the axis is the motor's (the hinge constrains only the other two axes)
  const Ode::Hinge& h = ode_->hinges[static_cast<std::size_t>(hinge.index)];
  const dJointFeedback& f = ode_->hinge_feedback[static_cast<std::size_t>(hinge.index)];
  dVector3 anchor;
  dJointGetHingeAnchor(h.id, anchor);
  const Vec3 com = to_vec(dBodyGetPosition(ode_->bodies[h.body.index].id));
  dVector3 axis;
  dJointGetHingeAxis(h.id, axis);
  const Vec3 about_anchor = to_vec(f.t1) - cross(to_vec(anchor) - com, to_vec(f.f1));
  return dot(about_anchor, to_vec(axis));
}

core::Pose PhysicsWorld::pose(BodyId body) const {
  const dBodyID b = ode_->bodies[body.index].id;
  return {to_mat(dBodyGetRotation(b)), to_vec(dBodyGetPosition(b)) + ode_->world_offset(body)};
}
Vec3 PhysicsWorld::linear_velocity(BodyId body) const {
  const dBodyID b = ode_->bodies[body.index].id;
  return to_vec(dBodyGetLinearVel(b)) + cross(to_vec(dBodyGetAngularVel(b)), ode_->world_offset(body));
}
Vec3 PhysicsWorld::angular_velocity(BodyId body) const {
  if (body == kWorld) return {};
  return to_vec(dBodyGetAngularVel(ode_->bodies[body.index].id));
}

double PhysicsWorld::kinetic_energy_j() const {
  double total = 0.0;
  for (const Ode::Body& b : ode_->bodies) {
    if (dBodyIsKinematic(b.id)) continue;
    dMass m;
    dBodyGetMass(b.id, &m);
    const Vec3 v = to_vec(dBodyGetLinearVel(b.id));
    dVector3 w;  // angular velocity in the body frame, where the inertia is
    const dReal* world_w = dBodyGetAngularVel(b.id);
    dBodyVectorFromWorld(b.id, world_w[0], world_w[1], world_w[2], w);
    double rotation = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        rotation += w[i] * m.I[i * 4 + j] * w[j];
    total += 0.5 * m.mass * core::dot(v, v) + 0.5 * rotation;
  }
  return total;
}

double PhysicsWorld::mass_kg(BodyId body) const {
  dMass m;
  dBodyGetMass(ode_->bodies[body.index].id, &m);
  return m.mass;
}

Vec3 PhysicsWorld::point_position(BodyId body, const Vec3& local) const {
  if (body == kWorld) return local;
  const Vec3 at = local + ode_->bodies[body.index].shape_offset;
  dVector3 out;
  dBodyGetRelPointPos(ode_->bodies[body.index].id, at.x, at.y, at.z, out);
  return to_vec(out);
}

Vec3 PhysicsWorld::point_velocity(BodyId body, const Vec3& local) const {
  if (body == kWorld) return {};
  const Vec3 at = local + ode_->bodies[body.index].shape_offset;
  dVector3 out;
  dBodyGetRelPointVel(ode_->bodies[body.index].id, at.x, at.y, at.z, out);
  return to_vec(out);
}

void PhysicsWorld::add_force_at(BodyId body, const Vec3& p, const Vec3& f) {
  if (body == kWorld) return;
  dBodyAddForceAtPos(ode_->bodies[body.index].id, f.x, f.y, f.z, p.x, p.y, p.z);
}

void PhysicsWorld::add_torque(BodyId body, const Vec3& t) {
  if (body == kWorld) return;
  dBodyAddTorque(ode_->bodies[body.index].id, t.x, t.y, t.z);
}

void PhysicsWorld::hold_point(BodyId body, const Vec3& world_point, const Vec3& normal, const Vec3& along,
                              double along_limit_n, double across_limit_n) {
  if (body == kWorld) return;
  dContact c{};
  // a contact joint whose two friction rows are the hold (constant force limits: no dContactApprox1) and
  // whose normal row, soft and at zero depth, passes next to nothing (a damper of 1/cfm = 100 N s/m)
  c.surface.mode = dContactMu2 | dContactFDir1 | dContactSoftCFM | dContactSoftERP;
  c.surface.mu = std::max(0.0, along_limit_n);
  c.surface.mu2 = std::max(0.0, across_limit_n);
  c.surface.soft_cfm = 1e-2;
  c.surface.soft_erp = 0.0;
  c.geom.pos[0] = world_point.x, c.geom.pos[1] = world_point.y, c.geom.pos[2] = world_point.z;
  c.geom.normal[0] = normal.x, c.geom.normal[1] = normal.y, c.geom.normal[2] = normal.z;
  c.geom.depth = 0.0;
  c.fdir1[0] = along.x, c.fdir1[1] = along.y, c.fdir1[2] = along.z;
  ode_->holds.emplace_back(ode_->bodies[body.index].id, c);
}

void PhysicsWorld::set_position(BodyId body, const Vec3& p) {
  const Vec3 com = p - ode_->world_offset(body);
  dBodySetPosition(ode_->bodies[body.index].id, com.x, com.y, com.z);
}
void PhysicsWorld::stop_body(BodyId body) {
  dBodySetLinearVel(ode_->bodies[body.index].id, 0.0, 0.0, 0.0);
  dBodySetAngularVel(ode_->bodies[body.index].id, 0.0, 0.0, 0.0);
}

void PhysicsWorld::set_linear_velocity(BodyId body, const Vec3& v) {
  const dBodyID b = ode_->bodies[body.index].id;
  const Vec3 com = v - cross(to_vec(dBodyGetAngularVel(b)), ode_->world_offset(body));
  dBodySetLinearVel(b, com.x, com.y, com.z);
}

void PhysicsWorld::exclude_contacts(BodyId a, BodyId b) {
  ode_->excluded.emplace_back(ode_->bodies[a.index].id, ode_->bodies[b.index].id);
}

void PhysicsWorld::collide() {
  // gather every touching pair's contacts with the pair ordered by shape index, then sort by pair: the joint
  // order (and so the solver's result, bit for bit) depends only on the state, not on the space's history
  ode_->pending.clear();
  static dNearCallback* const near = [](void* data, dGeomID g1, dGeomID g2) {
    auto* ode = static_cast<Ode*>(data);
    if (dGeomIsSpace(g1) || dGeomIsSpace(g2)) {
      // a kinematic body's shapes: only against a dynamic body's shape
      if (dGeomIsSpace(g1) && dGeomIsSpace(g2)) return;
      const dGeomID other = dGeomIsSpace(g1) ? g2 : g1;
      const dBodyID b = dGeomGetBody(other);
      if (!b || dBodyIsKinematic(b)) return;
      dSpaceCollide2(g1, g2, data, near);
      return;
    }
    dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
    if (!b1 && !b2) return;
    if (b1 && b2 &&
        (b1 == b2 || dAreConnectedExcluding(b1, b2, dJointTypeContact) || ode->is_excluded(b1, b2)))
      return;
    // kinematic bodies push dynamic ones only: not each other, not static geometry
    const bool kinematic1 = !b1 || dBodyIsKinematic(b1), kinematic2 = !b2 || dBodyIsKinematic(b2);
    if (kinematic1 && kinematic2) return;
    if (Ode::shape_index(g1) > Ode::shape_index(g2)) std::swap(g1, g2);
    const WorldSettings& s = ode->owner->settings_;
    std::vector<dContact>& contacts = ode->contact_buffer;  // reused: no allocation per colliding pair
    contacts.resize(static_cast<std::size_t>(s.max_contacts_per_pair));
    const int n = dCollide(g1, g2, s.max_contacts_per_pair, &contacts[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i)
      ode->pending.push_back({Ode::shape_index(g1), Ode::shape_index(g2), -1,
                              contacts[static_cast<std::size_t>(i)], static_cast<int>(ode->pending.size())});
  };
  dSpaceCollide(ode_->space, ode_.get(), near);
  // a total order (a stable sort's result without its temporary buffer)
  std::sort(ode_->pending.begin(), ode_->pending.end(), [](const auto& a, const auto& b) {
    return a.shape1 != b.shape1   ? a.shape1 < b.shape1
           : a.shape2 != b.shape2 ? a.shape2 < b.shape2
                                  : a.order < b.order;
  });

  // impacts: a pair of (body or static shape, surface) touching after being apart for impact_rearm_s opens an
  // impact window that measures its closing speed now and its impulse over the next steps
  const auto rearm = static_cast<std::int64_t>(settings_.impact_rearm_s / step_s_);
  for (std::size_t i = 0; i < ode_->pending.size(); ++i) {
    Ode::PendingContact& p = ode_->pending[i];
    const Ode::Shape& s1 = ode_->shapes[static_cast<std::size_t>(p.shape1)];
    const Ode::Shape& s2 = ode_->shapes[static_cast<std::size_t>(p.shape2)];
    const TouchKey key{s1.body == kWorld ? -2 - p.shape1 : s1.body.index, s1.surface,
                       s2.body == kWorld ? -2 - p.shape2 : s2.body.index, s2.surface};
    const bool same_as_previous =
        i > 0 && ode_->pending[i - 1].shape1 == p.shape1 && ode_->pending[i - 1].shape2 == p.shape2;
    if (!same_as_previous) {
      auto last = std::lower_bound(last_touch_.begin(), last_touch_.end(), key,
                                   [](const auto& entry, const TouchKey& k) { return entry.first < k; });
      const bool known = last != last_touch_.end() && last->first == key;
      if (!known || step_count_ - last->second > rearm) {
        const dContactGeom& g = p.contact.geom;
        dVector3 v1{0, 0, 0, 0}, v2{0, 0, 0, 0};
        if (s1.body != kWorld)
          dBodyGetPointVel(ode_->bodies[s1.body.index].id, g.pos[0], g.pos[1], g.pos[2], v1);
        if (s2.body != kWorld)
          dBodyGetPointVel(ode_->bodies[s2.body.index].id, g.pos[0], g.pos[1], g.pos[2], v2);
        const double closing = std::abs((v1[0] - v2[0]) * g.normal[0] + (v1[1] - v2[1]) * g.normal[1] +
                                        (v1[2] - v2[2]) * g.normal[2]);
        ImpactEvent e{s1.body, s2.body, s1.surface, s2.surface, closing, 0.0, {g.pos[0], g.pos[1], g.pos[2]}};
        if (e.body == kWorld) {  // a body first, static geometry second
          std::swap(e.body, e.other);
          std::swap(e.surface, e.other_surface);
        }
        open_impacts_.push_back({key, e, kImpulseWindowSteps});
      }
      if (known)
        last->second = step_count_;
      else
        last_touch_.insert(last, {key, step_count_});
    }
    for (std::size_t w = 0; w < open_impacts_.size(); ++w)
      if (open_impacts_[w].key == key) p.impact = static_cast<int>(w);
  }

  // a pair apart for longer than the re-arm time counts as never having touched: forget it
  std::erase_if(last_touch_, [&](const auto& entry) { return step_count_ - entry.second > rearm; });

  const WorldSettings& s = settings_;
  ode_->feedback.resize(ode_->pending.size());  // sized before any joint points into it
  for (std::size_t i = 0; i < ode_->pending.size(); ++i) {
    dContact& c = ode_->pending[i].contact;
    c.surface.mode = dContactSoftERP | dContactSoftCFM | dContactApprox1;
    c.surface.mu = s.contact_friction;
    c.surface.soft_erp = s.contact_erp;
    c.surface.soft_cfm = s.contact_cfm;
    dJointID j = dJointCreateContact(ode_->world, ode_->contacts, &c);
    dJointAttach(j, dGeomGetBody(c.geom.g1), dGeomGetBody(c.geom.g2));
    dJointSetFeedback(j, &ode_->feedback[i]);
  }
  contact_count_ = static_cast<int>(ode_->pending.size());
}

void PhysicsWorld::close_impact_windows(double dt_s) {
  for (std::size_t i = 0; i < ode_->pending.size(); ++i) {
    const Ode::PendingContact& p = ode_->pending[i];
    if (p.impact < 0) continue;
    const dJointFeedback& f = ode_->feedback[i];
    const dReal* n = p.contact.geom.normal;
    const double f1 = std::abs(f.f1[0] * n[0] + f.f1[1] * n[1] + f.f1[2] * n[2]);
    const double f2 = std::abs(f.f2[0] * n[0] + f.f2[1] * n[1] + f.f2[2] * n[2]);
    open_impacts_[static_cast<std::size_t>(p.impact)].event.impulse_ns += std::max(f1, f2) * dt_s;
  }
  std::size_t kept = 0;
  for (OpenImpact& w : open_impacts_) {
    if (--w.steps_left <= 0) {
      impacts_.push_back(w.event);
    } else {
      open_impacts_[kept++] = w;
    }
  }
  open_impacts_.resize(kept);
}

void record_solver_message(int number, const char* format, va_list args) {
  char text[256];
  std::vsnprintf(text, sizeof text, format, args);
  ++g_stepping->solver_messages_;
  g_stepping->last_solver_message_ = "ODE message " + std::to_string(number) + ": " + text;
}

int PhysicsWorld::take_solver_messages() {
  const int n = solver_messages_;
  solver_messages_ = 0;
  return n;
}

std::string PhysicsWorld::find_divergence(bool forces) const {
  for (std::size_t n = 0; n < ode_->bodies.size(); ++n) {
    const dBodyID b = ode_->bodies[n].id;
    const dReal* q = dBodyGetQuaternion(b);
    // the bounds on squares first, without a root (false for NaN too); the message only when one fails
    const bool within =
        norm_squared(dBodyGetPosition(b)) <= kMaxDistance_m * kMaxDistance_m &&
        norm_squared(dBodyGetLinearVel(b)) <= kMaxSpeed_mps * kMaxSpeed_mps &&
        norm_squared(dBodyGetAngularVel(b)) <= kMaxAngularSpeed_rad_s * kMaxAngularSpeed_rad_s &&
        (!forces || (norm_squared(dBodyGetForce(b)) <= kMaxForce_n * kMaxForce_n &&
                     norm_squared(dBodyGetTorque(b)) <= kMaxTorque_n_m * kMaxTorque_n_m));
    if (within && std::abs(q[0]) + norm(q + 1) <= 2.0) continue;
    const double checks[][2] = {{norm(dBodyGetPosition(b)), kMaxDistance_m},
                                {norm(dBodyGetLinearVel(b)), kMaxSpeed_mps},
                                {norm(dBodyGetAngularVel(b)), kMaxAngularSpeed_rad_s},
                                {std::abs(q[0]) + norm(q + 1), 2.0},
                                {forces ? norm(dBodyGetForce(b)) : 0.0, kMaxForce_n},
                                {forces ? norm(dBodyGetTorque(b)) : 0.0, kMaxTorque_n_m}};
    const char* names[] = {"position",    "speed",         "angular speed",
                           "orientation", "applied force", "applied torque"};
    for (std::size_t k = 0; k < std::size(checks); ++k)
      if (!(checks[k][0] <= checks[k][1]))  // also true for NaN
        return "body " + std::to_string(n) + ": " + names[k] + " " + std::to_string(checks[k][0]) +
               " is beyond " + std::to_string(checks[k][1]);
  }
  return {};
}

void PhysicsWorld::step(double dt_s) {
  // the holds are for this step only, whether it runs or not
  struct HoldsCleared {
    Ode& ode;
    ~HoldsCleared() { ode.holds.clear(); }
  } holds_cleared{*ode_};
  if (diverged()) return;
  step_s_ = dt_s;
  // what ODE would be handed: a diverged state stops the world before it reaches ODE's asserts
  divergence_ = find_divergence(true);
  if (diverged()) return;
  g_stepping = this;
  // ODE's per-thread collision data, once for each thread that steps a world
  thread_local const bool ode_thread_ready = dAllocateODEDataForThread(dAllocateMaskAll) != 0;
  if (!ode_thread_ready) {
    divergence_ = "ODE could not allocate its data for this thread";
    g_stepping = nullptr;
    return;
  }
  try {
    collide();
    for (auto& [body, hold] : ode_->holds)
      dJointAttach(dJointCreateContact(ode_->world, ode_->contacts, &hold), body, nullptr);
    dWorldStep(ode_->world, dt_s);
  } catch (const OdeFatal& e) {
    divergence_ = e.what();
  }
  g_stepping = nullptr;
  if (!diverged()) divergence_ = find_divergence(false);
  if (diverged()) return;
  close_impact_windows(dt_s);
  dJointGroupEmpty(ode_->contacts);
  ++step_count_;
}

std::vector<ImpactEvent> PhysicsWorld::take_impacts() {
  std::vector<ImpactEvent> out;
  drain_impacts(out);
  return out;
}

void PhysicsWorld::drain_impacts(std::vector<ImpactEvent>& into) {
  into.insert(into.end(), impacts_.begin(), impacts_.end());
  impacts_.clear();
}

std::uint64_t PhysicsWorld::state_hash() const {
  core::StateHash hash;
  for (const Ode::Body& body : ode_->bodies) {
    const dBodyID b = body.id;
    hash.add_bytes(dBodyGetPosition(b), 3 * sizeof(dReal));
    hash.add_bytes(dBodyGetQuaternion(b), 4 * sizeof(dReal));
    hash.add_bytes(dBodyGetLinearVel(b), 3 * sizeof(dReal));
    hash.add_bytes(dBodyGetAngularVel(b), 3 * sizeof(dReal));
  }
  return hash.value();
}

namespace {
constexpr std::uint32_t kPhysicsSection = 0x50485953;  // "PHYS"
struct Touch {
  std::array<int, 4> key;
  std::int64_t step;
};
}  // namespace

void PhysicsWorld::save_state(core::StateWriter& out) const {
  out.section(kPhysicsSection);
  std::vector<double> bodies;
  for (std::size_t b = 0; b < ode_->bodies.size(); ++b) {
    const auto pose = ode_->raw_pose(BodyId{static_cast<int>(b)});
    bodies.insert(bodies.end(), pose.begin(), pose.end());
    const dReal* v = dBodyGetLinearVel(ode_->bodies[b].id);
    const dReal* w = dBodyGetAngularVel(ode_->bodies[b].id);
    bodies.insert(bodies.end(),
                  {v[0], v[1], v[2], w[0], w[1], w[2], dBodyIsKinematic(ode_->bodies[b].id) ? 1.0 : 0.0});
  }
  out.put(bodies);
  out.put(static_cast<std::uint64_t>(ode_->attachments.size()));
  for (const Ode::Attachment& a : ode_->attachments) {
    // 0 detached, 1 fixed, 2 pivot (followed by its anchor): states saved before pivots read the same
    out.put(static_cast<std::uint8_t>(a.id == nullptr ? 0 : a.pivot ? 2 : 1));
    out.put(a.a);
    out.put(a.b);
    out.put(a.pose_a);
    out.put(a.pose_b);
    if (a.id && a.pivot) out.put(std::array<double, 3>{a.anchor.x, a.anchor.y, a.anchor.z});
  }
  std::vector<Touch> touches;
  for (const auto& [key, step] : last_touch_)
    touches.push_back({key, step});
  out.put(touches);
  std::vector<OpenImpact> open(open_impacts_.begin(), open_impacts_.end());
  out.put(open);
  out.put(step_count_);
  out.put(step_s_);
}

void PhysicsWorld::restore_state(core::StateReader& in) {
  in.section(kPhysicsSection, "physics");
  std::vector<double> bodies;
  constexpr std::size_t kPerBody = 19 + 6 + 1;
  in.get(bodies, static_cast<std::int64_t>(ode_->bodies.size() * kPerBody));
  // attachments first (a fixed joint keeps the relative pose of the moment it was made), then the bodies
  for (Ode::Attachment& a : ode_->attachments)
    if (a.id) dJointDestroy(a.id);
  ode_->attachments.clear();
  const auto attachments = in.get<std::uint64_t>();
  for (std::uint64_t n = 0; n < attachments; ++n) {
    Ode::Attachment a;
    const auto joint = in.get<std::uint8_t>();
    if (joint > 2) throw core::StateError("saved state has an attachment of an unknown kind");
    const bool active = joint != 0;
    a.pivot = joint == 2;
    in.get(a.a);
    in.get(a.b);
    in.get(a.pose_a);
    in.get(a.pose_b);
    if (a.pivot) {
      const auto anchor = in.get<std::array<double, 3>>();
      a.anchor = {anchor[0], anchor[1], anchor[2]};
    }
    const auto count = static_cast<int>(ode_->bodies.size());
    if (!a.a.valid() || a.a.index >= count || !a.b.valid() || a.b.index >= count)
      throw core::StateError("saved state attaches a body this simulation does not have");
    if (active) {
      ode_->set_raw_pose(a.a, a.pose_a);
      ode_->set_raw_pose(a.b, a.pose_b);
      a.id = ode_->make_joint(a);
    }
    ode_->attachments.push_back(a);
  }
  for (std::size_t b = 0; b < ode_->bodies.size(); ++b) {
    const double* v = &bodies[kPerBody * b];
    Ode::RawPose pose;
    std::copy(v, v + 19, pose.begin());
    ode_->set_raw_pose(BodyId{static_cast<int>(b)}, pose);
    dBodySetLinearVel(ode_->bodies[b].id, v[19], v[20], v[21]);
    dBodySetAngularVel(ode_->bodies[b].id, v[22], v[23], v[24]);
    set_kinematic(BodyId{static_cast<int>(b)}, v[25] != 0.0);
  }
  std::vector<Touch> touches;
  in.get(touches);
  last_touch_.clear();
  for (const Touch& t : touches)
    last_touch_.push_back({t.key, t.step});
  std::sort(last_touch_.begin(), last_touch_.end());
  std::vector<OpenImpact> open;
  in.get(open);
  open_impacts_ = open;
  in.get(step_count_);
  in.get(step_s_);
  impacts_.clear();
}

}  // namespace harbour::physics
