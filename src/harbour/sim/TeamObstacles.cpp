#include "harbour/sim/TeamObstacles.h"

#include <stdexcept>

#include "harbour/scene/Surface.h"

namespace harbour::sim {

namespace {
// where an obstacle is made, before its first input places it (in the same step's inputs: slots are fed
// together), touching nothing
constexpr core::Vec3 kParked_m{0.0, 0.0, -1000.0};
// the smallest box an obstacle is made with (an ODE box has no zero side); a gone one is disabled besides
constexpr double kLeast_m = 0.01;
core::Vec3 at_least(const core::Vec3& h) {
  return {std::max(h.x, kLeast_m), std::max(h.y, kLeast_m), std::max(h.z, kLeast_m)};
}
bool gone(const core::Vec3& h) {
  return h.x <= 0.0 || h.y <= 0.0 || h.z <= 0.0;
}
}  // namespace

void TeamObstacles::make(int slots) {
  if (slots > kMostObstacles)
    throw std::invalid_argument("team obstacle past " + std::to_string(kMostObstacles));
  while (count() < slots) {
    Obstacle o;
    // one space for them all: the broad phase meets the other members' machines as one entry
    o.body = world_.add_kinematic_body({core::Mat3::identity(), kParked_m},
                                       obstacles_.empty() ? physics::kWorld : obstacles_.front().body);
    // another station's machine: hit as a vehicle is (Evaluator: a vehicle collision)
    o.shape = world_.add_box_shape(o.body, at_least({}), {}, scene::kSurfaceTruck);
    world_.set_shape_enabled(o.shape, false);
    obstacles_.push_back(o);
  }
}

void TeamObstacles::resize(Obstacle& o, const core::Vec3& half_extents_m) {
  if (half_extents_m == o.half_extents_m) return;
  o.half_extents_m = half_extents_m;
  world_.set_box_shape(o.shape, at_least(half_extents_m), {});
  world_.set_shape_enabled(o.shape, !gone(half_extents_m));
}

void TeamObstacles::set(int slot, const core::Vec3& half_extents_m, const core::Pose& pose,
                        const core::Vec3& velocity_mps, const core::Vec3& angular_velocity_radps) {
  make(slot + 1);
  Obstacle& o = obstacles_[static_cast<std::size_t>(slot)];
  resize(o, half_extents_m);
  if (gone(half_extents_m)) {  // stays where it was, still (a far one would widen the group's bounds)
    world_.set_kinematic_motion(o.body, pose, {}, {});
  } else {
    world_.set_kinematic_motion(o.body, pose, velocity_mps, angular_velocity_radps);
  }
}

void TeamObstacles::save_sizes(core::StateWriter& out) const {
  out.put(static_cast<std::int32_t>(obstacles_.size()));
  for (const Obstacle& o : obstacles_)
    out.put(o.half_extents_m);
}

void TeamObstacles::restore_sizes(core::StateReader& in) {
  const auto saved = in.get<std::int32_t>();
  if (saved < count() || saved > kMostObstacles)
    throw core::StateError("saved state has " + std::to_string(saved) + " team obstacles, this simulation " +
                           std::to_string(count()));
  make(saved);
  for (Obstacle& o : obstacles_)
    resize(o, in.get<core::Vec3>());
}

void TeamObstacles::hash_into(core::StateHash& hash) const {
  for (const Obstacle& o : obstacles_)
    hash.add(o.half_extents_m);
}

}  // namespace harbour::sim
