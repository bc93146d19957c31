// The procedural models on their own: their geometry measured against the standards and sizes they are
// drawn from.
#include "harbour/ig/Models.h"
#include "harbour/ig/Structures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace harbour::ig {
namespace {

struct Extent {
  osg::Vec3 low{1e9f, 1e9f, 1e9f}, high{-1e9f, -1e9f, -1e9f};
};

Extent extent_of(const osg::Geometry& g) {
  Extent e;
  const auto& v = *static_cast<const osg::Vec3Array*>(g.getVertexArray());
  for (const osg::Vec3& p : v)
    for (int k = 0; k < 3; ++k) {
      e.low[k] = std::min(e.low[k], p[k]);
      e.high[k] = std::max(e.high[k], p[k]);
    }
  return e;
}

// the triangles' corners whose facet faces `normal` (within a few degrees), with their colours
template <typename Keep>
std::vector<std::pair<osg::Vec3, osg::Vec4>> facing(const osg::Geometry& g, const osg::Vec3& normal,
                                                    Keep keep) {
  const auto& v = *static_cast<const osg::Vec3Array*>(g.getVertexArray());
  const auto& n = *static_cast<const osg::Vec3Array*>(g.getNormalArray());
  const auto& c = *static_cast<const osg::Vec4Array*>(g.getColorArray());
  std::vector<std::pair<osg::Vec3, osg::Vec4>> out;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (n[k] * normal > 0.995f && keep(v[k])) out.emplace_back(v[k], c[k]);
  return out;
}

TEST(Models, AFortyFootContainerFillsItsIsoBoxWithItsCastingsAtTheCorners) {
  const core::Vec3 size{12.192, 2.438, 2.591};  // ISO 668 1AA
  const osg::ref_ptr<osg::Geometry> box = iso_container(size, {0.7f, 0.1f, 0.1f, 1.0f});
  const Extent e = extent_of(*box);
  for (int k = 0; k < 3; ++k) {  // the castings reach the box's faces, nothing sticks out
    const double half = (k == 0 ? size.x : k == 1 ? size.y : size.z) / 2.0;
    EXPECT_NEAR(e.high[k], half, 0.002) << "axis " << k;
    EXPECT_NEAR(e.low[k], -half, 0.002) << "axis " << k;
    EXPECT_LE(e.high[k], half);
    EXPECT_GE(e.low[k], -half);
  }
  // every top face at the box's top is a casting's (the roof and rails lie lower): four castings, each
  // 178 mm along and 162 mm across (ISO 1161)
  const float top = static_cast<float>(size.z / 2.0);
  const auto tops = facing(*box, {0, 0, 1}, [&](const osg::Vec3& p) { return p.z() > top - 0.002f; });
  std::set<std::pair<int, int>> corners;
  for (const auto& [p, colour] : tops) {
    EXPECT_GT(std::abs(p.x()), size.x / 2 - 0.178 - 1e-3) << "a top face away from the corners";
    EXPECT_GT(std::abs(p.y()), size.y / 2 - 0.162 - 1e-3) << "a top face away from the corners";
    corners.insert({p.x() > 0 ? 1 : -1, p.y() > 0 ? 1 : -1});
  }
  EXPECT_EQ(corners.size(), 4u);
  std::printf("40 ft container: %u triangles\n", box->getVertexArray()->getNumElements() / 3);
  EXPECT_LT(box->getVertexArray()->getNumElements() / 3, 4000u);  // cheap enough to repeat in a stack
}

TEST(Models, AContainersSideWallIsCorrugatedOnItsPitch) {
  const core::Vec3 size{6.058, 2.438, 2.591};  // ISO 668 1CC
  const osg::ref_ptr<osg::Geometry> box = iso_container(size, {0.1f, 0.25f, 0.6f, 1.0f});
  const float side = static_cast<float>(size.y / 2.0);
  // the +y wall's facets facing straight out: crests 12 mm inside the frame's face, valleys 36 mm deeper
  std::set<int> crest_starts, valleys;
  for (const auto& [p, colour] :
       facing(*box, {0, 1, 0}, [&](const osg::Vec3& p) { return std::abs(p.x()) < size.x / 2 - 0.2; })) {
    const float depth = side - p.y();
    if (std::abs(depth - 0.012f) < 1e-4f) crest_starts.insert(static_cast<int>(std::lround(p.x() * 1000)));
    if (std::abs(depth - 0.048f) < 1e-4f) valleys.insert(static_cast<int>(std::lround(p.x() * 1000)));
  }
  // between the posts (178 mm castings at each end) whole 278 mm pitches: their valleys' edges
  const int pitches = static_cast<int>((size.x - 2 * 0.178) / 0.278);
  EXPECT_EQ(valleys.size(), 2u * pitches);
  std::vector<int> sorted(valleys.begin(), valleys.end());
  for (std::size_t k = 2; k < sorted.size(); k += 2)
    EXPECT_NEAR(sorted[k] - sorted[k - 2], 278, 1) << "the pitch";
  for (std::size_t k = 1; k < sorted.size(); k += 2)
    EXPECT_NEAR(sorted[k] - sorted[k - 1], 70, 1) << "a valley's width";
}

TEST(Models, AContainersDoorsCarryFourLockingBarsInTheirHardwareColour) {
  const core::Vec3 size{12.192, 2.438, 2.896};  // 1AAA, a high cube
  const osg::Vec4 paint{0.15f, 0.45f, 0.2f, 1.0f};
  const osg::ref_ptr<osg::Geometry> box = iso_container(size, paint);
  // facing out of the door end (-x), 17 mm inside the castings' end faces (53 mm proud of the leaves), in
  // grey: the bars' faces, 36 mm wide, at four places across, running most of the door's height
  std::set<int> edges_mm;
  float low = 1e9f, high = -1e9f;
  for (const auto& [p, colour] : facing(*box, {-1, 0, 0}, [&](const osg::Vec3& p) {
         return std::abs(p.x() - (-size.x / 2 + 0.017)) < 1e-3;
       })) {
    EXPECT_NEAR(colour.r(), colour.g(), 0.05f) << "grey, not the paint";
    edges_mm.insert(static_cast<int>(std::lround(p.y() * 1000)));
    low = std::min(low, p.z());
    high = std::max(high, p.z());
  }
  ASSERT_EQ(edges_mm.size(), 8u);
  const std::vector<int> edges(edges_mm.begin(), edges_mm.end());
  for (std::size_t k = 0; k < 8; k += 2)
    EXPECT_EQ(edges[k + 1] - edges[k], 36);
  EXPECT_GT(high - low, 0.85 * size.z);
}

TEST(Models, ATyreTurnsAboutItsWidthAndReachesItsDiameterOnlyAtTheLugs) {
  EXPECT_EQ(tyre_axis({0.6, 1.6, 1.6}), 0);
  EXPECT_EQ(tyre_axis({1.1, 0.4, 1.1}), 1);
  EXPECT_EQ(tyre_axis({1.6, 0.6, 1.5}), -1);
  const osg::Vec4 rubber{0.08f, 0.08f, 0.08f, 1.0f}, rim{0.9f, 0.8f, 0.1f, 1.0f};
  const osg::ref_ptr<osg::Geometry> lugged = tyre({0.6, 1.6, 1.6}, rubber, rim, 36);
  const osg::ref_ptr<osg::Geometry> smooth = tyre({0.6, 1.6, 1.6}, rubber, rim, 12);
  const Extent e = extent_of(*lugged);
  EXPECT_NEAR(e.high.x() - e.low.x(), 0.6, 1e-4);
  EXPECT_NEAR(e.high.y(), 0.8, 1e-3);
  EXPECT_NEAR(e.high.z(), 0.8, 1e-3);
  // the tread's lugs stand 6 % of the radius proud of its base; the far level has none
  const auto& v = *static_cast<const osg::Vec3Array*>(lugged->getVertexArray());
  int at_full = 0, at_base = 0;
  for (const osg::Vec3& p : v) {
    const float r = std::hypot(p.y(), p.z());
    at_full += std::abs(r - 0.8f) < 1e-4f;
    at_base += std::abs(r - 0.8f * 0.94f) < 1e-4f;
  }
  EXPECT_GT(at_full, 36 * 4);
  EXPECT_GT(at_base, 36 * 4);
  EXPECT_LT(extent_of(*smooth).high.y(), 0.8f * 0.95f);
  EXPECT_LT(smooth->getVertexArray()->getNumElements(), lugged->getVertexArray()->getNumElements() / 3);
  // the rim's dish faces out on both sides in its own colour
  for (const float side : {-1.0f, 1.0f}) {
    const auto dish = facing(*lugged, {side, 0, 0}, [](const osg::Vec3&) { return true; });
    EXPECT_TRUE(std::any_of(dish.begin(), dish.end(), [&](const auto& pc) { return pc.second == rim; }));
  }
}

// A feeder's hull (150 x 23 m, 11.5 m deep): its full beam amidships, a stem at the bow, a transom 0.6 of
// the beam at the stern's deck, antifouling under the waterline and the topsides' paint above it.
TEST(Models, AHullHasItsBeamAmidshipsAStemAtTheBowAndATransomAtTheStern) {
  const core::Vec3 size{23.0, 150.0, 11.5};
  const osg::Vec4 topsides{0.15f, 0.22f, 0.35f, 1.0f}, bottom{0.55f, 0.12f, 0.10f, 1.0f},
      deck{0.4f, 0.2f, 0.15f, 1.0f};
  const osg::ref_ptr<osg::Geometry> g = hull(size, topsides, bottom, 7.0, deck);
  const Extent e = extent_of(*g);
  EXPECT_NEAR(e.high.x(), 11.5, 1e-4);
  EXPECT_NEAR(e.low.x(), -11.5, 1e-4);
  EXPECT_NEAR(e.high.y(), 75.0, 1e-4);
  EXPECT_NEAR(e.low.y(), -75.0, 1e-4);
  EXPECT_NEAR(e.low.z(), -5.75, 1e-4);
  EXPECT_NEAR(e.high.z(), 5.75, 1e-4);
  // the widest point at each end, at deck height
  const auto& v = *static_cast<const osg::Vec3Array*>(g->getVertexArray());
  const auto& c = *static_cast<const osg::Vec4Array*>(g->getColorArray());
  float bow = 0.0f, stern = 0.0f;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (std::abs(v[k].y() - 75.0f) < 1e-3f) bow = std::max(bow, std::abs(v[k].x()));
    if (std::abs(v[k].y() + 75.0f) < 1e-3f && v[k].z() > 5.7f) stern = std::max(stern, std::abs(v[k].x()));
    // painted by height: under the waterline (7 m up from the keel) the bottom's colour, above it the
    // topsides' (or the deck's, at the top)
    const float waterline = -5.75f + 7.0f;
    if (v[k].z() < waterline - 1e-3f) {
      EXPECT_EQ(c[k], bottom);
    } else if (v[k].z() > waterline + 1e-3f) {
      EXPECT_TRUE(c[k] == topsides || c[k] == deck);
    }
  }
  EXPECT_LT(bow, 0.01f) << "the stem";
  EXPECT_NEAR(stern, 0.6f * 11.5f, 0.01f) << "the transom";
  // open (no deck colour): nothing faces up at the deck's height
  const osg::ref_ptr<osg::Geometry> open = hull(size, topsides, bottom, 7.0, {0, 0, 0, 0});
  EXPECT_TRUE(facing(*open, {0, 0, 1}, [](const osg::Vec3& p) { return p.z() > 5.7f; }).empty());
  EXPECT_FALSE(facing(*g, {0, 0, 1}, [](const osg::Vec3& p) { return p.z() > 5.7f; }).empty());
  // a bulk carrier's: its deck open over the holds from -36 to +36 m, decked fore and aft of them
  const osg::ref_ptr<osg::Geometry> holds = hull(size, topsides, bottom, 7.0, deck, -36.0, 36.0);
  const auto deck_at = [&](float from, float to) {
    return facing(*holds, {0, 0, 1},
                  [&](const osg::Vec3& p) { return p.z() > 5.7f && p.y() > from && p.y() < to; });
  };
  EXPECT_TRUE(deck_at(-35.9f, 35.9f).empty());
  EXPECT_FALSE(deck_at(36.1f, 75.0f).empty());
  EXPECT_FALSE(deck_at(-75.0f, -36.1f).empty());
}

