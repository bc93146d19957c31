#include "harbour/sim/Machine.h"

#include <array>

namespace harbour::sim {

namespace {

// the rope points the snapshot's polylines use so far
std::size_t points_used(const scene::Snapshot& s) {
  return s.rope_count > 0 ? s.rope_first[static_cast<std::size_t>(s.rope_count - 1)] +
                                s.rope_points[static_cast<std::size_t>(s.rope_count - 1)]
                          : 0;
}

}  // namespace

void publish_polyline(std::span<const core::Vec3> points, scene::Snapshot& s) {
  if (s.rope_count >= scene::kMaxRopes) return;
  std::size_t used = points_used(s);
  const auto line = static_cast<std::size_t>(s.rope_count++);
  s.rope_first[line] = static_cast<std::uint16_t>(used);
  for (std::size_t p = 0; p < points.size() && used < scene::kMaxRopePoints; ++p)
    s.points[used++] = points[p];
  s.rope_points[line] = static_cast<std::uint16_t>(used - s.rope_first[line]);
}

void publish_ropes(const cable::HoistSystem& hoist, scene::Snapshot& s) {
  std::size_t used = points_used(s);
  for (int r = 0; r < hoist.rope_count() && s.rope_count < scene::kMaxRopes; ++r) {
    const auto rope = static_cast<std::size_t>(s.rope_count++);
    s.rope_first[rope] = static_cast<std::uint16_t>(used);
    for (int g = 0; g < hoist.segment_count(r); ++g) {
      // consecutive segments share their end at a sheave: drop the repeated point
      const int skip = g > 0 ? 1 : 0;
      std::array<core::Vec3, 64> points;
      const int k = hoist.polyline(r, g, points);
      for (int p = skip; p < k && used < scene::kMaxRopePoints; ++p)
        s.points[used++] = points[static_cast<std::size_t>(p)];
    }
    s.rope_points[rope] = static_cast<std::uint16_t>(used - s.rope_first[rope]);
  }
}

Telemetry Machine::telemetry() const {
  const MachineTally t = tally();
  return {core::length(t.swing_m), 0.0, t.axes};
}

}  // namespace harbour::sim
