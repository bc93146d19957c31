#include "harbour/ig/Models.h"

#include "harbour/ig/Materials.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace harbour::ig {

MeshBuilder::MeshBuilder()
    : vertices_(new osg::Vec3Array), normals_(new osg::Vec3Array), colours_(new osg::Vec4Array) {}

void MeshBuilder::triangle(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c,
                           const osg::Vec3& outward, const osg::Vec4& colour) {
  osg::Vec3 normal = (b - a) ^ (c - a);
  if (normal.length2() == 0.0f) return;  // degenerate: nothing to draw
  normal.normalize();
  const bool turned = normal * outward < 0.0f;
  if (turned) normal = -normal;
  for (const osg::Vec3* p : {&a, turned ? &c : &b, turned ? &b : &c}) {
    vertices_->push_back(*p);
    normals_->push_back(normal);
    colours_->push_back(colour);
  }
}

void MeshBuilder::quad(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c, const osg::Vec3& d,
                       const osg::Vec3& outward, const osg::Vec4& colour) {
  triangle(a, b, c, outward, colour);
  triangle(a, c, d, outward, colour);
}

void MeshBuilder::box(const osg::Vec3& centre, const osg::Vec3& half, const osg::Vec4& colour) {
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      osg::Vec3 normal, du, dv;
      normal[axis] = side;
      du[u] = half[u];
      dv[v] = half[v];
      const osg::Vec3 face =
          centre + osg::Vec3(normal.x() * half.x(), normal.y() * half.y(), normal.z() * half.z());
      quad(face - du - dv, face + du - dv, face + du + dv, face - du + dv, normal, colour);
    }
}

void MeshBuilder::append(const osg::Geometry& geometry, const osg::Vec3& offset) {
  const auto& v = *static_cast<const osg::Vec3Array*>(geometry.getVertexArray());
  const auto& n = *static_cast<const osg::Vec3Array*>(geometry.getNormalArray());
  const auto& c = *static_cast<const osg::Vec4Array*>(geometry.getColorArray());
  for (std::size_t k = 0; k < v.size(); ++k) {
    vertices_->push_back(v[k] + offset);
    normals_->push_back(n[k]);
    colours_->push_back(c[k]);
  }
}

osg::ref_ptr<osg::Geometry> MeshBuilder::build() const {
  osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry;
  geometry->setUseDisplayList(false);
  geometry->setUseVertexBufferObjects(true);
  geometry->setVertexArray(vertices_.get());
  geometry->setNormalArray(normals_.get(), osg::Array::BIND_PER_VERTEX);
  geometry->setColorArray(colours_.get(), osg::Array::BIND_PER_VERTEX);
  geometry->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, static_cast<int>(vertices_->size())));
  return geometry;
}