// EN ISO 14122-3: a stair's rises equal and at most 250 mm, its stride g + 2h 600-660 mm, its handrail
// 0.9-1.0 m above the pitch line. Measured on the drawn treads (their grating tops) and stanchions.
TEST(Structures, AFlightsStepsAndHandrailFollowEnIso14122) {
  for (const core::Vec3 size :
       {core::Vec3{4.0, 1.0, 3.25}, core::Vec3{3.0, 0.8, 3.0}, core::Vec3{6.0, 1.2, 3.0}}) {
    const osg::ref_ptr<osg::Geometry> flight = stairs(size, {0.9f, 0.7f, 0.1f, 1.0f});
    // the treads' tops: up-facing faces in the grating's colour
    std::set<int> heights_mm;
    for (const auto& [p, colour] : facing(*flight, {0, 0, 1}, [](const osg::Vec3&) { return true; }))
      if (std::abs(colour.r() - 0.55f) < 0.01f)
        heights_mm.insert(static_cast<int>(std::lround(p.z() * 1000)));
    const int rises = static_cast<int>(heights_mm.size());
    ASSERT_GE(rises, 10) << size.x << " x " << size.z;
    EXPECT_EQ(*heights_mm.rbegin(), static_cast<int>(std::lround(size.z * 500)));  // the last at the top
    const double rise = size.z / rises, going = size.x / rises;
    int previous = static_cast<int>(std::lround(-size.z * 500));
    for (const int h : heights_mm) {  // every rise the same
      EXPECT_NEAR(h - previous, rise * 1000, 1.5);
      previous = h;
    }
    EXPECT_LE(rise, access::kLargestRise_m);
    EXPECT_GE(going + 2 * rise, access::kStepLengthLow_m);
    EXPECT_LE(going + 2 * rise, access::kStepLengthHigh_m);
    // the stanchion at the foot: its top 0.95 m over the first nose (x = -run/2, one rise up)
    const float nose = static_cast<float>(-size.z / 2 + rise), foot = static_cast<float>(-size.x / 2);
    const auto tops = facing(*flight, {0, 0, 1}, [&](const osg::Vec3& p) {
      return std::abs(p.x() - foot) < 0.03f && p.z() > nose + 0.5f;
    });
    ASSERT_FALSE(tops.empty());
    float top = -1e9f;
    for (const auto& t : tops)
      top = std::max(top, t.first.z());
    EXPECT_GE(top - nose, 0.9f);
    EXPECT_LE(top - nose, 1.0f);
  }
}

