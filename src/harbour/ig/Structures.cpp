#include "harbour/ig/Structures.h"

#include "harbour/ig/Materials.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace harbour::ig {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// the axis (0 x, 1 y, 2 z) of a box's longest side; of its longer level side where `level`
int longest_axis(const core::Vec3& size_m, bool level) {
  if (level) return size_m.x >= size_m.y ? 0 : 1;
  if (size_m.x >= size_m.y && size_m.x >= size_m.z) return 0;
  return size_m.y >= size_m.z ? 1 : 2;
}

osg::Vec3 unit(int axis) {
  osg::Vec3 v;
  v[axis] = 1.0f;
  return v;
}

// hot-dip galvanised grating and a walkway's toe boards
const osg::Vec4 kGrating = finished(osg::Vec4(0.55f, 0.56f, 0.55f, 1.0f), Surface::kGalvanised);

// a guard-rail's members: handrail, knee rail and toe board along a deck edge from `a` to `b` (the deck's
// surface), stanchions at most 1.5 m apart, the rail `height` high, its members `bar` thick
void guard_rail(MeshBuilder& mesh, const osg::Vec3& a, const osg::Vec3& b, float height, float bar,
                const osg::Vec4& paint) {
  const osg::Vec3 up(0.0f, 0.0f, 1.0f);
  const float length = (b - a).length();
  const int spans = std::max(1, static_cast<int>(std::ceil(length / access::kLargestPostSpacing_m - 1e-4)));
  for (int k = 0; k <= spans; ++k) {
    const osg::Vec3 foot = a + (b - a) * (static_cast<float>(k) / static_cast<float>(spans));
    beam(mesh, foot, foot + up * height, bar, bar, paint);
  }
  beam(mesh, a + up * (height - bar / 2), b + up * (height - bar / 2), bar, bar, paint);  // handrail
  beam(mesh, a + up * (height / 2), b + up * (height / 2), bar, bar, paint);              // knee rail
  const float toe = static_cast<float>(access::kToeBoardHeight_m);
  beam(mesh, a + up * (toe / 2), b + up * (toe / 2), 0.02f, toe, kGrating);  // toe board
}

}  // namespace

void beam(MeshBuilder& mesh, const osg::Vec3& a, const osg::Vec3& b, float width, float depth,
          const osg::Vec4& colour) {
  osg::Vec3 along = b - a;
  const float length = along.length();
  if (!(length > 0.0f)) return;
  along /= length;
  osg::Vec3 side = along ^ osg::Vec3(0.0f, 0.0f, 1.0f);
  if (side.length2() < 1e-6f) side = osg::Vec3(0.0f, 1.0f, 0.0f);  // upright: its width along y
  side.normalize();
  osg::Vec3 deep = side ^ along;
  deep.normalize();
  const osg::Vec3 w = side * (width / 2), d = deep * (depth / 2);
  const std::array<osg::Vec3, 4> round{w + d, -w + d, -w - d, w - d};
  for (std::size_t k = 0; k < 4; ++k) {
    const osg::Vec3 &p = round[k], &q = round[(k + 1) % 4];
    mesh.quad(a + p, a + q, b + q, b + p, p + q, colour);
  }
  mesh.quad(a + round[0], a + round[1], a + round[2], a + round[3], -along, colour);
  mesh.quad(b + round[0], b + round[1], b + round[2], b + round[3], along, colour);
}

osg::ref_ptr<osg::Geometry> box_girder(const core::Vec3& size_m, double bay_m, const osg::Vec4& paint) {
  const int along = longest_axis(size_m, false);
  // across: the level side across it (the webs face it); deep: the flanges' way (up for a level girder)
  const int across = along == 2 ? 0 : (along == 0 ? 1 : 0);
  const int deep = 3 - along - across;
  const osg::Vec3 half(static_cast<float>(size_m.x / 2), static_cast<float>(size_m.y / 2),
                       static_cast<float>(size_m.z / 2));
  const float flange = std::clamp(0.03f * 2 * half[deep], 0.02f, 0.06f);
  const float outstand = std::clamp(0.04f * 2 * half[across], 0.03f, 0.10f);
  const float stiffener_out = std::clamp(0.6f * outstand, 0.02f, 0.06f), stiffener_wide = 0.12f;
  MeshBuilder mesh;
  // the webs' box between the flanges, and the flanges standing out past the webs
  osg::Vec3 core = half;
  core[deep] -= flange;
  mesh.box(osg::Vec3(), core, paint);
  for (const float side : {-1.0f, 1.0f}) {
    osg::Vec3 centre, plate = half;
    centre[deep] = side * (half[deep] - flange / 2);
    plate[deep] = flange / 2;
    plate[across] += outstand;
    mesh.box(centre, plate, paint);
  }
  // a stiffener on each web at every diaphragm
  const float length = 2 * half[along];
  const int bays = std::max(1, static_cast<int>(std::lround(length / bay_m)));
  for (int k = 1; k < bays; ++k)
    for (const float side : {-1.0f, 1.0f}) {
      osg::Vec3 centre, bar;
      centre[along] = -half[along] + length * static_cast<float>(k) / static_cast<float>(bays);
      centre[across] = side * (half[across] + stiffener_out / 2);
      bar[along] = stiffener_wide / 2;
      bar[across] = stiffener_out / 2;
      bar[deep] = core[deep];
      mesh.box(centre, bar, paint);
    }
  return mesh.build();
}

