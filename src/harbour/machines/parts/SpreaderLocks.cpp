#include "harbour/machines/parts/SpreaderLocks.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::sim {
namespace {
constexpr double kReachMargin_m = 0.01;  // rounding and more: the pre-check only skips boxes far out of reach
}  // namespace

void SpreaderLocks::step(physics::PhysicsWorld& world, physics::BodyId spreader, const Spreader& frame,
                         std::span<const ContainerRef> containers, const TwistlockSettings& settings,
                         bool lock, bool unlock, bool load_suspended, int faulty_corner, double dt_s) {
  // twistlock frame: on the underside, x along the spreader's length (the body's y)
  const core::Pose body = world.pose(spreader);
  core::Pose underside = body;
  underside.position = body.to_parent({0, 0, -frame.half_extents_m().z});
  underside.rotation = body.rotation * core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 2);
  std::array<bool, 4> landed{};
  std::optional<physics::BodyId> landed_on;
  // a box's castings are the same either way round: the spreader seats on it turned half a turn too
  const core::Mat3 half_turn = core::Mat3::rotation({0, 0, 1}, std::numbers::pi);
  // a pin lands within the tolerances of a casting: no pin of the spreader reaches a box whose centre lies
  // farther from the underside's centre than this (the pins' diagonal, the castings' and the box's half
  // height, with room for rounding); such a box is not looked at corner by corner
  const double pins_m = std::hypot(frame.pin_half_length_m(), frame.pin_half_width_m());
  for (const ContainerRef& box : containers) {
    core::Pose top = world.pose(box.body);
    const double castings_m =
        std::hypot(std::max(box.pocket_half_length_m, box.end_pocket_half_length_m), box.pocket_half_width_m);
    const double reach_m = pins_m + castings_m + settings.lateral_tolerance_m + settings.landed_gap_m +
                           box.half_extents_m.z + kReachMargin_m;
    const core::Vec3 apart = top.position - underside.position;
    if (core::dot(apart, apart) > reach_m * reach_m) continue;
    top.position = top.to_parent({0, 0, box.half_extents_m.z});
    const core::Pose turned{top.rotation * half_turn, top.position};
    for (const double apertures : {box.pocket_half_length_m, box.end_pocket_half_length_m}) {
      if (apertures <= 0.0) continue;
      for (const core::Pose& seat : {top, turned}) {
        auto corners = landed_corners(underside, frame.pin_half_length_m(), frame.pin_half_width_m(), seat,
                                      apertures, box.pocket_half_width_m, settings);
        if (faulty_corner >= 0 && faulty_corner < 4) corners[static_cast<std::size_t>(faulty_corner)] = false;
        if (corners[0] && corners[1] && corners[2] && corners[3]) {
          landed = corners;
          landed_on = box.body;
          break;
        }
      }
      if (landed_on) break;
    }
    if (landed_on) break;
  }
  const bool was_locked = twistlocks_.locked();
  twistlocks_.update(landed, lock, unlock, load_suspended, dt_s);
  if (!was_locked && twistlocks_.locked() && landed_on) {
    attachment_ = world.attach(spreader, *landed_on);
    locked_ = landed_on;
  } else if (was_locked && !twistlocks_.locked() && attachment_.valid()) {
    world.detach(attachment_);
    attachment_ = {};
    locked_.reset();
  }
}

template <typename Self, typename Archive>
void SpreaderLocks::archive(Self& self, Archive& ar) {
  physics::BodyId locked = self.locked_.value_or(physics::kWorld);
  ar(locked, self.attachment_);
  if constexpr (Archive::kRestoring)
    self.locked_ = locked == physics::kWorld ? std::nullopt : std::optional<physics::BodyId>(locked);
}

void SpreaderLocks::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void SpreaderLocks::restore_state(core::StateReader& in) {
  archive(*this, in);
}

}  // namespace harbour::sim