// A walkway's guard-rail (EN ISO 14122-3): the handrail at the walkway's height (1.1 m), a knee rail and a
// toe board leaving no gap over 0.5 m, stanchions at most 1.5 m apart, on the sides asked for.
TEST(Structures, AWalkwaysGuardRailFollowsEnIso14122) {
  const core::Vec3 size{10.0, 1.0, 1.1};
  const osg::ref_ptr<osg::Geometry> one_side = walkway(size, RailSides::kPlus, {0.9f, 0.7f, 0.1f, 1.0f});
  const Extent e = extent_of(*one_side);
  EXPECT_NEAR(e.high.z() - (-0.55f), 1.1f, 1e-4);  // the handrail's top over the deck (the box's bottom)
  // the rails' undersides and tops over the deck, across the +y edge: handrail, knee rail, toe board
  std::vector<float> levels;
  for (const osg::Vec3 normal : {osg::Vec3(0, 0, 1), osg::Vec3(0, 0, -1)})
    for (const auto& [p, colour] : facing(*one_side, normal, [](const osg::Vec3&) { return true; }))
      if (p.y() > 0.3f && p.z() > -0.54f) levels.push_back(p.z() + 0.55f);
  levels.push_back(0.0f);
  std::sort(levels.begin(), levels.end());
  levels.erase(
      std::unique(levels.begin(), levels.end(), [](float a, float b) { return std::abs(a - b) < 1e-3f; }),
      levels.end());
  for (std::size_t k = 0; k + 1 < levels.size(); ++k)
    EXPECT_LE(levels[k + 1] - levels[k], access::kLargestRailGap_m + 1e-4) << "between " << levels[k];
  EXPECT_GE(levels.size(), 6u);  // deck, toe board's top, knee rail's two faces, handrail's two faces
  // stanchions: upright members' x-facing sides along the rail, spaced at most 1.5 m
  std::set<int> posts_cm;
  for (const auto& [p, colour] :
       facing(*one_side, {1, 0, 0}, [](const osg::Vec3& q) { return q.z() > 0.0f; }))
    posts_cm.insert(static_cast<int>(std::lround(p.x() * 100)));
  std::vector<int> xs(posts_cm.begin(), posts_cm.end());
  ASSERT_GE(xs.size(), 8u);
  for (std::size_t k = 0; k + 1 < xs.size(); ++k)
    EXPECT_LE(xs[k + 1] - xs[k], 150);
  // only on the +y side
  EXPECT_TRUE(
      facing(*one_side, {0, 0, 1}, [](const osg::Vec3& q) { return q.y() < 0.0f && q.z() > -0.5f; }).empty());
}

