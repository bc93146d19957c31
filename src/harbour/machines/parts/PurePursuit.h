#pragma once

#include <span>

#include "harbour/core/Vec3.h"
#include "harbour/machines/parts/WheeledChassis.h"

namespace harbour::sim {

/// The ground-plane point of a polyline path `lookahead_m` on from the point nearest `from` (its last point
/// when the path ends sooner).
core::Vec3 point_ahead(std::span<const core::Vec3> path, const core::Vec3& from, double lookahead_m);

/// How far along a polyline path the ground-plane point nearest `point` lies, from its first point [m].
double distance_along(std::span<const core::Vec3> path, const core::Vec3& point);

/// Pure pursuit: the steering command [-1, 1] that puts a wheeled chassis at `pose` on the arc from its
/// reference point (the centre of its non-steered axles) through `target` (ground plane).
double pursuit_steer(const core::Pose& pose, const WheeledChassis& chassis, const core::Vec3& target);

}  // namespace harbour::sim
