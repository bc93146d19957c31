#pragma once

#include <osg/Geometry>
#include <osg/ref_ptr>

#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/ig/Models.h"

namespace harbour::ig {

/// The steelwork of the machines and the quay, built procedurally from the box each piece fills: box girders,
/// walkways and stairs with their guard-rails, members between two points, cylinders, light masts. Access
/// ways follow EN ISO 14122-3 (permanent means of access to machinery: stairs and guard-rails).
namespace access {
inline constexpr double kGuardRailHeight_m = 1.1;     ///< a platform's handrail above its deck (minimum)
inline constexpr double kLargestRailGap_m = 0.5;      ///< clear gap between handrail, knee rail and toe board
inline constexpr double kToeBoardHeight_m = 0.1;      ///< toe board (minimum)
inline constexpr double kLargestPostSpacing_m = 1.5;  ///< stanchions' spacing
inline constexpr double kLargestRise_m = 0.25;        ///< a stair's rise h
inline constexpr double kStairHandrailHeight_m = 0.95;  ///< above the pitch line (0.9-1.0 m)
inline constexpr double kStepLengthLow_m = 0.60;        ///< the stride rule: 0.60 <= g + 2h <= 0.66 m
inline constexpr double kStepLengthHigh_m = 0.66;
inline constexpr double kSteepestStair_deg = 45.0;  ///< steeper: a stepladder
inline constexpr double kFlattestStair_deg = 20.0;  ///< flatter: a ramp
}  // namespace access

/// A beam of `width` x `depth` section from `a` to `b` (a box turned along them; its depth in the upright
/// plane through them, across for an upright member).
void beam(MeshBuilder& mesh, const osg::Vec3& a, const osg::Vec3& b, float width, float depth,
          const osg::Vec4& colour);

/// A welded box girder filling a box of `size_m` round the origin, along its longest side: flanges, webs, the
/// flanges' outstands past the webs, and on each web a flat-bar stiffener at every diaphragm (`bay_m` apart,
/// whole bays, none at the ends, which are plated).
osg::ref_ptr<osg::Geometry> box_girder(const core::Vec3& size_m, double bay_m, const osg::Vec4& paint);

/// Which long sides of a walkway have a guard-rail: both, the one towards +across, towards -across, none (a
/// landing between flights).
enum class RailSides { kBoth, kPlus, kMinus, kNone };

/// A walkway filling a box of `size_m` round the origin, along its longer level side: a grating deck at its
/// bottom and guard-rails `size_m.z` high (EN ISO 14122-3: at least 1.1 m) on `rails`: handrail, knee rail at
/// half height, a toe board, stanchions at most 1.5 m apart; the deck drawn in `paint` darkened.
osg::ref_ptr<osg::Geometry> walkway(const core::Vec3& size_m, RailSides rails, const osg::Vec4& paint);

/// The rises a flight of stairs `run_m` long and `height_m` high is built with: rise at most 0.25 m and, of
/// those counts, the one whose stride g + 2h is nearest 0.63 m (EN ISO 14122-3).
int stair_rises(double run_m, double height_m);

/// A flight of stairs filling a box of `size_m` round the origin, climbing along +x from its bottom at -x to
/// its top at +x, `size_m.y` wide: grating treads on two stringers, a handrail 0.95 m above the pitch line on
/// each side with stanchions at both ends and between (at most 1.5 m apart along the slope).
osg::ref_ptr<osg::Geometry> stairs(const core::Vec3& size_m, const osg::Vec4& paint);

/// A cylinder filling a box of `size_m` round the origin, its axis along the side that differs from the other
/// two (those equal: its diameter), `segments` round it, capped at both ends.
osg::ref_ptr<osg::Geometry> cylinder(const core::Vec3& size_m, int segments, const osg::Vec4& paint);

/// A floodlight's mast standing on the quay with its lamp head `height_m` up at the origin: a tapered
/// octagonal pole (0.5 m across at the foot, 0.22 m at the head) on a concrete plinth, a ring of six lamp
/// housings 1.2 m round it tilted 53 degrees down, a service platform over them inside the ring with its
/// guard-rail, and a ladder up the pole.
osg::ref_ptr<osg::Geometry> light_mast(double height_m);
/// Where the light mast's six lamps' lenses are, from its head.
std::vector<osg::Vec3> light_mast_lenses();

/// The sag of a loop of cable `cable_m` long hanging between two carriers `span_m` apart, the loop taken as a
/// parabola (arc length ½√(s² + 16d²) + (s²/8d)·asinh(4d/s)): 0 where the cable is taut, half its length
/// where the carriers meet.
double festoon_sag(double span_m, double cable_m);

/// A festoon's loop of `cable_m` hanging from `a` to `b` (at one height, or nearly): `points` along it, down
/// (-z) by festoon_sag.
std::vector<osg::Vec3> festoon_loop(const osg::Vec3& a, const osg::Vec3& b, double cable_m, int points);

}  // namespace harbour::ig
