#include "harbour/machines/parts/PurePursuit.h"

#include <algorithm>
#include <cmath>

namespace harbour::sim {
namespace {

core::Vec3 flat(core::Vec3 v) {
  v.z = 0.0;
  return v;
}

}  // namespace

core::Vec3 point_ahead(std::span<const core::Vec3> path, const core::Vec3& from_point, double lookahead_m) {
  const core::Vec3 from = flat(from_point);
  std::size_t nearest_segment = 0;
  double nearest = 1e18, nearest_t = 0.0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const core::Vec3 a = path[k], b = path[k + 1];
    const double t = std::clamp(dot(from - a, b - a) / dot(b - a, b - a), 0.0, 1.0);
    const double d = core::length(from - (a + (b - a) * t));
    if (d < nearest) nearest = d, nearest_segment = k, nearest_t = t;
  }
  double ahead = lookahead_m;
  for (std::size_t k = nearest_segment; k + 1 < path.size(); ++k) {
    const core::Vec3 a = path[k], b = path[k + 1];
    const double left = core::length(b - a) * (k == nearest_segment ? 1.0 - nearest_t : 1.0);
    const core::Vec3 start = k == nearest_segment ? a + (b - a) * nearest_t : a;
    if (ahead <= left) return start + (b - a) * (ahead / core::length(b - a));
    ahead -= left;
  }
  return path.back();
}

double distance_along(std::span<const core::Vec3> path, const core::Vec3& point) {
  const core::Vec3 from = flat(point);
  double nearest = 1e18, along = 0.0, start = 0.0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const core::Vec3 a = flat(path[k]), b = flat(path[k + 1]);
    const double length = core::length(b - a);
    const double t = std::clamp(dot(from - a, b - a) / (length * length), 0.0, 1.0);
    const double d = core::length(from - (a + (b - a) * t));
    if (d < nearest) nearest = d, along = start + t * length;
    start += length;
  }
  return along;
}

double pursuit_steer(const core::Pose& pose, const WheeledChassis& chassis, const core::Vec3& target) {
  const core::Vec3 reference = flat(pose.to_parent({chassis.reference_x_m(), 0, 0}));
  const core::Vec3 x = flat(pose.rotation.column(0));
  const core::Vec3 to = flat(target) - reference;
  const double alpha = std::atan2(x.x * to.y - x.y * to.x, x.x * to.x + x.y * to.y);
  const double steer = std::atan(2.0 * chassis.steer_base_m() * std::sin(alpha) / core::length(to)) /
                       chassis.settings().max_steer_rad;
  return std::clamp(steer, -1.0, 1.0);
}

}  // namespace harbour::sim