osg::ref_ptr<osg::Geometry> walkway(const core::Vec3& size_m, RailSides rails, const osg::Vec4& paint) {
  const int along = longest_axis(size_m, true), across = 1 - along;
  const osg::Vec3 half(static_cast<float>(size_m.x / 2), static_cast<float>(size_m.y / 2),
                       static_cast<float>(size_m.z / 2));
  MeshBuilder mesh;
  constexpr float kDeck = 0.04f, kBar = 0.05f;
  osg::Vec3 deck = half;
  deck.z() = kDeck / 2;
  mesh.box(osg::Vec3(0.0f, 0.0f, -half.z() - kDeck / 2), deck, kGrating);
  for (const float side : {-1.0f, 1.0f}) {
    if (rails == RailSides::kNone || (side > 0 && rails == RailSides::kMinus) ||
        (side < 0 && rails == RailSides::kPlus))
      continue;
    osg::Vec3 a(0.0f, 0.0f, -half.z()), b = a;
    a[along] = -half[along];
    b[along] = half[along];
    a[across] = b[across] = side * (half[across] - kBar / 2);
    guard_rail(mesh, a, b, 2 * half.z(), kBar, paint);
  }
  return mesh.build();
}

int stair_rises(double run_m, double height_m) {
  const int fewest = std::max(1, static_cast<int>(std::ceil(height_m / access::kLargestRise_m - 1e-9)));
  const double ideal = 0.5 * (access::kStepLengthLow_m + access::kStepLengthHigh_m);
  int best = fewest;
  for (int n = fewest; n <= fewest * 4; ++n) {
    const double stride = (run_m + 2.0 * height_m) / n, best_stride = (run_m + 2.0 * height_m) / best;
    if (std::abs(stride - ideal) < std::abs(best_stride - ideal)) best = n;
  }
  return best;
}

osg::ref_ptr<osg::Geometry> stairs(const core::Vec3& size_m, const osg::Vec4& paint) {
  const float run = static_cast<float>(size_m.x), wide = static_cast<float>(size_m.y),
              tall = static_cast<float>(size_m.z);
  const int rises = stair_rises(run, tall);
  const float going = run / static_cast<float>(rises), rise = tall / static_cast<float>(rises);
  const float slope = rise / going;
  MeshBuilder mesh;
  constexpr float kTread = 0.04f, kStringerDeep = 0.25f, kStringerWide = 0.04f, kBar = 0.05f;
  // tread k (1..rises) spans x from -run/2 + (k-1) going to -run/2 + k going, its top k rises up
  for (int k = 1; k <= rises; ++k) {
    const float x = -run / 2 + (static_cast<float>(k) - 0.5f) * going;
    const float top = -tall / 2 + static_cast<float>(k) * rise;
    mesh.box(osg::Vec3(x, 0.0f, top - kTread / 2),
             osg::Vec3(going / 2 + 0.015f, wide / 2 - kStringerWide, kTread / 2), kGrating);
  }
  // the nose line (through the treads' front edges) and the stringers under it, from the floor to the top
  const auto nose = [&](float x) { return -tall / 2 + rise + (x + run / 2) * slope; };
  const float drop = 0.5f * kStringerDeep * std::sqrt(1.0f + slope * slope);
  const float x0 = -run / 2 - (rise - 2 * drop) / slope;  // the stringers' feet on the floor
  const float x1 = run / 2 - going;                       // the last nose, level with the top
  for (const float side : {-1.0f, 1.0f}) {
    const float y = side * (wide / 2 - kStringerWide / 2);
    beam(mesh, osg::Vec3(x0, y, nose(x0) - drop), osg::Vec3(x1, y, nose(x1) - drop), kStringerWide,
         kStringerDeep, paint);
    // the handrail 0.95 m above the nose line, its knee rail half way, stanchions from the stringer up
    const float rail = static_cast<float>(access::kStairHandrailHeight_m);
    const osg::Vec3 a(-run / 2, y, 0.0f), b(x1, y, 0.0f);
    const auto over = [&](const osg::Vec3& p, float h) { return osg::Vec3(p.x(), p.y(), nose(p.x()) + h); };
    beam(mesh, over(a, rail - kBar / 2), over(b, rail - kBar / 2), kBar, kBar, paint);
    beam(mesh, over(a, rail / 2), over(b, rail / 2), kBar, kBar, paint);
    const float along_slope = (x1 + run / 2) * std::sqrt(1.0f + slope * slope);
    const int spans =
        std::max(1, static_cast<int>(std::ceil(along_slope / access::kLargestPostSpacing_m - 1e-4)));
    for (int k = 0; k <= spans; ++k) {
      const osg::Vec3 foot = a + (b - a) * (static_cast<float>(k) / static_cast<float>(spans));
      beam(mesh, over(foot, 0.0f), over(foot, rail), kBar, kBar, paint);
    }
  }
  return mesh.build();
}

