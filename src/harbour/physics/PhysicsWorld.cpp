#include "harbour/physics/PhysicsWorld.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>

#include "harbour/core/Assert.h"
#include "harbour/core/StateHash.h"

namespace harbour::physics {
namespace {

using core::Vec3;

void init_ode_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    dInitODE2(0);
    HARBOUR_ASSERT(dCheckConfiguration("ODE_double_precision"), "ODE must be built in double precision");
  });
}

Vec3 to_vec(const dReal* v) {
  return {v[0], v[1], v[2]};
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
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  std::vector<dBodyID> bodies;
  std::vector<dJointID> sliders;
  std::vector<double> slider_sign;  // +1 or -1: ODE's slider sign against ours
  std::vector<dJointID> attachments;
  std::vector<dContact> contact_buffer;
  PhysicsWorld* owner = nullptr;
};

PhysicsWorld::PhysicsWorld(const WorldSettings& settings)
    : ode_(std::make_unique<Ode>()), settings_(settings) {
  init_ode_once();
  ode_->world = dWorldCreate();
  ode_->space = dSimpleSpaceCreate(nullptr);
  ode_->contacts = dJointGroupCreate(0);
  ode_->owner = this;
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
}

BodyId PhysicsWorld::add_box(const BoxSettings& box) {
  dBodyID b = dBodyCreate(ode_->world);
  dMass mass;
  const Vec3 size = box.half_extents_m * 2.0;
  dMassSetBoxTotal(&mass, box.mass_kg, size.x, size.y, size.z);
  dBodySetMass(b, &mass);
  dBodySetPosition(b, box.pose.position.x, box.pose.position.y, box.pose.position.z);
  dMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      r[4 * i + j] = box.pose.rotation.m[i][j];
    r[4 * i + 3] = 0.0;
  }
  dBodySetRotation(b, r);
  if (box.collides) {
    dGeomID g = dCreateBox(ode_->space, size.x, size.y, size.z);
    dGeomSetBody(g, b);
  }
  ode_->bodies.push_back(b);
  const BodyId id = static_cast<BodyId>(ode_->bodies.size()) - 1;
  dBodySetData(b, reinterpret_cast<void*>(static_cast<std::intptr_t>(id)));
  return id;
}

void PhysicsWorld::add_ground(double z_m) {
  dCreatePlane(ode_->space, 0, 0, 1, z_m);
}

void PhysicsWorld::add_static_box(const Vec3& half_extents_m, const core::Pose& pose) {
  dGeomID g = dCreateBox(ode_->space, 2 * half_extents_m.x, 2 * half_extents_m.y, 2 * half_extents_m.z);
  dGeomSetPosition(g, pose.position.x, pose.position.y, pose.position.z);
  dMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      r[4 * i + j] = pose.rotation.m[i][j];
    r[4 * i + 3] = 0.0;
  }
  dGeomSetRotation(g, r);
}

int PhysicsWorld::attach(BodyId a, BodyId b) {
  dJointID j = dJointCreateFixed(ode_->world, nullptr);
  dJointAttach(j, ode_->bodies[a], ode_->bodies[b]);
  dJointSetFixed(j);
  ode_->attachments.push_back(j);
  return static_cast<int>(ode_->attachments.size()) - 1;
}

void PhysicsWorld::detach(int attachment) {
  dJointID& j = ode_->attachments[static_cast<std::size_t>(attachment)];
  if (j) dJointDestroy(j);
  j = nullptr;
}

int PhysicsWorld::add_slider(BodyId a, BodyId b, const Vec3& axis) {
  dJointID j = dJointCreateSlider(ode_->world, nullptr);
  // ODE measures a slider as body 1 relative to body 2. On the world, attach b alone. Between two bodies the
  // (a, b) attachment is the numerically stable one (measured: (b, a) diverged under the STS trolley), so the
  // adapter flips its sign: our position and motor speed are b relative to a along +axis.
  if (a == kWorld) {
    dJointAttach(j, ode_->bodies[b], nullptr);
  } else {
    dJointAttach(j, ode_->bodies[a], ode_->bodies[b]);
  }
  dJointSetSliderAxis(j, axis.x, axis.y, axis.z);
  ode_->slider_sign.push_back(a == kWorld ? 1.0 : -1.0);
  ode_->sliders.push_back(j);
  return static_cast<int>(ode_->sliders.size()) - 1;
}

void PhysicsWorld::set_slider_motor(int slider, double velocity_mps, double max_force_n) {
  dJointSetSliderParam(ode_->sliders[slider], dParamVel, ode_->slider_sign[slider] * velocity_mps);
  dJointSetSliderParam(ode_->sliders[slider], dParamFMax, max_force_n);
}

double PhysicsWorld::slider_position(int slider) const {
  return ode_->slider_sign[slider] * dJointGetSliderPosition(ode_->sliders[slider]);
}

double PhysicsWorld::slider_rate(int slider) const {
  return ode_->slider_sign[slider] * dJointGetSliderPositionRate(ode_->sliders[slider]);
}