namespace {

osg::Vec4 shaded(const osg::Vec4& c, float factor) {
  return {c.r() * factor, c.g() * factor, c.b() * factor, c.a()};
}

// A trapezoidal profile: crest, flank, valley, flank along one pitch (the flanks' run along the sheet).
struct Corrugation {
  float pitch, crest, flank, depth;
};
constexpr Corrugation kWallSheet{0.278f, 0.072f, 0.068f, 0.036f};  // a dry van's side and front walls
constexpr Corrugation kRoofSheet{0.300f, 0.100f, 0.050f, 0.020f};  // its roof
constexpr Corrugation kDoorSheet{0.450f, 0.150f, 0.040f, 0.025f};  // its door leaves' horizontal ribs

// A corrugated sheet from `origin` (its crest plane) running `length` along `along` (the profile) and
// across `span` (a vector), its valleys `depth` towards `inward`; whole pitches centred, flat at both ends.
void corrugated_sheet(MeshBuilder& mesh, const osg::Vec3& origin, const osg::Vec3& along, float length,
                      const osg::Vec3& span, const osg::Vec3& inward, const Corrugation& profile,
                      const osg::Vec4& colour) {
  const int pitches = static_cast<int>(length / profile.pitch);
  const float margin = (length - static_cast<float>(pitches) * profile.pitch) / 2.0f;
  std::vector<std::pair<float, float>> points{{0.0f, 0.0f}, {margin, 0.0f}};  // (along, depth)
  for (int k = 0; k < pitches; ++k) {
    const float s = margin + static_cast<float>(k) * profile.pitch;
    const float valley = profile.pitch - profile.crest - 2.0f * profile.flank;
    points.insert(points.end(), {{s + profile.crest, 0.0f},
                                 {s + profile.crest + profile.flank, profile.depth},
                                 {s + profile.crest + profile.flank + valley, profile.depth},
                                 {s + profile.pitch, 0.0f}});
  }
  points.emplace_back(length, 0.0f);
  const osg::Vec3 outward = -inward;
  for (std::size_t n = 0; n + 1 < points.size(); ++n) {
    if (points[n + 1].first - points[n].first <= 0.0f) continue;
    const osg::Vec3 a = origin + along * points[n].first + inward * points[n].second;
    const osg::Vec3 b = origin + along * points[n + 1].first + inward * points[n + 1].second;
    mesh.quad(a, b, b + span, a + span, outward, colour);
  }
}

// ISO 1161 corner casting and the frame round it [m]
constexpr float kCastingAlong = 0.178f, kCastingAcross = 0.162f, kCastingTall = 0.118f;
constexpr float kTopRail = 0.10f, kBottomRail = 0.16f, kHeader = 0.12f, kSill = 0.15f;
constexpr float kWallInset = 0.012f;  // the sheets' crests inside the frame's faces
constexpr float kDoorInset = 0.07f;   // the door leaves inside the castings' end faces (room for the bars)

}  // namespace