// A box girder: its stiffeners stand on both webs at every diaphragm, whole bays, none at the plated ends.
TEST(Structures, ABoxGirdersStiffenersMarkItsDiaphragms) {
  const core::Vec3 size{48.5, 1.6, 3.0};
  const osg::ref_ptr<osg::Geometry> girder = box_girder(size, 5.0, {0.85f, 0.3f, 0.1f, 1.0f});
  // faces standing out of the webs (beyond y = 0.8, short of the flanges' outstands at 0.864)
  for (const float side : {-1.0f, 1.0f}) {
    std::set<int> stations_cm;
    for (const auto& [p, colour] : facing(*girder, {0, side, 0}, [&](const osg::Vec3& q) {
           return side * q.y() > 0.8f + 1e-3f && side * q.y() < 0.85f;  // not the flanges' edges
         }))
      stations_cm.insert(static_cast<int>(std::lround(p.x() * 100 / 2)) * 2);
    // each stiffener's outer face has its two edges 12 cm apart: pair them into centres
    std::vector<int> edges(stations_cm.begin(), stations_cm.end());
    ASSERT_EQ(edges.size(), 18u) << "nine stiffeners on a web (10 bays of 4.85 m)";
    for (std::size_t k = 0; k + 2 < edges.size(); k += 2)
      EXPECT_NEAR((edges[k + 2] + edges[k + 3]) / 2.0 - (edges[k] + edges[k + 1]) / 2.0, 485.0, 2.5);
  }
  const Extent e = extent_of(*girder);
  EXPECT_NEAR(e.high.x(), 24.25f, 1e-4);
  EXPECT_NEAR(e.high.z(), 1.5f, 1e-4);
}

