#pragma once

#include <cstdint>
#include <vector>

#include "harbour/core/StateArchive.h"
#include "harbour/core/Vec3.h"
#include "harbour/physics/PhysicsWorld.h"

namespace harbour::sim {

/// The other members' machines of a team session as this simulation's obstacles: each a kinematic box
/// (another station's tractor, trailer or spreader) that this machine can hit and that pushes it, moved only
/// by TeamInput::kObstacleAt — where its station has it, carried on at its velocity between inputs. Made as
/// the inputs first name them (slot by slot, in slot order), so a simulation that never joined a team has
/// none and hashes as before; a box of zero size is gone (its member left) and touches nothing.
class TeamObstacles {
 public:
  static constexpr int kMostObstacles = 32;
  explicit TeamObstacles(physics::PhysicsWorld& world) : world_(world) {}
  /// Obstacle `slot` (made with every slot before it where they are not yet) of `half_extents_m` (zero: gone)
  /// at `pose` (its centre), moving so.
  void set(int slot, const core::Vec3& half_extents_m, const core::Pose& pose, const core::Vec3& velocity_mps,
           const core::Vec3& angular_velocity_radps);
  int count() const { return static_cast<int>(obstacles_.size()); }
  core::Vec3 half_extents_m(int slot) const {
    return obstacles_[static_cast<std::size_t>(slot)].half_extents_m;
  }
  core::Pose pose(int slot) const { return world_.pose(obstacles_[static_cast<std::size_t>(slot)].body); }
  /// Their sizes, written before the physics' state: a restored simulation makes its obstacles before the
  /// physics' bodies are restored.
  void save_sizes(core::StateWriter& out) const;
  void restore_sizes(core::StateReader& in);
  void hash_into(core::StateHash& hash) const;

 private:
  struct Obstacle {
    physics::BodyId body = physics::kWorld;
    physics::ShapeId shape;
    core::Vec3 half_extents_m;  // zero: gone
  };
  void make(int slots);
  void resize(Obstacle& o, const core::Vec3& half_extents_m);
  physics::PhysicsWorld& world_;
  std::vector<Obstacle> obstacles_;
};

}  // namespace harbour::sim