osg::ref_ptr<osg::Geometry> iso_container(const core::Vec3& size_m, const osg::Vec4& paint) {
  MeshBuilder mesh;
  const float hx = static_cast<float>(size_m.x / 2.0), hy = static_cast<float>(size_m.y / 2.0),
              hz = static_cast<float>(size_m.z / 2.0);
  const osg::Vec4 casting = shaded(paint, 0.7f), dark(0.03f, 0.03f, 0.03f, 1.0f),
                  floor(0.12f, 0.10f, 0.08f, 1.0f),
                  steel = finished({0.55f, 0.56f, 0.57f, 1.0f}, Surface::kGalvanised);
  const osg::Vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);

  // corner castings, each with its apertures (the top's oblong hole, the side's and end's ovals as slots)
  for (const float sx : {-1.0f, 1.0f})
    for (const float sy : {-1.0f, 1.0f})
      for (const float sz : {-1.0f, 1.0f}) {
        const osg::Vec3 c(sx * (hx - kCastingAlong / 2), sy * (hy - kCastingAcross / 2),
                          sz * (hz - kCastingTall / 2));
        // the casting's faces 1.5 mm inside the box, its apertures' slots 1 mm proud of them
        mesh.box(c, {kCastingAlong / 2 - 0.0015f, kCastingAcross / 2 - 0.0015f, kCastingTall / 2 - 0.0015f},
                 casting);
        const osg::Vec3 top = c + z * (sz * (kCastingTall / 2 - 0.0005f));
        mesh.quad(top + osg::Vec3(-0.062f, -0.032f, 0), top + osg::Vec3(0.062f, -0.032f, 0),
                  top + osg::Vec3(0.062f, 0.032f, 0), top + osg::Vec3(-0.062f, 0.032f, 0), z * sz, dark);
        const osg::Vec3 side = c + y * (sy * (kCastingAcross / 2 - 0.0005f));
        mesh.quad(side + osg::Vec3(-0.039f, 0, -0.025f), side + osg::Vec3(0.039f, 0, -0.025f),
                  side + osg::Vec3(0.039f, 0, 0.025f), side + osg::Vec3(-0.039f, 0, 0.025f), y * sy, dark);
        const osg::Vec3 end = c + x * (sx * (kCastingAlong / 2 - 0.0005f));
        mesh.quad(end + osg::Vec3(0, -0.035f, -0.025f), end + osg::Vec3(0, 0.035f, -0.025f),
                  end + osg::Vec3(0, 0.035f, 0.025f), end + osg::Vec3(0, -0.035f, 0.025f), x * sx, dark);
      }
  // corner posts between the castings, and the rails along the sides and across the ends
  const float post_half_z = hz - kCastingTall;
  for (const float sx : {-1.0f, 1.0f})
    for (const float sy : {-1.0f, 1.0f})
      mesh.box({sx * (hx - kCastingAlong / 2), sy * (hy - kCastingAcross / 2 + 0.004f), 0.0f},
               {kCastingAlong / 2 - 0.01f, kCastingAcross / 2 - 0.004f, post_half_z}, paint);
  const float rail_half_x = hx - kCastingAlong;
  for (const float sy : {-1.0f, 1.0f}) {
    mesh.box({0.0f, sy * (hy - 0.045f), hz - kTopRail / 2 - 0.004f}, {rail_half_x, 0.041f, kTopRail / 2},
             paint);
    mesh.box({0.0f, sy * (hy - 0.035f), -hz + kBottomRail / 2 + 0.004f},
             {rail_half_x, 0.031f, kBottomRail / 2}, paint);
  }
  const float end_rail_half_y = hy - kCastingAcross;
  for (const float sx : {-1.0f, 1.0f}) {
    const float header = sx < 0 ? kHeader : kTopRail, sill = sx < 0 ? kSill : kBottomRail;
    mesh.box({sx * (hx - 0.05f), 0.0f, hz - header / 2 - 0.004f}, {0.046f, end_rail_half_y, header / 2},
             paint);
    mesh.box({sx * (hx - 0.05f), 0.0f, -hz + sill / 2 + 0.004f}, {0.046f, end_rail_half_y, sill / 2}, paint);
  }
  // the side walls: vertical corrugations along the length, between posts and rails
  const float wall_bottom = -hz + kBottomRail + 0.004f, wall_top = hz - kTopRail - 0.004f;
  for (const float sy : {-1.0f, 1.0f})
    corrugated_sheet(mesh, {-rail_half_x, sy * (hy - kWallInset), wall_bottom}, x, 2 * rail_half_x,
                     z * (wall_top - wall_bottom), y * -sy, kWallSheet, paint);
  // the front wall (+x): vertical corrugations across the width
  {
    const float bottom = -hz + kBottomRail + 0.004f, top = hz - kTopRail - 0.004f;
    corrugated_sheet(mesh, {hx - kWallInset, -end_rail_half_y, bottom}, y, 2 * end_rail_half_y,
                     z * (top - bottom), -x, kWallSheet, paint);
  }
  // the roof between the top rails: shallow corrugations across it, pitched along the length
  corrugated_sheet(mesh, {-rail_half_x, -(hy - 0.086f), hz - 0.006f}, x, 2 * rail_half_x,
                   y * (2 * (hy - 0.086f)), -z, kRoofSheet, paint);
  // the floor's underside
  mesh.quad({-rail_half_x, -hy + 0.066f, -hz + 0.05f}, {rail_half_x, -hy + 0.066f, -hz + 0.05f},
            {rail_half_x, hy - 0.066f, -hz + 0.05f}, {-rail_half_x, hy - 0.066f, -hz + 0.05f}, -z, floor);
  // the doors (-x): two leaves with horizontal ribs, each with two locking bars (cams top and bottom, a
  // handle a metre up) and four hinges on its outer edge
  const float door_bottom = -hz + kSill + 0.004f, door_top = hz - kHeader - 0.004f;
  const float door_x = -hx + kDoorInset, leaf_gap = 0.006f;
  // the dark inside, seen through the gap between the leaves
  mesh.quad({door_x + kDoorSheet.depth + 0.01f, -0.05f, door_bottom},
            {door_x + kDoorSheet.depth + 0.01f, 0.05f, door_bottom},
            {door_x + kDoorSheet.depth + 0.01f, 0.05f, door_top},
            {door_x + kDoorSheet.depth + 0.01f, -0.05f, door_top}, -x, floor);
  for (const float sy : {-1.0f, 1.0f}) {
    const float inner = sy * leaf_gap, outer = sy * end_rail_half_y;
    const float leaf = std::abs(outer - inner);
    corrugated_sheet(mesh, {door_x, std::min(inner, outer), door_bottom}, z, door_top - door_bottom, y * leaf,
                     x, kDoorSheet, paint);
    for (const float share : {0.30f, 0.76f}) {  // from the hinges
      const float bar_y = outer - sy * share * leaf;
      const float bar_x = door_x - 0.035f;
      mesh.box({bar_x, bar_y, (door_bottom + door_top) / 2}, {0.018f, 0.018f, (door_top - door_bottom) / 2},
               steel);
      for (const float end : {door_bottom + 0.06f, door_top - 0.06f})
        mesh.box({bar_x, bar_y, end}, {0.03f, 0.04f, 0.05f}, shaded(steel, 0.8f));
      mesh.box({bar_x - 0.02f, bar_y - sy * 0.14f, -hz + 1.0f}, {0.012f, 0.14f, 0.02f}, steel);
    }
    for (int k = 0; k < 4; ++k) {
      const float hinge_z = door_bottom + 0.25f + (door_top - door_bottom - 0.5f) * static_cast<float>(k) / 3;
      mesh.box({door_x - 0.03f, outer - sy * 0.03f, hinge_z}, {0.03f, 0.03f, 0.06f}, shaded(paint, 0.85f));
    }
  }
  return mesh.build();
}

