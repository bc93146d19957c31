#include "harbour/machines/parts/SpreaderHoist.h"

#include <stdexcept>

#include "harbour/core/Units.h"
#include "harbour/scene/Surface.h"

namespace harbour::sim {
namespace {

// the falls: each rope's segments with an end on a headblock sheave (segment k joins path[k] and path[k+1])
std::vector<std::pair<int, int>> fall_segments(const cable::ReevingSettings& reeving, int headblock) {
  std::vector<std::pair<int, int>> falls;
  const auto on_headblock = [&](int element) {
    const cable::ElementSettings& e = reeving.elements[static_cast<std::size_t>(element)];
    return e.kind == cable::ElementKind::kSheave && e.mount.body == headblock;
  };
  for (std::size_t r = 0; r < reeving.ropes.size(); ++r) {
    const std::vector<int>& path = reeving.ropes[r].path;
    for (std::size_t k = 0; k + 1 < path.size(); ++k)
      if (on_headblock(path[k]) || on_headblock(path[k + 1]))
        falls.emplace_back(static_cast<int>(r), static_cast<int>(k));
  }
  return falls;
}

// mean position of the reeving's sheaves on one body, in its frame
core::Vec3 mean_sheave_m(const cable::ReevingSettings& reeving, int body) {
  core::Vec3 sum;
  int count = 0;
  for (const cable::ElementSettings& e : reeving.elements)
    if (e.kind == cable::ElementKind::kSheave && e.mount.body == body) {
      sum += e.mount.local;
      ++count;
    }
  return count ? sum * (1.0 / count) : core::Vec3{};
}

}  // namespace

SpreaderHoist::SpreaderHoist(physics::PhysicsWorld& world, const SpreaderHoistSettings& settings,
                             std::vector<physics::BodyId> bodies, const core::Pose& spreader_pose)
    : world_(world), settings_(settings), limits_(settings.lower_limit_m, settings.upper_limit_m) {
  if (bodies.empty() || settings.hoist.ropes.empty())
    throw std::invalid_argument("a spreader hoist needs a trolley and ropes");
  const int headblock = static_cast<int>(bodies.size());
  headblock_sheaves_m_ = mean_sheave_m(settings.hoist, headblock);
  falls_ = fall_segments(settings.hoist, headblock);
  falls_per_rope_ = static_cast<double>(falls_.size()) / static_cast<double>(settings.hoist.ropes.size());
  for (const auto& [rope, segment] : falls_) {
    const std::vector<int>& path = settings.hoist.ropes[static_cast<std::size_t>(rope)].path;
    for (const int end :
         {path[static_cast<std::size_t>(segment)], path[static_cast<std::size_t>(segment) + 1]}) {
      const cable::Mount& mount = settings.hoist.elements[static_cast<std::size_t>(end)].mount;
      if (mount.body != headblock) fall_tops_.push_back(mount);
    }
  }
  if (falls_.empty()) throw std::invalid_argument("the hoist's ropes reach no sheave on the headblock");

  // the spreader's body; its frame and flippers are shapes the Spreader resizes as it telescopes
  const SpreaderSettings& frame = settings.spreader;
  physics::BoxSettings spreader;
  spreader.mass_kg = frame.mass_kg;
  spreader.half_extents_m = {0.5 * frame.width_m, 0.5 * frame.length_m[1], 0.5 * frame.height_m};
  spreader.pose = spreader_pose;
  spreader.collides = false;
  spreader_ = world.add_box(spreader);
  frame_ =
      std::make_unique<Spreader>(world, spreader_, scene::kSurfaceSpreader, scene::kSurfaceFlipper, frame);

  bodies.push_back(spreader_);
  cable_bodies_ = std::make_unique<OdeCableBodies>(world, std::move(bodies));
  hoist_ = std::make_unique<cable::HoistSystem>(settings.hoist, *cable_bodies_,
                                                core::Vec3{0, 0, -core::kStandardGravity});
}

double SpreaderHoist::attachment_bottom_z_m() const {
  return world_.pose(spreader_).position.z - frame_->half_extents_m().z;
}

double SpreaderHoist::pendulum_length_m() const {
  // the falls' mean height at their upper ends (trolley sheaves, the drum, dead ends) over their lower ends
  double top = 0.0;
  for (const cable::Mount& m : fall_tops_)
    top += cable_bodies_->point_position(m.body, m.local).z;
  return top / static_cast<double>(fall_tops_.size()) -
         world_.pose(spreader_).to_parent(headblock_sheaves_m_).z;
}

double SpreaderHoist::hoisted_load_n() const {
  double total = 0.0;
  for (const auto& [rope, segment] : falls_)
    total += hoist_->tension(rope, segment);
  return total;
}

double SpreaderHoist::falls_weight_n() const {
  return fall_count() * pendulum_length_m() * settings_.hoist.ropes[0].mass_per_m_kg * core::kStandardGravity;
}

double SpreaderHoist::net_load_t() const {
  // a fall's tension is its mean along it: at its lower end it carries half its own weight less
  const double on_headblock_n = hoisted_load_n() - 0.5 * falls_weight_n();
  return std::max(0.0, on_headblock_n / core::kStandardGravity / 1000.0 - spreader_mass_kg() / 1000.0);
}

double SpreaderHoist::full_hoist_speed_mps() const {
  const cable::ElementSettings& drum =
      settings_.hoist.elements[static_cast<std::size_t>(settings_.hoist.ropes[0].path[0])];
  return drum.max_rope_speed_mps / falls_per_rope_;
}

void SpreaderHoist::step(const SpreaderHoistCommand& c, std::span<const ContainerRef> containers,
                         double dt_s) {
  // limit switches: slow down ahead of them so the spreader stops on them, and count a push into one
  const cable::ElementSettings& drum =
      settings_.hoist.elements[static_cast<std::size_t>(settings_.hoist.ropes[0].path[0])];
  const double spreader_z = world_.pose(spreader_).position.z;
  const double lever = limits_.limit(c.hoist, spreader_z, drum.max_rope_speed_mps / falls_per_rope_,
                                     drum.max_rope_acceleration_mps2 / falls_per_rope_, dt_s);

  // raising reels rope in (negative pay-out); the e-stop cuts the motor and sets the brake
  const cable::DrumCommand command{c.emergency_stop ? 0.0 : -lever, brake_fault_, !c.emergency_stop};
  hoist_->step(dt_s, {&command, 1}, *cable_bodies_);

  // twistlocks against the container under the spreader, if any; the load hangs when the ropes carry
  // clearly more than the empty spreader (landing pins stay pressed while a locked container hangs, so
  // "landed" alone cannot tell)
  const bool load_suspended = hoisted_load_n() > 1.3 * settings_.spreader.mass_kg * core::kStandardGravity;
  locks_.step(world_, spreader_, *frame_, containers, settings_.twistlocks, c.lock, c.unlock, load_suspended,
              landed_sensor_fault_, dt_s);
  // the telescope (interlocked while landed or locked) and flippers
  const SpreaderSize sizes[] = {SpreaderSize::k20ft, SpreaderSize::k40ft, SpreaderSize::k45ft};
  const SpreaderSize* size_button = nullptr;
  for (int k = 0; k < 3; ++k)
    if (c.spreader_size_ft == (k == 0 ? 20 : k == 1 ? 40 : 45)) size_button = &sizes[k];
  frame_->step(size_button, c.flipper_down,
               locks_.twistlocks().lamps().landed || locks_.twistlocks().locked(), dt_s);
}

void SpreaderHoist::clear_faults() {
  brake_fault_ = false;
  landed_sensor_fault_ = -1;
}

void SpreaderHoist::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void SpreaderHoist::restore_state(core::StateReader& in) {
  archive(*this, in);
}

}  // namespace harbour::sim