TEST(Structures, AStairCountsTheRisesTheStrideRuleAsks) {
  EXPECT_EQ(stair_rises(4.0, 3.25), 17);  // 191 mm rises, 235 mm goings: 618 mm (16 rises: 656 mm)
  EXPECT_EQ(stair_rises(3.0, 3.0), 14);   // 45 degrees: 214 mm, 643 mm (15 rises: 600 mm)
  EXPECT_EQ(stair_rises(6.0, 3.0), 19);   // 27 degrees: 158 mm rises, 316 mm goings: 632 mm
}

// A festoon's loop: a parabola whose arc is the cable's length. Taut at a span of the cable's length, half
// the cable deep where the carriers meet, and for a shallow loop the parabola's series L = s + 8d^2/(3s).
TEST(Structures, AFestoonsLoopHangsByItsCablesLength) {
  EXPECT_NEAR(festoon_sag(5.0, 5.0), 0.0, 1e-9);
  EXPECT_NEAR(festoon_sag(0.0, 5.0), 2.5, 1e-9);
  EXPECT_NEAR(festoon_sag(0.01, 5.0), 2.5, 0.01);
  const double span = 10.0, shallow = 10.05;  // d = sqrt(3 s (L - s) / 8)
  EXPECT_NEAR(festoon_sag(span, shallow), std::sqrt(3.0 * span * (shallow - span) / 8.0), 0.005);
  double previous = 0.0;
  for (const double s : {4.5, 3.0, 2.0, 1.0, 0.5}) {  // deeper as the carriers close in
    const double d = festoon_sag(s, 5.0);
    EXPECT_GT(d, previous);
    previous = d;
  }
  // the drawn loop's polyline is the cable's length (a fine one: the chords fall short of the arc)
  const std::vector<osg::Vec3> loop = festoon_loop({0, 0, 0}, {2.0f, 0, 0}, 5.0, 401);
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < loop.size(); ++k)
    length += (loop[k + 1] - loop[k]).length();
  EXPECT_NEAR(length, 5.0, 0.005);
  EXPECT_NEAR(loop[200].z(), -festoon_sag(2.0, 5.0), 1e-5);
}

}  // namespace
}  // namespace harbour::ig