osg::ref_ptr<osg::Geometry> clamshell(const core::Vec3& size_m, double hinge_m, const osg::Vec4& paint) {
  MeshBuilder mesh;
  const float reach = static_cast<float>(size_m.x), half_width = static_cast<float>(size_m.y / 2.0),
              height = static_cast<float>(size_m.z), lip = static_cast<float>(hinge_m);
  const osg::Vec4 worn = finished({0.50f, 0.48f, 0.45f, 1.0f}, Surface::kSteel),
                  edge = finished({0.40f, 0.40f, 0.41f, 1.0f}, Surface::kSteel);
  const osg::Vec3 y(0, 1, 0);
  // the back's profile (x, z) from the lip round to the top of the back: a quarter ellipse about the point
  // above the lip at the back's top height
  constexpr int kSegments = 12;
  const float top = -lip + height;
  std::vector<osg::Vec3> profile;
  for (int k = 0; k <= kSegments; ++k) {
    const float phi = 0.5f * std::numbers::pi_v<float> * static_cast<float>(k) / kSegments;
    profile.emplace_back(reach * std::sin(phi), 0.0f, top - height * std::cos(phi));
  }
  const osg::Vec3 centre(0.0f, 0.0f, top);  // the bucket's inside is towards here
  for (int k = 0; k < kSegments; ++k) {
    const osg::Vec3 a = profile[static_cast<std::size_t>(k)], b = profile[static_cast<std::size_t>(k) + 1];
    const osg::Vec3 out = (a + b) * 0.5f - centre;
    const osg::Vec3 a0 = a - y * half_width, a1 = a + y * half_width, b0 = b - y * half_width,
                    b1 = b + y * half_width;
    mesh.quad(a0, b0, b1, a1, out, paint);
    mesh.quad(a0, b0, b1, a1, -out, worn);
    // the side plates: a fan from the ellipse's centre, both faces
    for (const float side : {-1.0f, 1.0f}) {
      const osg::Vec3 c = centre + y * (side * half_width), p = a + y * (side * half_width),
                      q = b + y * (side * half_width);
      mesh.triangle(c, p, q, y * side, paint);
      mesh.triangle(c, p, q, y * -side, worn);
    }
  }
  // the cutting edge along the lip, and the arms from the back's top corners to the pivot
  mesh.box({0.03f, 0.0f, -lip + 0.03f}, {0.05f, half_width + 0.02f, 0.04f}, edge);
  for (const float side : {-1.0f, 1.0f}) {
    const osg::Vec3 from(reach, side * (half_width - 0.1f), top), to(0.0f, side * (half_width - 0.1f), 0.0f);
    const osg::Vec3 along = to - from;
    osg::Vec3 across = along ^ y;
    across.normalize();
    const osg::Vec3 w = across * 0.09f, t = y * 0.09f;
    for (const auto& [u, v] : {std::pair{w, t}, std::pair{t, -w}, std::pair{-w, -t}, std::pair{-t, w}})
      mesh.quad(from + u + v, to + u + v, to + u - v, from + u - v, u, paint);
  }
  return mesh.build();
}