osg::ref_ptr<osg::Geometry> cylinder(const core::Vec3& size_m, int segments, const osg::Vec4& paint) {
  const Revolved drum(size_m);
  const float radius = drum.radius, half = drum.half_length;
  const auto at = [&](float theta, float r, float w) { return drum.at(theta, r, w); };
  const osg::Vec3 axle = unit(drum.axis);
  MeshBuilder mesh;
  const float step = 2.0f * kPi / static_cast<float>(segments);
  for (int k = 0; k < segments; ++k) {
    const float t0 = step * static_cast<float>(k), t1 = t0 + step;
    mesh.quad(at(t0, radius, -half), at(t1, radius, -half), at(t1, radius, half), at(t0, radius, half),
              at(t0 + step / 2, 1.0f, 0.0f), paint);
    for (const float side : {-1.0f, 1.0f})
      mesh.triangle(at(0.0f, 0.0f, side * half), at(t0, radius, side * half), at(t1, radius, side * half),
                    axle * side, paint);
  }
  return mesh.build();
}

namespace {
// a light mast's lamps: six on a ring 1.2 m round its head, each looking out and 53 degrees down
constexpr int kMastLamps = 6;
osg::Vec3 lamp_mount(int k) {
  const float t = kPi / 3 * static_cast<float>(k);
  return osg::Vec3(std::cos(t), std::sin(t), 0.0f) * 1.2f;
}
osg::Vec3 lamp_look(int k) {
  const float t = kPi / 3 * static_cast<float>(k);
  osg::Vec3 look = osg::Vec3(std::cos(t), std::sin(t), 0.0f) * 0.6f + osg::Vec3(0.0f, 0.0f, -0.8f);
  look.normalize();
  return look;
}
}  // namespace

std::vector<osg::Vec3> light_mast_lenses() {
  std::vector<osg::Vec3> lenses;
  for (int k = 0; k < kMastLamps; ++k)
    lenses.push_back(lamp_mount(k) + lamp_look(k) * 0.16f);
  return lenses;
}