core::Pose PhysicsWorld::pose(BodyId body) const {
  return {to_mat(dBodyGetRotation(ode_->bodies[body])), to_vec(dBodyGetPosition(ode_->bodies[body]))};
}
Vec3 PhysicsWorld::linear_velocity(BodyId body) const {
  return to_vec(dBodyGetLinearVel(ode_->bodies[body]));
}
Vec3 PhysicsWorld::angular_velocity(BodyId body) const {
  return to_vec(dBodyGetAngularVel(ode_->bodies[body]));
}

double PhysicsWorld::mass_kg(BodyId body) const {
  dMass m;
  dBodyGetMass(ode_->bodies[body], &m);
  return m.mass;
}

Vec3 PhysicsWorld::point_position(BodyId body, const Vec3& local) const {
  if (body == kWorld) return local;
  dVector3 out;
  dBodyGetRelPointPos(ode_->bodies[body], local.x, local.y, local.z, out);
  return to_vec(out);
}

Vec3 PhysicsWorld::point_velocity(BodyId body, const Vec3& local) const {
  if (body == kWorld) return {};
  dVector3 out;
  dBodyGetRelPointVel(ode_->bodies[body], local.x, local.y, local.z, out);
  return to_vec(out);
}

void PhysicsWorld::add_force_at(BodyId body, const Vec3& p, const Vec3& f) {
  if (body == kWorld) return;
  dBodyAddForceAtPos(ode_->bodies[body], f.x, f.y, f.z, p.x, p.y, p.z);
}

void PhysicsWorld::set_position(BodyId body, const Vec3& p) {
  dBodySetPosition(ode_->bodies[body], p.x, p.y, p.z);
}
void PhysicsWorld::set_linear_velocity(BodyId body, const Vec3& v) {
  dBodySetLinearVel(ode_->bodies[body], v.x, v.y, v.z);
}

void PhysicsWorld::step(double dt_s) {
  step_s_ = dt_s;
  // contacts: every colliding geometry pair in the simple space's fixed order
  contact_count_ = 0;
  dSpaceCollide(ode_->space, ode_.get(), [](void* data, dGeomID g1, dGeomID g2) {
    auto* ode = static_cast<Ode*>(data);
    const WorldSettings& s = ode->owner->settings_;
    dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
    if (!b1 && !b2) return;
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
    std::vector<dContact>& contacts = ode->contact_buffer;  // reused: no allocation per colliding pair
    contacts.resize(static_cast<std::size_t>(s.max_contacts_per_pair));
    const int n = dCollide(g1, g2, s.max_contacts_per_pair, &contacts[0].geom, sizeof(dContact));
    // a pair touching now that did not touch last step is an impact: closing speed along the normal
    PhysicsWorld& self = *ode->owner;
    const BodyId id1 = b1 ? static_cast<BodyId>(reinterpret_cast<std::intptr_t>(dBodyGetData(b1))) : kWorld;
    const BodyId id2 = b2 ? static_cast<BodyId>(reinterpret_cast<std::intptr_t>(dBodyGetData(b2))) : kWorld;
    if (n > 0) {
      const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(id1)) << 32) |
                                static_cast<std::uint32_t>(id2);
      const auto last = self.last_touch_.find(key);
      const auto rearm = static_cast<std::int64_t>(s.impact_rearm_s / self.step_s_);
      if (last == self.last_touch_.end() || self.step_count_ - last->second > rearm) {
        const dContactGeom& g = contacts[0].geom;
        dVector3 v1{0, 0, 0, 0}, v2{0, 0, 0, 0};
        if (b1) dBodyGetPointVel(b1, g.pos[0], g.pos[1], g.pos[2], v1);
        if (b2) dBodyGetPointVel(b2, g.pos[0], g.pos[1], g.pos[2], v2);
        const double closing = std::abs((v1[0] - v2[0]) * g.normal[0] + (v1[1] - v2[1]) * g.normal[1] +
                                        (v1[2] - v2[2]) * g.normal[2]);
        self.impacts_.push_back({id1, id2, closing, {g.pos[0], g.pos[1], g.pos[2]}});
      }
      self.last_touch_[key] = self.step_count_;
    }
    for (int i = 0; i < n; ++i) {
      dContact& c = contacts[static_cast<std::size_t>(i)];
      c.surface.mode = dContactSoftERP | dContactSoftCFM | dContactApprox1;
      c.surface.mu = s.contact_friction;
      c.surface.soft_erp = s.contact_erp;
      c.surface.soft_cfm = s.contact_cfm;
      dJointAttach(dJointCreateContact(ode->world, ode->contacts, &c), b1, b2);
    }
    ode->owner->contact_count_ += n;
  });
  dWorldStep(ode_->world, dt_s);
  dJointGroupEmpty(ode_->contacts);
  ++step_count_;
}

std::vector<ImpactEvent> PhysicsWorld::take_impacts() {
  std::vector<ImpactEvent> out;
  out.swap(impacts_);
  return out;
}

std::uint64_t PhysicsWorld::state_hash() const {
  core::StateHash hash;
  for (dBodyID b : ode_->bodies) {
    hash.add_bytes(dBodyGetPosition(b), 3 * sizeof(dReal));
    hash.add_bytes(dBodyGetQuaternion(b), 4 * sizeof(dReal));
    hash.add_bytes(dBodyGetLinearVel(b), 3 * sizeof(dReal));
    hash.add_bytes(dBodyGetAngularVel(b), 3 * sizeof(dReal));
  }
  return hash.value();
}

}  // namespace harbour::physics