osg::ref_ptr<osg::Geometry> hull(const core::Vec3& size_m, const osg::Vec4& topsides, const osg::Vec4& bottom,
                                 double waterline_m, const osg::Vec4& deck, double open_from_m,
                                 double open_to_m) {
  MeshBuilder mesh;
  const float half_beam = static_cast<float>(size_m.x / 2.0),
              half_length = static_cast<float>(size_m.y / 2.0), depth = static_cast<float>(size_m.z),
              keel = -depth / 2.0f;
  const float bow_run = std::min(0.22f * 2.0f * half_length, 2.5f * half_beam);  // the entrance
  const float stern_run = std::min(0.15f * 2.0f * half_length, 1.8f * half_beam);
  const float bilge = 0.1f * 2.0f * half_beam, waterline = keel + static_cast<float>(waterline_m);
  // the half breadth at station y and height z above the keel: 1 amidships, closing in at the ends (fuller
  // at the deck than at the keel)
  const auto breadth = [&](float y, float z) {
    const float up = std::clamp((z - keel) / depth, 0.0f, 1.0f);
    if (y > half_length - bow_run) {
      const float t = (y - (half_length - bow_run)) / bow_run;
      return half_beam * (1.0f - std::pow(t, 1.2f + 1.3f * up));
    }
    if (y < -half_length + stern_run) {
      const float t = (-half_length + stern_run - y) / stern_run;
      const float transom = 0.6f * up * up;  // the transom's share of the beam, nothing at the keel
      return half_beam * (1.0f - (1.0f - transom) * std::pow(t, 1.5f + 1.5f * up));
    }
    return half_beam;
  };
  // the section's points from the keel's centre line round the bilge up to the deck edge: (out, z)
  std::vector<std::pair<float, float>> section{{0.0f, keel}};
  for (int k = 0; k <= 4; ++k) {
    const float a = 0.5f * std::numbers::pi_v<float> * static_cast<float>(k) / 4.0f;
    section.emplace_back(1.0f - bilge / half_beam * (1.0f - std::sin(a)),
                         keel + bilge * (1.0f - std::cos(a)));
  }
  for (const float z : {waterline, keel + depth})
    if (z > section.back().second) section.emplace_back(1.0f, z);
  // stations along the length, closer where the ends curve
  std::vector<float> stations;
  const int end_steps = 12;
  for (int k = 0; k <= end_steps; ++k)
    stations.push_back(-half_length + stern_run * static_cast<float>(k) / end_steps);
  for (int k = 1; k < 4; ++k)
    stations.push_back(-half_length + stern_run +
                       (2.0f * half_length - stern_run - bow_run) * static_cast<float>(k) / 4);
  for (int k = 0; k <= end_steps; ++k)
    stations.push_back(half_length - bow_run + bow_run * static_cast<float>(k) / end_steps);
  const float open_from = static_cast<float>(open_from_m), open_to = static_cast<float>(open_to_m);
  for (const float y : {open_from, open_to})  // the deck's opening ends on a station
    if (open_to > open_from && y > -half_length && y < half_length) stations.push_back(y);
  std::sort(stations.begin(), stations.end());
  const auto point = [&](float y, std::size_t n, float side) {
    const auto [out, z] = section[n];
    return osg::Vec3(side * out * breadth(y, z), y, z);
  };
  for (const float side : {-1.0f, 1.0f})
    for (std::size_t s = 0; s + 1 < stations.size(); ++s)
      for (std::size_t n = 0; n + 1 < section.size(); ++n) {
        const float y0 = stations[s], y1 = stations[s + 1];
        const osg::Vec3 a = point(y0, n, side), b = point(y1, n, side), c = point(y1, n + 1, side),
                        d = point(y0, n + 1, side);
        const float mid_z = 0.5f * (section[n].second + section[n + 1].second);
        const osg::Vec3 outward = osg::Vec3(side, 0.0f, 0.0f) * (section[n + 1].first > 0.99f ? 1.0f : 0.5f) +
                                  osg::Vec3(0.0f, 0.0f, -1.0f) * (mid_z < keel + bilge ? 0.5f : 0.0f);
        mesh.quad(a, b, c, d, outward, mid_z < waterline ? bottom : topsides);
      }
  // the transom, flat across the stern from the keel to the deck
  for (std::size_t n = 0; n + 1 < section.size(); ++n) {
    const float y = stations.front();
    const osg::Vec4 paint =
        0.5f * (section[n].second + section[n + 1].second) < waterline ? bottom : topsides;
    mesh.quad(point(y, n, -1.0f), point(y, n, 1.0f), point(y, n + 1, 1.0f), point(y, n + 1, -1.0f),
              {0, -1, 0}, paint);
  }
  if (deck.a() > 0.0f)  // the deck between the deck edges
    for (std::size_t s = 0; s + 1 < stations.size(); ++s) {
      const std::size_t top = section.size() - 1;
      const float y0 = stations[s], y1 = stations[s + 1];
      if (y0 >= open_from && y1 <= open_to) continue;  // over the holds
      mesh.quad(point(y0, top, -1.0f), point(y1, top, -1.0f), point(y1, top, 1.0f), point(y0, top, 1.0f),
                {0, 0, 1}, deck);
    }
  return mesh.build();
}