osg::ref_ptr<osg::Geometry> light_mast(double height_m) {
  const float top = 0.0f, foot = -static_cast<float>(height_m);
  const osg::Vec4 steel = finished(osg::Vec4(0.60f, 0.61f, 0.60f, 1.0f), Surface::kGalvanised);
  const osg::Vec4 concrete = finished(osg::Vec4(0.42f, 0.41f, 0.39f, 1.0f), Surface::kConcrete);
  const osg::Vec4 housing = finished(osg::Vec4(0.22f, 0.23f, 0.24f, 1.0f), Surface::kPaint);
  const osg::Vec4 lens = finished(osg::Vec4(0.85f, 0.85f, 0.80f, 1.0f), Surface::kGlass);
  MeshBuilder mesh;
  constexpr float kPlinth = 0.5f;
  mesh.box(osg::Vec3(0.0f, 0.0f, foot + kPlinth / 2), osg::Vec3(0.6f, 0.6f, kPlinth / 2), concrete);
  // the pole: an octagonal frustum from the plinth to the head
  const float r0 = 0.25f, r1 = 0.11f, z0 = foot + kPlinth, z1 = top - 0.2f;
  for (int k = 0; k < 8; ++k) {
    const float t0 = kPi / 4 * static_cast<float>(k), t1 = t0 + kPi / 4, tm = t0 + kPi / 8;
    const auto ring = [](float t, float r, float z) {
      return osg::Vec3(r * std::cos(t), r * std::sin(t), z);
    };
    mesh.quad(ring(t0, r0, z0), ring(t1, r0, z0), ring(t1, r1, z1), ring(t0, r1, z1),
              osg::Vec3(std::cos(tm), std::sin(tm), 0.0f), steel);
  }
  // the head: a ring of six lamp housings looking down and out, on arms from the pole's top
  for (int k = 0; k < kMastLamps; ++k) {
    const osg::Vec3 mount = lamp_mount(k), look = lamp_look(k);
    beam(mesh, osg::Vec3(0.0f, 0.0f, top - 0.15f), mount, 0.1f, 0.1f, steel);
    beam(mesh, mount - look * 0.15f, mount + look * 0.12f, 0.7f, 0.5f, housing);
    beam(mesh, mount + look * 0.12f, mount + look * 0.14f, 0.6f, 0.4f, lens);
  }
  // a service platform inside the ring of lamps, over them, with its guard-rail, reached by a ladder up the
  // pole
  constexpr float kPlatform = 1.0f;
  const float deck = top + 0.35f;
  for (int k = 0; k < 8; ++k) {
    const float t0 = kPi / 4 * static_cast<float>(k), t1 = t0 + kPi / 4;
    const osg::Vec3 a(kPlatform * std::cos(t0), kPlatform * std::sin(t0), deck),
        b(kPlatform * std::cos(t1), kPlatform * std::sin(t1), deck);
    mesh.triangle(osg::Vec3(0.0f, 0.0f, deck), a, b, osg::Vec3(0.0f, 0.0f, 1.0f), kGrating);
    mesh.triangle(osg::Vec3(0.0f, 0.0f, deck - 0.04f), a - osg::Vec3(0, 0, 0.04f), b - osg::Vec3(0, 0, 0.04f),
                  osg::Vec3(0.0f, 0.0f, -1.0f), kGrating);
    guard_rail(mesh, a, b, static_cast<float>(access::kGuardRailHeight_m), 0.04f, steel);
  }
  constexpr float kLadderOut = 0.45f, kLadderHalf = 0.15f, kRungs = 0.28f;
  for (const float side : {-1.0f, 1.0f})
    beam(mesh, osg::Vec3(-kLadderOut, side * kLadderHalf, z0),
         osg::Vec3(-kLadderOut, side * kLadderHalf, deck), 0.06f, 0.03f, steel);
  for (float z = z0 + kRungs; z < deck; z += kRungs)
    beam(mesh, osg::Vec3(-kLadderOut, -kLadderHalf, z), osg::Vec3(-kLadderOut, kLadderHalf, z), 0.03f, 0.03f,
         steel);
  return mesh.build();
}

double festoon_sag(double span_m, double cable_m) {
  if (!(cable_m > span_m) || !(span_m > 0.0)) return span_m > 0.0 ? 0.0 : cable_m / 2.0;
  const auto arc = [&](double d) {
    return 0.5 * std::sqrt(span_m * span_m + 16.0 * d * d) +
           span_m * span_m / (8.0 * d) * std::asinh(4.0 * d / span_m);
  };
  double low = 0.0, high = cable_m / 2.0;  // the arc grows with the sag
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (low + high);
    (mid > 0.0 && arc(mid) > cable_m ? high : low) = mid;
  }
  return 0.5 * (low + high);
}

std::vector<osg::Vec3> festoon_loop(const osg::Vec3& a, const osg::Vec3& b, double cable_m, int points) {
  const float sag = static_cast<float>(festoon_sag((b - a).length(), cable_m));
  std::vector<osg::Vec3> loop;
  loop.reserve(static_cast<std::size_t>(points));
  for (int k = 0; k < points; ++k) {
    const float t = static_cast<float>(k) / static_cast<float>(points - 1);
    loop.push_back(a + (b - a) * t - osg::Vec3(0.0f, 0.0f, 4.0f * sag * t * (1.0f - t)));
  }
  return loop;
}

}  // namespace harbour::ig