int tyre_axis(const core::Vec3& size_m) {
  const std::array<double, 3> s{size_m.x, size_m.y, size_m.z};
  for (int a = 0; a < 3; ++a)
    if (s[static_cast<std::size_t>((a + 1) % 3)] == s[static_cast<std::size_t>((a + 2) % 3)]) return a;
  return -1;
}

Revolved::Revolved(const core::Vec3& size_m) : axis(std::max(tyre_axis(size_m), 0)) {
  const std::array<double, 3> s{size_m.x, size_m.y, size_m.z};
  radius = static_cast<float>(s[static_cast<std::size_t>((axis + 1) % 3)] / 2.0);
  half_length = static_cast<float>(s[static_cast<std::size_t>(axis)] / 2.0);
}

osg::Vec3 Revolved::at(float theta, float r, float w) const {
  osg::Vec3 p;
  p[axis] = w;
  p[(axis + 1) % 3] = r * std::cos(theta);
  p[(axis + 2) % 3] = r * std::sin(theta);
  return p;
}

osg::ref_ptr<osg::Geometry> tyre(const core::Vec3& size_m, const osg::Vec4& rubber_colour,
                                 const osg::Vec4& rim, int segments) {
  const osg::Vec4 rubber = finished(rubber_colour, Surface::kRubber);
  const Revolved wheel(size_m);
  const int axis = wheel.axis;
  const float radius = wheel.radius, half_width = wheel.half_length;
  const auto at = [&](float theta, float r, float w) { return wheel.at(theta, r, w); };
  const auto radial = [&](float theta) { return at(theta, 1.0f, 0.0f); };
  osg::Vec3 axle;
  axle[axis] = 1.0f;
  MeshBuilder mesh;
  const float lug = std::clamp(0.06f * radius, 0.01f, 0.06f);  // the tread's depth
  const float base = radius - lug, shoulder = 0.14f * half_width * 2.0f;
  const float rim_r = 0.58f * radius, flange_w = half_width - 0.06f * half_width;
  const float dish = std::min(0.35f * half_width, 0.12f * radius);
  // the carcass: tread base, shoulders, sidewalls down to the rim's flange, revolved; each profile segment's
  // outward normal points away from the section's middle
  const std::vector<std::pair<float, float>> profile{// (r, w), from one flange round to the other
                                                     {rim_r, -flange_w},
                                                     {0.5f * (rim_r + base), -half_width},
                                                     {base - 0.6f * shoulder, -half_width},
                                                     {base, -half_width + shoulder},
                                                     {base, half_width - shoulder},
                                                     {base - 0.6f * shoulder, half_width},
                                                     {0.5f * (rim_r + base), half_width},
                                                     {rim_r, flange_w}};
  const float middle_r = 0.5f * (rim_r + radius);
  const float step = 2.0f * std::numbers::pi_v<float> / static_cast<float>(segments);
  for (int k = 0; k < segments; ++k) {
    const float t0 = step * static_cast<float>(k), t1 = t0 + step, tm = t0 + step / 2;
    for (std::size_t n = 0; n + 1 < profile.size(); ++n) {
      const auto [r0, w0] = profile[n];
      const auto [r1, w1] = profile[n + 1];
      const osg::Vec3 outward = radial(tm) * (0.5f * (r0 + r1) - middle_r) + axle * (0.5f * (w0 + w1));
      mesh.quad(at(t0, r0, w0), at(t0, r1, w1), at(t1, r1, w1), at(t1, r0, w0), outward, rubber);
    }
  }
  // the lugs: blocks from the tread base to the full radius, staggered from one shoulder to the other
  if (segments >= 24)
    for (int k = 0; k < segments; ++k) {
      const float centre = step * (static_cast<float>(k) + 0.5f), half_arc = 0.30f * step;
      const float t0 = centre - half_arc, t1 = centre + half_arc;
      const float side = k % 2 == 0 ? 1.0f : -1.0f;
      const float w0 = side * 0.06f * half_width, w1 = side * (half_width - 0.5f * shoulder);
      const float wl = std::min(w0, w1), wh = std::max(w0, w1);
      mesh.quad(at(t0, radius, wl), at(t1, radius, wl), at(t1, radius, wh), at(t0, radius, wh),
                radial(centre), rubber);
      for (const auto& [t, dir] : {std::pair{t0, -1.0f}, std::pair{t1, 1.0f}}) {
        const osg::Vec3 tangent = at(t + std::numbers::pi_v<float> / 2, 1.0f, 0.0f) * dir;
        mesh.quad(at(t, base, wl), at(t, radius, wl), at(t, radius, wh), at(t, base, wh), tangent, rubber);
      }
      for (const auto& [w, dir] : {std::pair{wl, -1.0f}, std::pair{wh, 1.0f}})
        mesh.quad(at(t0, base, w), at(t1, base, w), at(t1, radius, w), at(t0, radius, w), axle * dir, rubber);
    }
  // the rim on each side: the flange's inside down to the dished disc, the hub and a circle of nuts
  const osg::Vec4 hub = shaded(rim, 0.55f);
  const float hub_r = 0.28f * rim_r;
  for (const float side : {-1.0f, 1.0f}) {
    const float face = side * flange_w, disc = side * (flange_w - dish),
                cap = side * (flange_w - 0.4f * dish);
    for (int k = 0; k < segments; ++k) {
      const float t0 = step * static_cast<float>(k), t1 = t0 + step, tm = t0 + step / 2;
      mesh.quad(at(t0, rim_r, face), at(t1, rim_r, face), at(t1, rim_r, disc), at(t0, rim_r, disc),
                -radial(tm), rim);
      mesh.quad(at(t0, hub_r, disc), at(t1, hub_r, disc), at(t1, rim_r, disc), at(t0, rim_r, disc),
                axle * side, rim);
      mesh.quad(at(t0, hub_r, disc), at(t1, hub_r, disc), at(t1, hub_r, cap), at(t0, hub_r, cap), radial(tm),
                hub);
      mesh.triangle(at(0.0f, 0.0f, cap), at(t0, hub_r, cap), at(t1, hub_r, cap), axle * side, hub);
    }
    if (segments >= 24)
      for (int n = 0; n < 8; ++n) {
        const osg::Vec3 nut = at(static_cast<float>(n) * std::numbers::pi_v<float> / 4,
                                 0.5f * (hub_r + rim_r), disc + side * 0.02f * radius);
        osg::Vec3 half(0.03f * radius, 0.03f * radius, 0.03f * radius);
        half[axis] = 0.02f * radius;
        mesh.box(nut, half, hub);
      }
  }
  return mesh.build();
}

}  // namespace harbour::ig
