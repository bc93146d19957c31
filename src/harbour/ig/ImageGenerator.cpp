#include "harbour/ig/ImageGenerator.h"

#include <osg/BlendFunc>
#include <osg/Depth>
#include <osg/Fog>
#include <osg/FrameBufferObject>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Image>
#include <osg/LOD>
#include <osg/LightModel>
#include <osg/LightSource>
#include <osg/LineWidth>
#include <osg/Material>
#include <osg/MatrixTransform>
#include <osg/Point>
#include <osg/Program>
#include <osg/ShapeDrawable>
#include <osg/Texture2D>
#include <osg/Uniform>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>
#include <osgParticle/PrecipitationEffect>
#include <osgShadow/ShadowedScene>
#include <osgShadow/ViewDependentShadowMap>
#include <osgText/Text>
#include <osgViewer/Viewer>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "harbour/core/Rng.h"
#include "harbour/ig/HeadlessContext.h"
#include "harbour/ig/Materials.h"
#include "harbour/ig/Models.h"
#include "harbour/ig/Sky.h"
#include "harbour/ig/Structures.h"

namespace harbour::ig {

namespace {

constexpr double kCabNear_m = 0.25;  // a cab view's near plane: depth steps of 0.24 m at 1 km (24 bits)

// `v` turned by `angle` about the unit `axis` (Rodrigues)
core::Vec3 turned(const core::Vec3& v, const core::Vec3& axis, double angle) {
  return v * std::cos(angle) + cross(axis, v) * std::sin(angle) +
         axis * (dot(axis, v) * (1.0 - std::cos(angle)));
}

// a view's axes turned as a head looks round: left by `yaw` about the picture's up, then up by `pitch` about
// its right
void look_round(core::Vec3& forward, core::Vec3& up, core::Vec3& right, double yaw, double pitch) {
  if (yaw == 0.0 && pitch == 0.0) return;
  forward = turned(forward, up, yaw);
  right = turned(right, up, yaw);
  forward = turned(forward, right, pitch);
  up = turned(up, right, pitch);
}
constexpr double kPi = std::numbers::pi;
constexpr double kLongestRoll_s = 1.0;   // snapshots further apart are a jump (a seek): the tyres do not roll
constexpr double kFetch_m = 2000.0;      // the harbour basin's open water upwind, for the wind sea (assumed)
constexpr double kCloudBase_m = 1200.0;  // the cloud deck's height
constexpr double kCloudTile_m = 5000.0;  // its noise texture's tile
// a cloud as the deck's density passes its threshold: opaque within `edge` of it (fair-weather cloud's edge
// crisp, rain cloud's ragged), thick (its darkest base) at `depth` past it (a fair-weather cloud's core dark
// under its sunlit rim, a rain cloud's deck more even)
constexpr double kFairCloudEdge = 0.036, kRainCloudEdge = 0.12, kFairCloudDepth = 0.15, kRainCloudDepth = 0.6;
constexpr double kCrestShareOfWhitecaps = 0.5;  // of the whitecaps, on the crests breaking now (ours)
constexpr int kWaterColumns = 96,
              kWaterRows = 64;          // the water's grid, laid over the screen (projected grid)
constexpr double kWaterFar_m = 3000.0;  // where it ends; a flat sea beyond
// render bins after the solid scene's (0): the water, then the far sea under it
constexpr int kWaterBin = 5, kFarWaterBin = 6, kSprayBin = 20, kLampBin = 21;
constexpr int kSprayCells = 64;
constexpr double kQuayEdge_m = 18.0;  // the quay's top reaches x = 18 m; the harbour's water lies beyond  //
                                      // spray's grid, 5 m cells: 320 m round the eye
// node masks: what draws into the sun's shadow map (the ground and flat markings only receive); what the main
// view draws and what the insets' cameras do (the lit scene with or without the sun's shadows)
constexpr unsigned kCastsShadow = 0x2u, kReceivesOnly = ~kCastsShadow, kMainView = 0x4u, kInsetViews = 0x8u;

osg::Vec3 to_osg(const core::Vec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

osg::Matrixd to_osg(const core::Pose& p) {
  // OSG multiplies row vectors: element (i, j) is the rotation's (j, i), the translation the last row
  const core::Mat3& r = p.rotation;
  return osg::Matrixd(r.m[0][0], r.m[1][0], r.m[2][0], 0.0, r.m[0][1], r.m[1][1], r.m[2][1], 0.0, r.m[0][2],
                      r.m[1][2], r.m[2][2], 0.0, p.position.x, p.position.y, p.position.z, 1.0);
}

osg::Vec4 rgba(const core::Vec3& c) {
  return {static_cast<float>(c.x), static_cast<float>(c.y), static_cast<float>(c.z), 1.0f};
}

// the quay's concrete paving, dry
const osg::Vec4 kQuayPaving = finished({0.42f, 0.42f, 0.40f, 1.0f}, Surface::kConcrete);

// a flat rectangle at height z, cut into cells so that the lighting done per vertex varies over it
osg::ref_ptr<osg::Geode> tessellated_plane(double x0, double x1, double y0, double y1, double z, double cell,
                                           const osg::Vec4& color) {
  osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry();
  osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array();
  osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array();
  const int nx = std::max(1, static_cast<int>((x1 - x0) / cell)),
            ny = std::max(1, static_cast<int>((y1 - y0) / cell));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const double xa = x0 + (x1 - x0) * i / nx, xb = x0 + (x1 - x0) * (i + 1) / nx;
      const double ya = y0 + (y1 - y0) * j / ny, yb = y0 + (y1 - y0) * (j + 1) / ny;
      for (const auto& [x, y] :
           {std::pair{xa, ya}, std::pair{xb, ya}, std::pair{xb, yb}, std::pair{xa, yb}}) {
        vertices->push_back(osg::Vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
        normals->push_back(osg::Vec3(0, 0, 1));
      }
    }
  geometry->setUseDisplayList(false);  // buffer objects: a colour change (wet) reaches the next frame
  geometry->setUseVertexBufferObjects(true);
  geometry->setVertexArray(vertices);
  geometry->setNormalArray(normals, osg::Array::BIND_PER_VERTEX);
  osg::ref_ptr<osg::Vec4Array> colors = new osg::Vec4Array();
  colors->push_back(color);
  geometry->setColorArray(colors, osg::Array::BIND_OVERALL);
  geometry->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, static_cast<int>(vertices->size())));
  osg::ref_ptr<osg::Geode> geode = new osg::Geode();
  geode->addDrawable(geometry);
  return geode;
}

// A mesh read from a file drawn from buffer objects, as every other geometry here is (its reader's display
// lists, compiled after a geometry drawn from a buffer object, read their arrays through the buffer still
// bound: a software renderer crashed on it).
void use_buffer_objects(osg::Node& mesh) {
  struct Buffered : osg::NodeVisitor {
    Buffered() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Drawable& drawable) override {
      drawable.setUseDisplayList(false);
      drawable.setUseVertexBufferObjects(true);
    }
  } buffered;
  mesh.accept(buffered);
}

// The part's colour on a mesh's geometry that brings none of its own (the lit shader reads vertex colours;
// a material's diffuse colour, where the file has one, wins), with the part's finish in its alpha.
void paint_uncoloured(osg::Node& mesh, const osg::Vec4& color) {
  struct Painter : osg::NodeVisitor {
    osg::Vec4 color;
    explicit Painter(const osg::Vec4& c) : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN), color(c) {}
    void apply(osg::Drawable& drawable) override {
      osg::Geometry* geometry = drawable.asGeometry();
      if (!geometry || geometry->getColorArray()) return;
      osg::Vec4 paint = color;
      osg::StateSet* parent_state =
          geometry->getNumParents() > 0 ? geometry->getParent(0)->getStateSet() : nullptr;
      for (const osg::StateSet* state : {geometry->getStateSet(), parent_state})
        if (state)
          if (const auto* material =
                  dynamic_cast<const osg::Material*>(state->getAttribute(osg::StateAttribute::MATERIAL)))
            paint = material->getDiffuse(osg::Material::FRONT);
      paint.a() = color.a();  // the part's finish
      osg::ref_ptr<osg::Vec4Array> colors = new osg::Vec4Array;
      colors->push_back(paint);
      geometry->setColorArray(colors, osg::Array::BIND_OVERALL);
    }
  } painter(color);
  mesh.accept(painter);
}

// A lattice girder filling the box of `size` round `centre`: four chords along its longest side, at every
// panel point a vertical in each side face and a strut in the top and bottom faces, Warren diagonals (one
// way, then the other) in all four faces. Members are square bars `member` thick.
void add_lattice(MeshBuilder& mesh, const core::Vec3& centre, const core::Vec3& size, double bay,
                 double member, const osg::Vec4& color) {
  // the girder's axes: a along the longest side, b and c across it
  const std::array<double, 3> sides{size.x, size.y, size.z};
  const int a = static_cast<int>(std::max_element(sides.begin(), sides.end()) - sides.begin());
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const auto point = [&](double along, double across_b, double across_c) {
    std::array<double, 3> p{};
    p[static_cast<std::size_t>(a)] = along;
    p[static_cast<std::size_t>(b)] = across_b;
    p[static_cast<std::size_t>(c)] = across_c;
    return centre + core::Vec3{p[0], p[1], p[2]};
  };
  const auto bar = [&](const core::Vec3& from, const core::Vec3& to) {
    beam(mesh, to_osg(from), to_osg(to), static_cast<float>(member), static_cast<float>(member), color);
  };
  const double length = sides[static_cast<std::size_t>(a)];
  const double hb = (sides[static_cast<std::size_t>(b)] - member) / 2.0,
               hc = (sides[static_cast<std::size_t>(c)] - member) / 2.0;
  const int bays = std::max(1, static_cast<int>(std::lround(length / bay)));
  const double step = length / bays, start = -length / 2.0;
  for (const double sb : {-hb, hb})
    for (const double sc : {-hc, hc})
      bar(point(start, sb, sc), point(-start, sb, sc));  // chords
  // the four faces, each by its two corners (b, c) round the girder
  const std::array<std::array<double, 4>, 4> faces{
      {{-hb, -hc, -hb, hc}, {hb, -hc, hb, hc}, {-hb, -hc, hb, -hc}, {-hb, hc, hb, hc}}};
  for (int k = 0; k <= bays; ++k) {
    const double x = start + step * k;
    for (const auto& f : faces) {
      bar(point(x, f[0], f[1]), point(x, f[2], f[3]));  // vertical or strut
      if (k == bays) continue;
      const bool rising = k % 2 == 0;  // Warren: the diagonals alternate
      bar(point(x, rising ? f[0] : f[2], rising ? f[1] : f[3]),
          point(x + step, rising ? f[2] : f[0], rising ? f[3] : f[1]));
    }
  }
}

// a steelwork part (ig/Structures.h) built about its centre; none for any other shape
osg::ref_ptr<osg::Geometry> structure(const VisualPart& part, const core::Vec3& size,
                                      const osg::Vec4& paint) {
  switch (part.shape) {
    case VisualPart::Shape::kGirder:
      return box_girder(size, part.bay_m, paint);
    case VisualPart::Shape::kWalkway:
      return walkway(size, part.rails, paint);
    case VisualPart::Shape::kStairs:
      return stairs(size, paint);
    case VisualPart::Shape::kCylinder:
      return cylinder(size, 20, paint);
    case VisualPart::Shape::kMember: {
      MeshBuilder mesh;
      const osg::Vec3 half = to_osg(part.along) * static_cast<float>(size.x / 2);
      beam(mesh, -half, half, static_cast<float>(size.y), static_cast<float>(size.z), paint);
      return mesh.build();
    }
    default:
      return nullptr;
  }
}

}  // namespace

// The procedural models (ig/Models.h) of a scene, each built once per size and colour and shared by every
// entity drawing it, within a level of detail: beyond its range a container is a plain box, a tyre smooth.
class ModelCache {
 public:
  osg::ref_ptr<osg::Node> detailed(const VisualPart& part, const core::Vec3& size, const core::Vec3& color) {
    const bool container = part.shape == VisualPart::Shape::kContainer;
    const std::array<double, 11> key{container ? 1.0 : 0.0,
                                     size.x,
                                     size.y,
                                     size.z,
                                     color.x,
                                     color.y,
                                     color.z,
                                     part.rim_color.x,
                                     part.rim_color.y,
                                     part.rim_color.z,
                                     static_cast<double>(part.surface)};
    const osg::Vec4 paint = finished(rgba(color), part.surface);
    osg::ref_ptr<osg::Node>& node = nodes_[key];
    if (node) return node;
    osg::ref_ptr<osg::Geode> near = new osg::Geode, far = new osg::Geode;
    osg::ref_ptr<osg::LOD> lod = new osg::LOD;
    if (container) {
      near->addDrawable(iso_container(size, paint));
      osg::ref_ptr<osg::ShapeDrawable> box = new osg::ShapeDrawable(new osg::Box(
          osg::Vec3(), static_cast<float>(size.x), static_cast<float>(size.y), static_cast<float>(size.z)));
      box->setColor(paint);
      far->addDrawable(box);
      lod->addChild(near, 0.0f, kContainerDetail_m);
      lod->addChild(far, kContainerDetail_m, std::numeric_limits<float>::max());
    } else {
      const osg::Vec4 rim = finished(rgba(part.rim_color), part.surface);
      near->addDrawable(tyre(size, rgba(color), rim, 36));
      far->addDrawable(tyre(size, rgba(color), rim, 12));
      lod->addChild(near, 0.0f, kTyreDetail_m);
      lod->addChild(far, kTyreDetail_m, std::numeric_limits<float>::max());
    }
    node = lod;
    return node;
  }

 private:
  static constexpr float kContainerDetail_m = 150.0f, kTyreDetail_m = 80.0f;
  std::map<std::array<double, 11>, osg::ref_ptr<osg::Node>> nodes_;
};

namespace {

// a body of declination `declination` seen at hour angle `hour_angle` from `latitude`: the direction
// towards it (x east, y north, z up)
core::Vec3 sky_direction(double hour_angle, double declination, double latitude) {
  return {-std::cos(declination) * std::sin(hour_angle),
          std::cos(latitude) * std::sin(declination) -
              std::sin(latitude) * std::cos(declination) * std::cos(hour_angle),
          std::sin(latitude) * std::sin(declination) +
              std::cos(latitude) * std::cos(declination) * std::cos(hour_angle)};
}

// the local sidereal angle: the sun's hour angle plus its right ascension (0 at the March equinox)
double sidereal_angle(double t_h, double day_of_year) {
  return (t_h - 12.0) / 24.0 * 2.0 * kPi + 2.0 * kPi * (day_of_year - 80.0) / 365.25;
}

constexpr double kObliquity = 23.44 * kPi / 180.0;
constexpr double kSynodicMonth_d = 29.53;
constexpr double kNewMoonDay = 5.0;  // a new moon on 5 January (a year's phases repeat; assumed)
constexpr int kStars = 900;
constexpr double kDomeRadius_m = 3900.0;

}  // namespace

// the sky's colours for a sun (the clear sky of `Daylight`) under the weather's veil: rain clouds
// (`overcast`, 0-1) hide the sun; they and fog (`grey`, the larger of the two) turn the sky towards a grey of
// its own brightness, darker under rain clouds. Made once an update: the water's shader mirrors `horizon` and
// `zenith`, the stars sit on `towards`.
struct SkyShade {
  Daylight daylight;
  core::Vec3 sun;
  double grey = 0.0, overcast = 0.0;
  core::Vec3 horizon, zenith;
  double sun_visible = 0.0;

  SkyShade(const core::Vec3& to_sun, double sun_elevation, double grey_share, double overcast_share,
           double sun_clouded = 0.0)
      : daylight(to_sun), sun(to_sun), grey(grey_share), overcast(overcast_share) {
    horizon = veiled(daylight.horizon());
    zenith = veiled(daylight.zenith());
    sun_visible = sun_elevation > -0.01 ? std::clamp((sun_elevation + 0.01) / 0.02, 0.0, 1.0) : 0.0;
    sun_visible *= 1.0 - std::max({grey, overcast, sun_clouded});
  }
  core::Vec3 veiled(const core::Vec3& c) const {
    const double luminance = (0.30 * c.x + 0.59 * c.y + 0.11 * c.z) * (1.0 - 0.35 * overcast);
    const core::Vec3 g{luminance, luminance, luminance * 1.03};
    return c + (g - c) * grey;
  }
  osg::Vec4 towards(const core::Vec3& d) const {
    core::Vec3 c = veiled(daylight.sky(d));
    if (dot(d, sun) > 0.99996)
      c = c + core::Vec3{1.0, 0.95, 0.85} * sun_visible;  // the disc, ~0.5 deg across
    return {static_cast<float>(std::min(c.x, 1.0)), static_cast<float>(std::min(c.y, 1.0)),
            static_cast<float>(std::min(c.z, 1.0)), 1.0f};
  }
};

namespace {

// The lit scene's shading, physically based: each surface's colour and its finish (ig/Materials.h: its
// roughness and metalness, carried in the colour's alpha) lit by the sun (light 0: its diffuse as what a
// white matt surface facing it shows, dimmed where the shadow map says the sun is hidden), the sky's light
// (light 0's ambient) and the floodlights (lights 1..n, their attenuation). Per pixel the sun's diffuse light
// and its glint by the GGX microfacet distribution with Smith's visibility (Schlick-GGX) and Schlick's
// Fresnel; per vertex the sky's and the floodlights' diffuse light and the sky mirrored by the surface (the
// horizon's and the zenith's colours along the reflected ray, the ground's under it, blurred towards the
// sky's mean as the surface roughens) weighted by Karis's analytic fit of the split-sum environment term;
// in rain the faces turned up darkened and smoothed by their water film. With DETAIL, surface detail from a
// tileable noise texture laid on the object's own faces (it rides the machine): blotches that vary the colour
// and the roughness (worn paint, stained concrete), a fine grain that bumps the normal, and on upright faces
// streaks running down (rust under paint, water stains on concrete), each as strong as the finish says. A
// highlight beyond white is rolled off by a shoulder (identity to 0.8, then 0.8 + 0.2 x / (x + 0.2), x = c -
// 0.8), not clipped; then the fog per pixel. With WET (the quay in rain) a water film per pixel: it mirrors
// the sky by Fresnel's reflectance, shows the sun's and the floodlights' glare, and rings where drops land.
// With CLOUDS (fair-weather cloud in the sky) the sun's light taken where a cloud hides it. Each combination
// is a program of its own, since llvmpipe shades both sides of a branch (the film in a branch cost every dry
// pixel as much as the rest of the frame; the clouds' shade cost a clear day's chase view 22 ms in 129).
constexpr char kLitVertexShader[] = R"(
uniform int floodlights;   // lights 1..floodlights are on
uniform vec4 finishes[8];  // (roughness, metalness, texture, weathering) by surface (ig/Materials.h)
uniform float wetness;     // rain's water on the surfaces: 0 dry, 1 wet through
varying vec3 unshadowed;   // the sky's and the floodlights' light on a white matt surface
varying vec3 sky_reflected;
varying vec3 base_colour;
varying vec4 finish;
varying vec3 eye_position;
varying vec3 eye_normal;
#ifdef DETAIL
varying vec3 object_position;  // where the surface detail is laid
varying vec3 object_normal;
#endif
uniform vec3 sky_horizon;  // the sky that surfaces mirror
uniform vec3 sky_zenith;
uniform mat4 osg_ViewMatrix;
// the sky mirrored along `r` (the ground's light under the horizon: paving of albedo 0.3 under the sky),
// blurred towards the sky's mean as the surface roughens, times Karis's (2014) fit of the preintegrated
// environment term for reflectance `f0`; per vertex (the sky's gradient is smooth)
vec3 sky_reflection(vec3 n, vec3 v, vec3 f0, float roughness) {
  vec3 r = reflect(-v, n);
  float up = dot(r, osg_ViewMatrix[2].xyz);
  vec3 sky_light = gl_LightSource[0].ambient.rgb;
  vec3 mirrored = up > 0.0 ? mix(sky_horizon, sky_zenith, sqrt(up)) : 0.3 * sky_light;
  vec3 seen = mix(mirrored, sky_light, roughness);
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 fit = roughness * c0 + c1;
  float a004 = min(fit.x * fit.x, exp2(-9.28 * max(dot(n, v), 0.0))) * fit.x + fit.y;
  vec2 ab = vec2(-1.04, 1.04) * a004 + fit.zw;
  return seen * (f0 * ab.x + ab.y);
}
void main() {
  vec4 eye = gl_ModelViewMatrix * gl_Vertex;
  vec3 n = normalize(gl_NormalMatrix * gl_Normal);
  eye_position = eye.xyz;
  eye_normal = n;
#ifdef DETAIL
  object_position = gl_Vertex.xyz;
  object_normal = gl_Normal;
#endif
  finish = finishes[int(clamp(floor((1.0 - gl_Color.a) * 16.0 + 0.5), 0.0, 7.0))];
  base_colour = gl_Color.rgb;
  // water lies on faces turned up: under its film an albedo A shows (1 - re)(1 - ri) A / (1 - ri A) (Lekner &
  // Dorf 1988; water's diffuse reflectances from outside re = 0.066 and inside ri = 1 - (1 - re) / 1.33^2 =
  // 0.472): darker, the darker it was; a metal's reflectance stays; the film smooths it (roughness 0.15)
  float wet = wetness * smoothstep(0.5, 0.9, dot(n, osg_ViewMatrix[2].xyz));
  base_colour = mix(base_colour, mix(0.4932 * base_colour / (1.0 - 0.472 * base_colour), base_colour, finish.y),
                    wet);
#ifndef WET
  finish.x = mix(finish.x, 0.15, wet);  // the quay's film is its own (WET)
#endif
  sky_reflected = sky_reflection(n, normalize(-eye.xyz), mix(vec3(0.04), base_colour, finish.y), finish.x);
  unshadowed = gl_LightModel.ambient.rgb + gl_LightSource[0].ambient.rgb;
  for (int i = 1; i < 8; ++i) {
    if (i > floodlights) break;
    vec3 to_light = gl_LightSource[i].position.xyz - eye.xyz;
    float d = length(to_light);
    float attenuation = 1.0 / (gl_LightSource[i].constantAttenuation + gl_LightSource[i].linearAttenuation * d +
                               gl_LightSource[i].quadraticAttenuation * d * d);
    unshadowed += max(dot(n, to_light / d), 0.0) * attenuation * gl_LightSource[i].diffuse.rgb;
  }
  gl_TexCoord[1] = vec4(dot(eye, gl_EyePlaneS[1]), dot(eye, gl_EyePlaneT[1]), dot(eye, gl_EyePlaneR[1]),
                        dot(eye, gl_EyePlaneQ[1]));
  gl_Position = gl_ProjectionMatrix * eye;
}
)";
constexpr char kLitFragmentShader[] = R"(
uniform sampler2DShadow shadowTexture0;
uniform bool sun_shadows;  // off in the insets' small pictures (no shadow map of their own)
varying vec3 unshadowed;
varying vec3 sky_reflected;
varying vec3 base_colour;
varying vec4 finish;
varying vec3 eye_position;
varying vec3 eye_normal;
#ifdef DETAIL
uniform sampler2D detail_texture;  // 4 m a tile: blotches, grain, streaks (surface_detail_texture)
varying vec3 object_position;
varying vec3 object_normal;
#endif
uniform bool soft_shadows;  // filtered edges (ImageGenerator::set_soft_shadows)
uniform float sun_seen;     // how much of the sun's disc shows (none under rain cloud or in fog): its glint
uniform mat4 osg_ViewMatrixInverse;
#ifdef CLOUDS
uniform sampler2D cloud_noise;  // the cloud deck's density (the clouds' texture)
// the deck's threshold, the density past it a cloud is half opaque, the deck's drift [m]
uniform vec4 cloud_deck;
// the share of the sun's light a cloud takes from a point: the deck's density where the sun's ray from it
// meets the deck (1,200 m up, 5 km a tile: the clouds' own), as opaque as the cloud drawn there
float cloud_shade(vec3 world, vec3 to_sun) {
  vec2 deck = world.xy + to_sun.xy * (1200.0 - world.z) / max(to_sun.z, 0.01) - cloud_deck.zw;
  vec2 at = deck / 5000.0;
  float n = 0.65 * texture2D(cloud_noise, at).r + 0.35 * texture2D(cloud_noise, at * 3.1 + 0.37).r;
  return clamp((n - cloud_deck.x) / (2.0 * cloud_deck.y), 0.0, 1.0);
}
#endif
// Schlick's Fresnel term from the reflectance at normal incidence `f0`, at an angle of cosine `c`
vec3 schlick(vec3 f0, float c) {
  float m = 1.0 - max(c, 0.0);
  float m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
}
// the sun's glint: GGX's distribution (alpha = roughness^2), Smith's visibility with Schlick-GGX's k = alpha/2,
// Schlick's Fresnel; in the units of the sun's diffuse light (what a white matt surface facing it shows: the
// irradiance over pi), so the glint is pi D V F (n.l) times it
vec3 sun_glint(vec3 n, vec3 v, vec3 l, vec3 f0, float roughness) {
  vec3 h = normalize(l + v);
  float nl = max(dot(n, l), 0.0), nv = max(dot(n, v), 1e-3), nh = max(dot(n, h), 0.0);
  float a = max(roughness * roughness, 2e-3);
  float a2 = a * a;
  float d = nh * nh * (a2 - 1.0) + 1.0;
  float k = 0.5 * a;
  float visibility = 0.25 / ((nl * (1.0 - k) + k) * (nv * (1.0 - k) + k));
  return schlick(f0, dot(v, h)) * (a2 / (d * d) * visibility * nl) * gl_LightSource[0].diffuse.rgb;
}
#ifdef DETAIL
// the normal `n` bumped by the height field `h` (m) over the surface: Mikkelsen's (2010) surface gradient
// from the screen-space derivatives of the position and the height
vec3 bumped(vec3 n, float h) {
  vec3 dpdx = dFdx(eye_position), dpdy = dFdy(eye_position);
  vec3 r1 = cross(dpdy, n), r2 = cross(n, dpdx);
  float det = dot(dpdx, r1);
  vec3 gradient = sign(det) * (dFdx(h) * r1 + dFdy(h) * r2);
  return normalize(abs(det) * n - gradient);
}
#endif
#ifdef WET
uniform int floodlights;
uniform vec3 sky_horizon;  // the sky the film mirrors
uniform vec3 sky_zenith;
uniform mat4 osg_ViewMatrix;
uniform float wetness;      // this surface's water film: 0 dry, 1 wet through
uniform float splash_rate;  // drops whose splash shows, per square metre and second
uniform float time_s;
float hash(vec2 p) {
  return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453);
}
// the rings of the drops landing round `xy` (world, m): in each 0.35 m cell one drop at a time, at a random
// place and moment, its ring spreading at 0.25 m/s and fading over 0.3 s
float splash(vec2 xy) {
  const float cell = 0.35;
  vec2 c = floor(xy / cell);
  float period = 1.0 / max(splash_rate * cell * cell, 1e-3);
  float t = time_s / period + hash(c);
  float k = floor(t);
  float age = (t - k) * period;
  vec2 at = (c + vec2(hash(c + vec2(k, 1.7)), hash(c + vec2(5.3, k)))) * cell;
  float ring = abs(length(xy - at) - (0.01 + 0.25 * age));
  return (1.0 - smoothstep(0.0, 0.015, ring)) * max(0.0, 1.0 - age / 0.3);
}
// Schlick's reflectance of water (R0 = 0.02) at an angle of cosine `c`
float fresnel(float c) {
  return 0.02 + 0.98 * pow(1.0 - max(c, 0.0), 5.0);
}
// a light's glare on the film: energy-normalised Blinn-Phong (exponent 400) of the light from `to_light`
vec3 glare(vec3 n, vec3 v, vec3 to_light, vec3 light) {
  vec3 h = normalize(to_light + v);
  return fresnel(dot(v, h)) * (408.0 / 25.13) * pow(max(dot(n, h), 0.0), 400.0) * max(dot(n, to_light), 0.0) *
         light;
}
vec3 wet(vec3 colour, float lit, vec3 n, vec3 v, float distance) {
  vec3 up = osg_ViewMatrix[2].xyz;
  vec3 r = reflect(-v, n);
  vec3 sky = mix(sky_horizon, sky_zenith, sqrt(max(dot(r, up), 0.0)));
  vec3 c = mix(colour, sky, fresnel(dot(n, v)) * wetness);
  c += wetness * lit * glare(n, v, normalize(gl_LightSource[0].position.xyz), gl_LightSource[0].diffuse.rgb);
  for (int i = 1; i < 8; ++i) {
    if (i > floodlights) break;
    vec3 to_light = gl_LightSource[i].position.xyz - eye_position;
    float d = length(to_light);
    float attenuation = 1.0 / (gl_LightSource[i].constantAttenuation + gl_LightSource[i].linearAttenuation * d +
                               gl_LightSource[i].quadraticAttenuation * d * d);
    // a lamp is far brighter to look at than the pool it lights (its glare a few times its light: assumed 4)
    c += wetness * 4.0 * glare(n, v, to_light / d, gl_LightSource[i].diffuse.rgb * attenuation);
  }
  vec2 xy = (osg_ViewMatrixInverse * vec4(eye_position, 1.0)).xy;
  float near = clamp(1.0 - distance / 35.0, 0.0, 1.0);  // a ring's width is under a pixel farther off
  return c + splash(xy) * near * 0.8 * gl_LightSource[0].ambient.rgb;
}
#endif
// percentage-closer filtering: the share of a 3x3 patch of the shadow map (a texel apart, each tap
// compared and filtered by the hardware) that sees the sun, so a shadow's edge is a soft ramp a few texels
// wide instead of the map's staircase
float sun_visible(vec4 at) {
  const float step = 1.0 / 1024.0;  // the shadow map's texel: ShadowSettings' 1024x1024
  float sum = 0.0;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      sum += shadow2DProj(shadowTexture0, at + vec4(float(i) * step * at.w, float(j) * step * at.w, 0.0, 0.0)).r;
  return sum / 9.0;
}
void main() {
  vec4 at = gl_TexCoord[1];
  at.z -= 0.0015 * at.w;  // towards the sun: no self-shadowing on lit faces, the filter's taps included
  float lit = !sun_shadows ? 1.0 : soft_shadows ? sun_visible(at) : shadow2DProj(shadowTexture0, at).r;
#ifdef CLOUDS
  // under a cloud the sun's direct light falls by 85 % (as under an overcast)
  vec3 world = (osg_ViewMatrixInverse * vec4(eye_position, 1.0)).xyz;
  vec3 to_sun_world = (osg_ViewMatrixInverse * vec4(gl_LightSource[0].position.xyz, 0.0)).xyz;
  lit *= 1.0 - 0.85 * cloud_shade(world, normalize(to_sun_world));
#endif
  float roughness = finish.x, metalness = finish.y;
  vec3 tint = vec3(1.0);
  vec3 n = normalize(eye_normal);
#ifdef DETAIL
  // the detail on the face's own plane (the object's frame, z up): blotches (r), grain (g), streaks (b)
  vec3 across = abs(object_normal);
  vec2 on_face = across.z > 0.7 ? object_position.xy
                                : (across.x > across.y ? object_position.yz : object_position.xz);
  vec4 detail = texture2D(detail_texture, on_face * 0.25);
  // blotches at two scales, the larger turned 30 degrees and 4.33 times as large: no 4 m grid shows
  float large = texture2D(detail_texture, mat2(0.866, 0.5, -0.5, 0.866) * on_face * (0.25 / 4.33)).r;
  float blotch = 0.5 * (detail.r - 0.5) + 0.5 * (large - 0.5);
  float streak = (1.0 - smoothstep(0.3, 0.5, across.z)) * smoothstep(0.72, 0.95, detail.b) * finish.w;
  tint = (1.0 + finish.z * blotch) * mix(vec3(1.0), vec3(0.72, 0.55, 0.42), 0.5 * streak);
  roughness = clamp(roughness + 0.5 * finish.z * blotch, 0.03, 1.0);
  n = bumped(n, 0.004 * finish.z * (detail.g - 0.5));
#endif
  float distance = length(eye_position);
  vec3 v = -eye_position / distance, l = gl_LightSource[0].position.xyz;  // a unit vector, turned rigidly
  vec3 colour = base_colour * tint;
  vec3 diffuse = colour * (1.0 - metalness);  // a metal's diffuse part is nil
  vec3 f0 = mix(vec3(0.04), colour, metalness);  // 4 % for a dielectric, a metal's colour
  colour = (unshadowed + lit * max(dot(n, l), 0.0) * gl_LightSource[0].diffuse.rgb) * diffuse +
           sky_reflected * mix(vec3(1.0), tint, metalness) + lit * sun_seen * sun_glint(n, v, l, f0, roughness);
#ifdef WET
  colour = wet(colour, lit, normalize(eye_normal), v, distance);  // the film is smooth over the grain
#endif
  vec3 over = max(colour - 0.8, 0.0);
  colour = min(colour, 0.8) + 0.2 * over / (over + 0.2);  // the highlights' shoulder
  float fog = clamp(exp(-gl_Fog.density * distance), 0.0, 1.0);
  gl_FragColor = vec4(mix(gl_Fog.color.rgb, colour, fog), 1.0);
}
)";
// Spray torn off the crests in a gale: puffs on a world-fixed grid of 5 m cells round the eye (kSprayCells
// across), each cell at most one puff at a time, born at a random moment of its 2.5 s period with the chance
// `spray_share`; a puff rises and falls (its height `spray_height` times sin(pi age / life)) while the wind
// carries it at 0.7 of its speed, grows from 1 to 3 m across and fades in and out; over water only (beyond
// the quay's edge), fading out from 100 to 300 m. Billboards in the eye's frame, drawn out 2.5 times along
// the wind, white in the light the foam takes, fogged per vertex.
constexpr char kSprayVertexShader[] = R"(#version 120
uniform vec2 first_cell;    // world, m: the grid's corner cell
uniform float time_s;
uniform float spray_share;  // the chance a cell carries a puff in a period
uniform float spray_height; // m
uniform vec2 wind;          // m/s
uniform float water_level;  // m
uniform float quay_edge;    // x of the quay's edge: water beyond it
uniform mat4 osg_ViewMatrix;
varying vec2 corner;
varying float opacity;
varying float fog;
float hash(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }
void main() {
  const float cell = 5.0, life = 2.5;
  vec2 c = first_cell / cell + gl_Vertex.xy;  // the cell's index in the world
  float t = time_s / life + hash(c);
  float k = floor(t);
  float age = t - k;  // 0-1 of its life
  bool born = hash(c + vec2(k * 0.37, 3.1)) < spray_share;
  vec2 at = (c + vec2(hash(c + vec2(1.3, k)), hash(c + vec2(k, 7.9)))) * cell + wind * (0.7 * age * life);
  float rise = sin(3.14159265 * age);
  vec3 world = vec3(at, water_level + spray_height * rise);
  float size = 0.5 + 1.0 * age;  // half its width
  vec4 eye = osg_ViewMatrix * vec4(world, 1.0);
  // drawn out along the wind, as the picture shows it: a streak 2.5 times as long as it is wide
  vec2 along = (osg_ViewMatrix * vec4(wind, 0.0, 0.0)).xy;
  along = dot(along, along) > 1e-4 ? normalize(along) : vec2(1.0, 0.0);
  eye.xy += (2.5 * gl_MultiTexCoord0.x * along + gl_MultiTexCoord0.y * vec2(-along.y, along.x)) * size;
  corner = gl_MultiTexCoord0.xy;
  float near = clamp(1.5 - length(eye.xyz) / 200.0, 0.0, 1.0);  // farther off it is the haze's
  opacity = (born && at.x > quay_edge + 1.0) ? 0.35 * rise * near : 0.0;
  fog = clamp(exp(-gl_Fog.density * length(eye.xyz)), 0.0, 1.0);
  gl_Position = gl_ProjectionMatrix * eye;
}
)";
constexpr char kSprayFragmentShader[] = R"(#version 120
uniform float sky_light;  // the light on the foam (update_water)
varying vec2 corner;
varying float opacity;
varying float fog;
void main() {
  float r2 = dot(corner, corner);
  float a = opacity * max(1.0 - r2, 0.0) * max(1.0 - r2, 0.0);
  if (a < 0.004) discard;
  vec3 colour = vec3(0.86, 0.89, 0.91) * sky_light;
  gl_FragColor = vec4(mix(gl_Fog.color.rgb, colour, fog), a);
}
)";
// A lit lamp seen as the eye sees one at night: a glow round it (a billboard at the lamp, half a metre across
// near and widening with distance so that a far lamp stays a few pixels), its brightness falling off as
// exp(-6 r^2) from the centre, added to the picture; a floodlight faces down, so it shows to an eye below it
// (fading out as the eye comes level with it, none from above); it fades in the fog.
constexpr char kLampVertexShader[] = R"(#version 120
uniform mat4 osg_ViewMatrix;
varying vec2 corner;
varying float shown;
void main() {
  vec4 eye = osg_ViewMatrix * gl_Vertex;
  float distance = length(eye.xyz);
  vec3 down = (osg_ViewMatrix * vec4(0.0, 0.0, -1.0, 0.0)).xyz;
  float facing = dot(-eye.xyz / max(distance, 1e-3), down);  // the cosine from its axis to the eye
  eye.xy += gl_MultiTexCoord0.xy * (0.3 + 0.004 * distance);
  corner = gl_MultiTexCoord0.xy;
  shown = smoothstep(-0.1, 0.3, facing) * clamp(exp(-gl_Fog.density * distance), 0.0, 1.0);
  gl_FrontColor = gl_Color;
  gl_Position = gl_ProjectionMatrix * eye;
}
)";
constexpr char kLampFragmentShader[] = R"(#version 120
varying vec2 corner;
varying float shown;
void main() {
  float glow = exp(-6.0 * dot(corner, corner)) * shown;
  if (glow < 0.004) discard;
  gl_FragColor = vec4(gl_Color.rgb * glow, 1.0);
}
)";
// The water's shading per pixel: the normal from the slopes of the swell and the wind sea (interpolated
// from the grid's vertices, the wind sea faded where the grid is too coarse to carry it), the sky it mirrors
// by Fresnel's reflectance (Schlick's approximation, R0 = 0.02 for water) over the deep water's colour, the
// sun's glint, then the fog. World coordinates throughout (the grid is laid in them).
// The ropes' shading: their colour lit by the sky's ambient light and fogged per pixel like the lit scene
// (fixed-function fog on thin lines read crisp against a fading spreader).
constexpr char kRopeVertexShader[] = R"(#version 120
varying float fog_depth;
void main() {
  vec4 eye = gl_ModelViewMatrix * gl_Vertex;
  fog_depth = length(eye.xyz);
  gl_FrontColor = gl_Color;
  gl_Position = gl_ProjectionMatrix * eye;
}
)";
constexpr char kRopeFragmentShader[] = R"(#version 120
varying float fog_depth;
void main() {
  float fog = clamp(exp(-gl_Fog.density * fog_depth), 0.0, 1.0);
  gl_FragColor = vec4(mix(gl_Fog.color.rgb, gl_Color.rgb, fog), 1.0);
}
)";
constexpr char kWaterVertexShader[] = R"(#version 120
varying vec3 world;
varying vec2 slope;
varying float fog;
varying vec2 foam;  // the crests' foam (0.5 at the breaking slope) and how much of the wind sea the grid carries
void main() {
  world = gl_Vertex.xyz;
  slope = gl_MultiTexCoord0.xy;
  foam = gl_MultiTexCoord1.xy;
  vec4 eye = gl_ModelViewMatrix * gl_Vertex;
  fog = clamp(exp(-gl_Fog.density * length(eye.xyz)), 0.0, 1.0);
  gl_Position = gl_ProjectionMatrix * eye;
}
)";
constexpr char kWaterFragmentShader[] = R"(#version 120
uniform vec3 eye_world;
uniform vec3 to_sun;
uniform vec3 horizon;
uniform vec3 zenith;
uniform vec3 deep;
uniform float daylight;
varying vec3 world;
uniform float sky_light;  // the light on the foam: daylight, and the floodlights' share at night
uniform float breaking;   // the share of the sea's surface white with foam (whitecaps)
uniform float crest_share;  // the share of it on the crests breaking now
uniform float time_s;
uniform vec2 wind_dir;    // where the wind blows towards (whitecaps streak along it)
float hash(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }
float value_noise(vec2 p) {  // smooth noise 0-1 on a unit lattice
  vec2 i = floor(p), t = fract(p);
  t = t * t * (3.0 - 2.0 * t);
  return mix(mix(hash(i), hash(i + vec2(1.0, 0.0)), t.x), mix(hash(i + vec2(0.0, 1.0)), hash(i + 1.0), t.x), t.y);
}
varying vec2 slope;
varying float fog;
varying vec2 foam;
// one layer of foam streaks: cells `size` metres (along the wind, across) apart, a share of them white at a
// time, each for a few seconds, its streak placed and sized at random within its cell, its edge ragged; white
// over `cover` of the sea on average (where a streak's edge is past half white); far off, where a pixel spans
// a cell or more, that mean instead of dots
float streaks(vec2 along_m, vec2 size, float layer, float cover, float noise) {
  const float kArea = 0.112;  // a streak's mean white area at its smallest, in cells
  float share = min(0.6, cover / kArea);
  float grow = sqrt(cover / max(share * kArea, 1e-6));
  vec2 at = along_m / size + layer * vec2(0.37, 0.61);
  at.x += hash(vec2(floor(at.y), layer));  // each row of cells shifted along the wind: no rows line up
  vec2 cell = floor(at);
  float born = floor(time_s / 3.0 + 7.0 * hash(cell + 13.0 * layer));
  // one hash a streak (a sine each is dear to a software renderer): whether it shows, and from its digits its
  // size and place
  float h = hash(cell + 17.0 * born + 31.0 * layer);
  float radius = 0.04 + grow * (0.15 + 0.075 * fract(h * 61.7));
  vec2 centre = 0.5 + max(0.5 - radius, 0.0) * (fract(h * vec2(127.3, 241.9)) - 0.5);
  float edge = length(fract(at) - centre) + 0.2 * (noise - 0.5);
  float white = h < share ? smoothstep(radius, radius - 0.08, edge) : 0.0;
  vec2 span = fwidth(along_m / size);  // not of `at`: it jumps between rows
  return mix(white, cover, smoothstep(0.35, 1.0, max(span.x, span.y)));
}
void main() {
  vec3 n = normalize(vec3(-slope, 1.0));
  vec3 v = normalize(eye_world - world);
  float cos_view = clamp(dot(n, v), 0.0, 1.0);
  vec3 r = 2.0 * cos_view * n - v;  // the reflected view ray: what the water mirrors
  r.z = max(r.z, 0.02);
  r = normalize(r);
  float m = 1.0 - cos_view;
  float f = 0.02 + 0.98 * m * m * m * m * m;
  vec3 sky = mix(horizon, zenith, sqrt(r.z));
  float glint = daylight * pow(max(dot(r, to_sun), 0.0), 400.0);
  vec3 colour = min((1.0 - f) * deep + f * sky + glint * vec3(1.0, 1.0, 0.9), vec3(1.0));
  // whitecaps cover a `breaking` share of the sea: the crests breaking now where the grid carries the wind
  // sea (their foam past the breaking slope, its edge broken by noise 1.5 m across so the grid's triangles do
  // not show), and the foam they leave as streaks along the wind in two layers of cells of two sizes (one
  // lattice of them shows as one), as many and as large as make crests and streaks together cover `breaking`
  float noise = value_noise((world.xy + 0.7 * time_s * wind_dir) / 1.5);
  float crest = foam.y * smoothstep(0.4, 0.6, foam.x + 0.4 * (noise - 0.5));
  float crests_here = crest_share * foam.y;
  float layer_cover = 1.0 - sqrt((1.0 - breaking) / (1.0 - crests_here));
  vec2 along = vec2(dot(world.xy, wind_dir), dot(world.xy, vec2(-wind_dir.y, wind_dir.x)));
  float patch = max(streaks(along, vec2(10.0, 1.6), 0.0, layer_cover, noise),
                    streaks(along, vec2(14.0, 2.2), 1.0, layer_cover, noise));
  colour = mix(colour, vec3(0.86, 0.89, 0.91) * sky_light, clamp(max(crest, patch), 0.0, 1.0));
  gl_FragColor = vec4(mix(gl_Fog.color.rgb, colour, fog), 1.0);
}
)";
// The cloud deck: each pixel's ray from the eye (`dir`, the dome's vertex) meets a flat deck 1,200 m up at
// `reach` metres; there the noise texture (two octaves of it, 5 km a tile) is the deck's density, cloud where
// it passes `threshold` (set for the cover), thicker the further past. Far off, where a pixel spans many
// tiles, the texture gives way to its mean, and the deck thins into the horizon's haze. Thicker cloud is
// darker underneath.
constexpr char kCloudVertexShader[] = R"(#version 120
varying vec3 dir;
void main() {
  dir = gl_Vertex.xyz;
  gl_Position = ftransform();
}
)";
constexpr char kCloudFragmentShader[] = R"(#version 120
uniform sampler2D cloud_noise;
uniform float threshold;
uniform float edge;   // the density past the threshold a cloud is opaque at
uniform float depth;  // and at its thickest
uniform vec3 to_sun;
uniform vec3 rim;     // the sun's light scattered forward through a thin cloud's edge (none in rain's deck)
uniform vec2 deck_shift_m;  // the eye's place over the ground less the deck's drift with the wind
uniform vec3 light;         // thin cloud's colour
uniform vec3 dark;          // thick cloud's base
uniform vec3 horizon;
varying vec3 dir;
void main() {
  vec3 d = normalize(dir);
  float reach = 1200.0 / max(d.z, 0.01);  // kCloudBase_m
  vec2 at = (deck_shift_m + d.xy * reach) / 5000.0;  // kCloudTile_m
  float n = 0.65 * texture2D(cloud_noise, at).r + 0.35 * texture2D(cloud_noise, at * 3.1 + 0.37).r;
  float far = smoothstep(8000.0, 40000.0, reach);
  n = mix(n, 0.5, far);
  float thickness = clamp((n - threshold) / depth, 0.0, 1.0);
  // a cloud's thin edge towards the sun glows with the sun's light scattered forward (its silver lining; at
  // dusk in the sun's colour)
  float towards = max(dot(d, to_sun), 0.0);
  vec3 colour = mix(mix(light, dark, thickness) + rim * (1.0 - thickness) * pow(towards, 8.0), horizon, 0.6 * far);
  float opaque = smoothstep(0.0, edge, n - threshold);
  gl_FragColor = vec4(colour, opaque * (1.0 - 0.6 * smoothstep(20000.0, 100000.0, reach)));
}
)";

// a dome of `radius` round its centre from `lowest` (rad) up to the zenith: `rings` rings of 48 segments, as
// triangle strips
osg::ref_ptr<osg::Geometry> dome_geometry(double radius, double lowest, int rings) {
  constexpr int kSegments = 48;
  osg::ref_ptr<osg::Geometry> dome = new osg::Geometry;
  dome->setUseDisplayList(false);
  dome->setUseVertexBufferObjects(true);
  osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array;
  for (int r = 0; r <= rings; ++r) {
    const double elevation = lowest + (kPi / 2.0 - lowest) * r / rings;
    for (int k = 0; k <= kSegments; ++k) {
      const double azimuth = 2.0 * kPi * k / kSegments;
      vertices->push_back(osg::Vec3(static_cast<float>(std::cos(elevation) * std::cos(azimuth)),
                                    static_cast<float>(std::cos(elevation) * std::sin(azimuth)),
                                    static_cast<float>(std::sin(elevation))) *
                          static_cast<float>(radius));
    }
  }
  for (int r = 0; r < rings; ++r) {
    osg::ref_ptr<osg::DrawElementsUShort> strip = new osg::DrawElementsUShort(GL_TRIANGLE_STRIP);
    for (int k = 0; k <= kSegments; ++k) {
      strip->push_back(static_cast<unsigned short>((r + 1) * (kSegments + 1) + k));
      strip->push_back(static_cast<unsigned short>(r * (kSegments + 1) + k));
    }
    dome->addPrimitiveSet(strip);
  }
  dome->setVertexArray(vertices);
  return dome;
}

// Tileable value noise over a `size` x `size` tile: `octaves` layers, the first of `cells_x` x `cells_y`
// lattice cells over the tile, each next twice as fine and half as strong (smoothstep between lattice
// values); 0-1, normalised by the layers' weights.
std::vector<double> tileable_noise(core::Rng& rng, int size, int cells_x, int cells_y, int octaves) {
  std::vector<double> sum(static_cast<std::size_t>(size * size), 0.0);
  double weight = 0.0, amplitude = 1.0;
  for (int octave = 0; octave < octaves; ++octave, cells_x *= 2, cells_y *= 2, amplitude *= 0.5) {
    std::vector<double> lattice(static_cast<std::size_t>(cells_x * cells_y));
    for (double& v : lattice)
      v = rng.uniform();
    const auto at = [&](int i, int j) {
      return lattice[static_cast<std::size_t>(((j % cells_y) + cells_y) % cells_y * cells_x +
                                              ((i % cells_x) + cells_x) % cells_x)];
    };
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double u = static_cast<double>(x) * cells_x / size, v = static_cast<double>(y) * cells_y / size;
        const int i = static_cast<int>(u), j = static_cast<int>(v);
        const double fx = u - i, fy = v - j;
        const double sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
        const double top = at(i, j) + (at(i + 1, j) - at(i, j)) * sx;
        const double bottom = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * sx;
        sum[static_cast<std::size_t>(y * size + x)] += amplitude * (top + (bottom - top) * sy);
      }
    weight += amplitude;
  }
  for (double& v : sum)
    v /= weight;
  return sum;
}

unsigned char byte_of(double v) {
  return static_cast<unsigned char>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}

// the cloud deck's thickness: four octaves from 4 cells a tile
osg::ref_ptr<osg::Image> cloud_noise() {
  constexpr int kSize = 256;
  core::Rng rng(0xC10D5);
  const std::vector<double> noise = tileable_noise(rng, kSize, 4, 4, 4);
  osg::ref_ptr<osg::Image> image = new osg::Image;
  image->allocateImage(kSize, kSize, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE);
  for (int k = 0; k < kSize * kSize; ++k)
    image->data()[k] = byte_of(noise[static_cast<std::size_t>(k)]);
  return image;
}

// The lit surfaces' detail, a 4 m tile: blotches 1 m down to 25 cm (red), a grain 12 down to 3 cm (green),
// and streaks 12 cm wide and 2 m long along the tile's second axis (blue: up an upright face), their
// contrast stretched (x 2 about the middle) so that the shader's thresholds find them.
osg::ref_ptr<osg::Image> surface_detail_texture() {
  constexpr int kSize = 256;
  core::Rng rng(0xDE7A1);
  const std::vector<double> blotches = tileable_noise(rng, kSize, 4, 4, 3);
  const std::vector<double> grain = tileable_noise(rng, kSize, 32, 32, 3);
  const std::vector<double> streaks = tileable_noise(rng, kSize, 32, 2, 3);
  osg::ref_ptr<osg::Image> image = new osg::Image;
  image->allocateImage(kSize, kSize, 1, GL_RGBA, GL_UNSIGNED_BYTE);
  for (std::size_t k = 0; k < blotches.size(); ++k) {
    unsigned char* texel = image->data() + 4 * k;
    texel[0] = byte_of(0.5 + 2.0 * (blotches[k] - 0.5));
    texel[1] = byte_of(0.5 + 2.0 * (grain[k] - 0.5));
    texel[2] = byte_of(0.5 + 2.0 * (streaks[k] - 0.5));
    texel[3] = 255;
  }
  return image;
}

}  // namespace

core::Vec3 sun_direction(double t_h, double day_of_year, double latitude_deg, double& elevation) {
  const double declination = 23.45 * kPi / 180.0 * std::sin(2.0 * kPi * (284.0 + day_of_year) / 365.0);
  const core::Vec3 d =
      sky_direction((t_h - 12.0) / 24.0 * 2.0 * kPi, declination, latitude_deg * kPi / 180.0);
  elevation = std::asin(std::clamp(d.z, -1.0, 1.0));
  return d;
}

core::Vec3 moon_direction(double t_h, double day_of_year, double latitude_deg, double& illuminated) {
  // the moon on the ecliptic, its elongation from the sun growing through a synodic month (5 deg of
  // inclination and the equation of time left out)
  const double sun_longitude = 2.0 * kPi * (day_of_year - 80.0) / 365.25;
  const double age = std::fmod(day_of_year + t_h / 24.0 - kNewMoonDay, kSynodicMonth_d) / kSynodicMonth_d;
  const double elongation = 2.0 * kPi * (age < 0.0 ? age + 1.0 : age);
  const double longitude = sun_longitude + elongation;
  const double declination = std::asin(std::sin(kObliquity) * std::sin(longitude));
  const double right_ascension = std::atan2(std::cos(kObliquity) * std::sin(longitude), std::cos(longitude));
  illuminated = (1.0 - std::cos(elongation)) / 2.0;
  return sky_direction(sidereal_angle(t_h, day_of_year) - right_ascension, declination,
                       latitude_deg * kPi / 180.0);
}

ImageGenerator::ImageGenerator(const scene::SceneDescription& scene, std::map<std::string, Visual> visuals,
                               int width, int height, std::optional<int> multisamples)
    : visuals_(std::move(visuals)), width_(width), height_(height) {
  context_ = std::make_unique<HeadlessContext>(width, height);
  const bool software = software_renderer(renderer());
  viewer_ = std::make_unique<osgViewer::Viewer>();
  viewer_->setUpViewerAsEmbeddedInWindow(0, 0, width, height);
  viewer_->setThreadingModel(osgViewer::Viewer::SingleThreaded);
  viewer_->setLightingMode(osg::View::NO_LIGHT);
  viewer_->getCamera()->setCullMask(~kInsetViews);
  build(scene);
  viewer_->setSceneData(frame_);
  image_ = new osg::Image;
  image_->allocateImage(width, height, 1, GL_RGB, GL_UNSIGNED_BYTE);
  viewer_->getCamera()->attach(osg::Camera::COLOR_BUFFER, image_.get());
  viewer_->realize();
  set_soft_shadows(!software);
  set_surface_detail(!software);
  if (const int samples = multisamples.value_or(software ? 0 : kDefaultMultisamples); samples > 1)
    draw_multisampled(samples);
}

void ImageGenerator::draw_multisampled(int samples) {
  // the picture is drawn into a framebuffer of our own with `samples` per pixel and resolved into a plain one
  // that is read (OSG's own multisampled camera target is refused as incomplete by Mesa); the pbuffer's
  // multisampled configurations draw one sample on Mesa's surfaceless platform
  osg::GraphicsContext* gc = viewer_->getCamera()->getGraphicsContext();
  const osg::GLExtensions* gl = osg::GLExtensions::Get(gc->getState()->getContextID(), true);
  if (!gl->isFrameBufferObjectSupported || !gl->isRenderbufferMultisampleSupported()) return;
  GLint most = 0;
  glGetIntegerv(GL_MAX_SAMPLES_EXT, &most);
  samples = std::min(samples, static_cast<int>(most));
  if (samples < 2) return;
  gl->glGenFramebuffers(2, framebuffers_.data());
  gl->glGenRenderbuffers(3, renderbuffers_.data());
  auto storage = [&](GLuint buffer, int count, GLenum format) {
    gl->glBindRenderbuffer(GL_RENDERBUFFER_EXT, buffer);
    gl->glRenderbufferStorageMultisample(GL_RENDERBUFFER_EXT, count, format, width_, height_);
  };
  storage(renderbuffers_[0], samples, GL_RGB8);
  storage(renderbuffers_[1], samples, GL_DEPTH_COMPONENT24);
  storage(renderbuffers_[2], 0, GL_RGB8);
  gl->glBindFramebuffer(GL_FRAMEBUFFER_EXT, framebuffers_[1]);
  gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER_EXT, GL_COLOR_ATTACHMENT0_EXT, GL_RENDERBUFFER_EXT,
                                renderbuffers_[2]);
  const bool resolve_complete =
      gl->glCheckFramebufferStatus(GL_FRAMEBUFFER_EXT) == GL_FRAMEBUFFER_COMPLETE_EXT;
  gl->glBindFramebuffer(GL_FRAMEBUFFER_EXT, framebuffers_[0]);
  gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER_EXT, GL_COLOR_ATTACHMENT0_EXT, GL_RENDERBUFFER_EXT,
                                renderbuffers_[0]);
  gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER_EXT, GL_DEPTH_ATTACHMENT_EXT, GL_RENDERBUFFER_EXT,
                                renderbuffers_[1]);
  if (!resolve_complete || gl->glCheckFramebufferStatus(GL_FRAMEBUFFER_EXT) != GL_FRAMEBUFFER_COMPLETE_EXT) {
    gl->glBindFramebuffer(GL_FRAMEBUFFER_EXT, 0);
    gl->glDeleteFramebuffers(2, framebuffers_.data());
    gl->glDeleteRenderbuffers(3, renderbuffers_.data());
    framebuffers_ = {};
    return;
  }
  multisamples_ = samples;
  // OSG draws into it wherever it would draw into the window (its render-to-texture passes rebind it after
  // them), and no longer reads the picture itself: render() resolves and reads it
  gc->setDefaultFboId(framebuffers_[0]);
  osg::Camera* camera = viewer_->getCamera();
  camera->detach(osg::Camera::COLOR_BUFFER);
  camera->setDrawBuffer(GL_COLOR_ATTACHMENT0_EXT);
  camera->setReadBuffer(GL_COLOR_ATTACHMENT0_EXT);
}

void ImageGenerator::read_multisampled() {
  const osg::GLExtensions* gl =
      osg::GLExtensions::Get(viewer_->getCamera()->getGraphicsContext()->getState()->getContextID(), true);
  gl->glBindFramebuffer(GL_READ_FRAMEBUFFER_EXT, framebuffers_[0]);
  gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER_EXT, framebuffers_[1]);
  gl->glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl->glBindFramebuffer(GL_READ_FRAMEBUFFER_EXT, framebuffers_[1]);
  glReadBuffer(GL_COLOR_ATTACHMENT0_EXT);
  image_->readPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE);
  gl->glBindFramebuffer(GL_FRAMEBUFFER_EXT, framebuffers_[0]);
}

ImageGenerator::~ImageGenerator() = default;

std::string ImageGenerator::renderer() const {
  return context_->renderer();
}

void ImageGenerator::set_soft_shadows(bool on) {
  soft_shadows_->set(on);
}

void ImageGenerator::set_surface_detail(bool on) {
  surface_detail_ = on;
  for (osg::Group* lit : {static_cast<osg::Group*>(shadowed_.get()), unshadowed_.get()})
    lit->getOrCreateStateSet()->setAttribute(lit_programs_[0][on][cloud_shade_]);
  for (const osg::ref_ptr<osg::StateSet>& quay : quay_states_)
    if (quay->getAttribute(osg::StateAttribute::PROGRAM))
      quay->setAttribute(lit_programs_[1][on][cloud_shade_]);
}

bool ImageGenerator::surface_detail() const {
  return surface_detail_;
}

std::vector<double> ImageGenerator::tyre_angles() const {
  std::vector<double> angles;
  for (const TurningPart& part : turning_parts_)
    if (part.speed_indicator >= 0) angles.push_back(part.rolled_rad);
  return angles;
}

int ImageGenerator::multisamples() const {
  return multisamples_;
}

bool ImageGenerator::soft_shadows() const {
  bool on = false;
  soft_shadows_->get(on);
  return on;
}

bool software_renderer(const std::string& renderer) {
  for (const char* software : {"llvmpipe", "softpipe", "swrast", "Software Rasterizer"})
    if (renderer.find(software) != std::string::npos) return true;
  return false;
}

// the sun and the lit scene's state: shadows from the sun for the main view, none for the insets; fog
void ImageGenerator::build_lighting() {
  osg::StateSet* state = root_->getOrCreateStateSet();
  sun_ = new osg::LightSource;
  sun_->getLight()->setLightNum(0);
  root_->addChild(sun_);
  state->setMode(GL_LIGHTING, osg::StateAttribute::ON);
  state->setMode(GL_LIGHT0, osg::StateAttribute::ON);
  state->setMode(GL_NORMALIZE, osg::StateAttribute::ON);
  osg::ref_ptr<osg::LightModel> no_global_ambient = new osg::LightModel;  // all ambient light is the sky's
  no_global_ambient->setAmbientIntensity(osg::Vec4(0.0f, 0.0f, 0.0f, 1.0f));
  state->setAttributeAndModes(no_global_ambient);
  // solids show their outsides only: from the seat, the cab's own walls are not drawn and the world shows
  // through them (its windows), while the bonnet and the mirror arms ahead of them are
  state->setMode(GL_CULL_FACE, osg::StateAttribute::ON);
  osg::ref_ptr<osg::Material> material = new osg::Material();
  material->setColorMode(osg::Material::AMBIENT_AND_DIFFUSE);  // the geometry's colours, lit
  state->setAttribute(material);
  // what the sun lights: the quay and every entity, casting and receiving the sun's shadows
  {
    osg::ref_ptr<osgShadow::ShadowSettings> settings = new osgShadow::ShadowSettings;
    settings->setLightNum(0);
    settings->setShaderHint(osgShadow::ShadowSettings::NO_SHADERS);  // the lit scene's own shading, below
    settings->setBaseShadowTextureUnit(1);
    settings->setTextureSize(osg::Vec2s(1024, 1024));
    settings->setMaximumShadowMapDistance(600.0);
    settings->setShadowMapProjectionHint(osgShadow::ShadowSettings::ORTHOGRAPHIC_SHADOW_MAP);
    settings->setCastsShadowTraversalMask(kCastsShadow);
    shadowed_ = new osgShadow::ShadowedScene(new osgShadow::ViewDependentShadowMap);
    shadowed_->setShadowSettings(settings);
    // the lit shaders' four programs: dry or wet (the film), plain or with surface detail
    for (const bool wet : {false, true})
      for (const bool detail : {false, true})
        for (const bool clouds : {false, true}) {
          const std::string defines = std::string("#version 120\n") + (wet ? "#define WET\n" : "") +
                                      (detail ? "#define DETAIL\n" : "") + (clouds ? "#define CLOUDS\n" : "");
          osg::ref_ptr<osg::Program>& program = lit_programs_[wet][detail][clouds];
          program = new osg::Program;
          program->addShader(new osg::Shader(osg::Shader::VERTEX, defines + kLitVertexShader));
          program->addShader(new osg::Shader(osg::Shader::FRAGMENT, defines + kLitFragmentShader));
        }
    osg::StateSet* lit = shadowed_->getOrCreateStateSet();
    floodlights_on_ = new osg::Uniform("floodlights", 0);
    lit->addUniform(floodlights_on_);
    lit->addUniform(new osg::Uniform("sun_shadows", true));
    soft_shadows_ = new osg::Uniform("soft_shadows", false);
    lit->addUniform(soft_shadows_);
    // rain's water on the surfaces (0 dry, 1 wet through) and the quay's water film's
    wetness_ = new osg::Uniform("wetness", 0.0f);
    lit->addUniform(wetness_);
    sun_seen_ = new osg::Uniform("sun_seen", 1.0f);
    lit->addUniform(sun_seen_);
    film_ = {new osg::Uniform("splash_rate", 0.0f), new osg::Uniform("time_s", 0.0f),
             new osg::Uniform("sky_horizon", osg::Vec3()), new osg::Uniform("sky_zenith", osg::Vec3())};
    for (const osg::ref_ptr<osg::Uniform>& u : film_)
      lit->addUniform(u);
    osg::ref_ptr<osg::Uniform> finishes =
        new osg::Uniform(osg::Uniform::FLOAT_VEC4, "finishes", static_cast<int>(kSurfaceFinishes.size()));
    for (std::size_t k = 0; k < kSurfaceFinishes.size(); ++k) {
      const SurfaceFinish& f = kSurfaceFinishes[k];
      finishes->setElement(static_cast<unsigned>(k),
                           osg::Vec4(f.roughness, f.metalness, f.texture, f.weathering));
    }
    lit->addUniform(finishes);
    // the surfaces' detail texture on unit 2 (the shadow map's is 1), mipmapped: the grain fades to flat
    // with distance instead of shimmering
    osg::ref_ptr<osg::Texture2D> detail = new osg::Texture2D(surface_detail_texture());
    detail->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    detail->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    detail->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
    detail->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    osg::ref_ptr<osg::Uniform> detail_unit = new osg::Uniform("detail_texture", 2);
    lit->setTextureAttribute(2, detail);
    lit->addUniform(detail_unit);
    // the cloud deck's density on unit 3, for the clouds' shade on the ground
    cloud_texture_ = new osg::Texture2D(cloud_noise());
    cloud_texture_->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    cloud_texture_->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    cloud_texture_->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
    cloud_texture_->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    osg::ref_ptr<osg::Uniform> cloud_unit = new osg::Uniform("cloud_noise", 3);
    cloud_deck_ = new osg::Uniform("cloud_deck", osg::Vec4(2.0f, 0.1f, 0.0f, 0.0f));
    lit->setTextureAttribute(3, cloud_texture_);
    lit->addUniform(cloud_unit);
    lit->addUniform(cloud_deck_);
    // the same nodes lit the same way but without a shadow pass, for the insets: a camera drawing the
    // shadowed scene draws a 1024^2 shadow map of its own, which cost an inset more than its picture
    shadowed_->setNodeMask(kMainView | kCastsShadow);  // the shadow pass bounds its casters from here
    unshadowed_ = new osg::Group;
    unshadowed_->setNodeMask(kInsetViews);
    osg::StateSet* inset_lit = unshadowed_->getOrCreateStateSet();
    inset_lit->addUniform(floodlights_on_);
    inset_lit->addUniform(new osg::Uniform("sun_shadows", false));
    for (const osg::ref_ptr<osg::Uniform>& u : film_)
      inset_lit->addUniform(u);
    inset_lit->addUniform(finishes);
    inset_lit->addUniform(wetness_);
    inset_lit->addUniform(sun_seen_);
    inset_lit->setTextureAttribute(2, detail);
    inset_lit->addUniform(detail_unit);
    inset_lit->setTextureAttribute(3, cloud_texture_);
    inset_lit->addUniform(cloud_unit);
    inset_lit->addUniform(cloud_deck_);
  }
  fog_ = new osg::Fog;
  fog_->setMode(osg::Fog::EXP);
  fog_->setFogCoordinateSource(osg::Fog::FRAGMENT_DEPTH);
  state->setAttributeAndModes(fog_, osg::StateAttribute::ON);
}

// the sky: a dome round the eye, drawn first, unlit, unfogged, behind everything
void ImageGenerator::build_sky() {
  {
    osg::ref_ptr<osg::Geometry> dome = dome_geometry(4000.0, -0.2, 16);
    const auto& vertices = static_cast<const osg::Vec3Array&>(*dome->getVertexArray());
    sky_directions_ = new osg::Vec3Array;
    sky_colors_ = new osg::Vec4Array;
    for (const osg::Vec3& v : vertices) {
      sky_directions_->push_back(v / v.length());
      sky_colors_->push_back(osg::Vec4(0.5f, 0.6f, 0.9f, 1.0f));
    }
    dome->setColorArray(sky_colors_, osg::Array::BIND_PER_VERTEX);
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(dome);
    osg::StateSet* sky_state = geode->getOrCreateStateSet();
    sky_state->setMode(GL_LIGHTING, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
    sky_state->setMode(GL_FOG, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
    sky_state->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
    sky_state->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false));
    sky_state->setRenderBinDetails(-3, "RenderBin");
    sky_ = new osg::MatrixTransform;
    sky_->setCullingActive(false);
    sky_->addChild(geode);
    root_->addChild(sky_);

    // stars (fixed on the celestial sphere, turned by the sidereal angle) and the moon with its phase, on
    // the dome after the sky, faded in by the dark
    core::Rng rng(0x57A125);
    star_positions_.resize(kStars);
    for (auto& [right_ascension, declination, brightness] : star_positions_) {
      right_ascension = rng.uniform(0.0, 2.0 * kPi);
      declination = std::asin(rng.uniform(-1.0, 1.0));
      brightness = 0.25 + 0.75 * std::pow(rng.uniform(), 4.0);  // few bright, many faint
    }
    const auto sky_points = [&](GLenum mode, int count) {
      osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
      g->setUseDisplayList(false);
      g->setUseVertexBufferObjects(true);
      g->setDataVariance(osg::Object::DYNAMIC);
      g->setVertexArray(new osg::Vec3Array(count));
      g->setColorArray(new osg::Vec4Array(count), osg::Array::BIND_PER_VERTEX);
      g->addPrimitiveSet(new osg::DrawArrays(mode, 0, count));
      return g;
    };
    stars_ = sky_points(GL_POINTS, kStars);
    moon_ = sky_points(GL_TRIANGLES, kMoonRings * kMoonSegments * 6);
    osg::ref_ptr<osg::Geode> night = new osg::Geode;
    night->addDrawable(stars_);
    night->addDrawable(moon_);
    osg::StateSet* night_state = night->getOrCreateStateSet();
    night_state->setMode(GL_LIGHTING, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
    night_state->setMode(GL_FOG, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
    night_state->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
    night_state->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false));
    night_state->setAttributeAndModes(new osg::Point(2.0f));
    night_state->setRenderBinDetails(-2, "RenderBin");
    sky_->addChild(night);
  }
  build_clouds();
}

// the cloud deck: 1,200 m up seen through the dome (each pixel's ray meets it), its density from a tileable
// noise texture, drifting with the wind; in front of the stars, behind everything else
void ImageGenerator::build_clouds() {
  osg::ref_ptr<osg::Geometry> deck = dome_geometry(3800.0, 0.01, 12);  // inside the sky's dome
  clouds_ = new osg::Geode;
  clouds_->addDrawable(deck);
  clouds_->setNodeMask(0u);  // clear until cloud comes
  // the deck's densities over a tile (off the texels, as the sky's rays meet it), sorted: the share of the
  // sky a threshold leaves clear
  constexpr int kSamples = 192;
  cloud_densities_.clear();
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i)
      cloud_densities_.push_back(
          cloud_density((i + 0.37) * kCloudTile_m / kSamples, (j + 0.61) * kCloudTile_m / kSamples));
  std::sort(cloud_densities_.begin(), cloud_densities_.end());
  osg::StateSet* state = clouds_->getOrCreateStateSet();
  state->setTextureAttributeAndModes(0, cloud_texture_);
  osg::ref_ptr<osg::Program> program = new osg::Program;
  program->addShader(new osg::Shader(osg::Shader::VERTEX, kCloudVertexShader));
  program->addShader(new osg::Shader(osg::Shader::FRAGMENT, kCloudFragmentShader));
  state->setAttribute(program);
  state->addUniform(new osg::Uniform("cloud_noise", 0));
  cloud_uniforms_ = {new osg::Uniform("threshold", 1.0f),      new osg::Uniform("deck_shift_m", osg::Vec2()),
                     new osg::Uniform("light", osg::Vec3()),   new osg::Uniform("dark", osg::Vec3()),
                     new osg::Uniform("horizon", osg::Vec3()), new osg::Uniform("edge", 0.12f),
                     new osg::Uniform("depth", 0.6f),          new osg::Uniform("to_sun", osg::Vec3(0, 0, 1)),
                     new osg::Uniform("rim", osg::Vec3())};
  for (const osg::ref_ptr<osg::Uniform>& u : cloud_uniforms_)
    state->addUniform(u);
  state->setMode(GL_LIGHTING, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
  state->setMode(GL_FOG, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
  state->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
  state->setMode(GL_BLEND, osg::StateAttribute::ON);
  state->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false));
  state->setRenderBinDetails(-1, "RenderBin");
  sky_->addChild(clouds_);
}

double ImageGenerator::cloud_density(double x_m, double y_m) const {
  // as the shader samples it: bilinear, repeating, two octaves
  const osg::Image& noise = *cloud_texture_->getImage();
  const int size = noise.s();
  const auto texture = [&](double u, double v) {
    const double x = u * size - 0.5, y = v * size - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const auto texel = [&](double i, double j) {
      const auto wrap = [size](double k) { return static_cast<int>(k - size * std::floor(k / size)); };
      return noise.data(wrap(i), wrap(j))[0] / 255.0;
    };
    const double a = x - fx, b = y - fy;
    return (1 - a) * (1 - b) * texel(fx, fy) + a * (1 - b) * texel(fx + 1, fy) +
           (1 - a) * b * texel(fx, fy + 1) + a * b * texel(fx + 1, fy + 1);
  };
  const double u = x_m / kCloudTile_m, v = y_m / kCloudTile_m;
  return 0.65 * texture(u, v) + 0.35 * texture(u * 3.1 + 0.37, v * 3.1 + 0.37);
}

// the quay (its top at z = 0, up to its edge at x = 18 m), the rain, the harbour's water beyond
void ImageGenerator::build_quay_and_water() {
  osg::ref_ptr<osg::Geode> apron = tessellated_plane(-60.0, kQuayEdge_m, -80.0, 80.0, 0.0, 3.0, kQuayPaving);
  quay_states_.push_back(apron->getOrCreateStateSet());
  apron->setNodeMask(kReceivesOnly);
  add_lit(apron);
  for (const auto& [x0, x1, y0, y1] :
       {std::array{-300.0, -60.0, -400.0, 400.0}, std::array{-60.0, kQuayEdge_m, -400.0, -80.0},
        std::array{-60.0, kQuayEdge_m, 80.0, 400.0}}) {
    osg::ref_ptr<osg::Geode> part = tessellated_plane(x0, x1, y0, y1, 0.0, 20.0, kQuayPaving);
    quay_states_.push_back(part->getOrCreateStateSet());
    part->setNodeMask(kReceivesOnly);
    add_lit(part);
  }
  rain_ = new osgParticle::PrecipitationEffect;
  rain_->setNodeMask(0);  // dry until the weather says otherwise
  root_->addChild(rain_);
  // the water: a grid round the eye moved every frame, over a flat sea to the horizon (below its troughs)
  far_water_ = new osg::MatrixTransform;
  far_water_->addChild(
      tessellated_plane(-4000.0, 4000.0, -4000.0, 4000.0, -4.0, 400.0, rgba({0.04, 0.12, 0.17})));
  // the water after everything solid, the far sea after the near: a pixel something hides is never shaded
  // (the depth test runs before the shader; a software rasteriser spends most of a frame shading)
  far_water_->getOrCreateStateSet()->setRenderBinDetails(kFarWaterBin, "RenderBin");
  root_->addChild(far_water_);
  {
    water_ = new osg::Geometry;
    water_->setUseDisplayList(false);
    water_->setUseVertexBufferObjects(true);
    water_->setDataVariance(osg::Object::DYNAMIC);
    const int row = kWaterColumns + 1;
    const auto points = static_cast<unsigned>(row * (kWaterRows + 1));
    water_->setVertexArray(new osg::Vec3Array(points));
    water_->setTexCoordArray(0, new osg::Vec2Array(points), osg::Array::BIND_PER_VERTEX);  // the slope
    water_->setTexCoordArray(1, new osg::Vec2Array(points), osg::Array::BIND_PER_VERTEX);  // whitecaps
    for (int j = 0; j < kWaterRows; ++j) {
      osg::ref_ptr<osg::DrawElementsUShort> strip = new osg::DrawElementsUShort(GL_TRIANGLE_STRIP);
      for (int i = 0; i <= kWaterColumns; ++i) {
        strip->push_back(static_cast<unsigned short>((j + 1) * row + i));
        strip->push_back(static_cast<unsigned short>(j * row + i));
      }
      water_->addPrimitiveSet(strip);
    }
    water_->setCullingActive(false);  // it moves with the eye
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(water_);
    osg::StateSet* shading = geode->getOrCreateStateSet();
    shading->setRenderBinDetails(kWaterBin, "RenderBin");
    shading->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    shading->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->addShader(new osg::Shader(osg::Shader::VERTEX, kWaterVertexShader));
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, kWaterFragmentShader));
    shading->setAttribute(program);
    shading->addUniform(new osg::Uniform("daylight", 0.0f));
    shading->addUniform(new osg::Uniform("sky_light", 0.0f));
    shading->addUniform(new osg::Uniform("breaking", 0.0f));
    shading->addUniform(new osg::Uniform("crest_share", 0.0f));
    shading->addUniform(new osg::Uniform("time_s", 0.0f));
    shading->addUniform(new osg::Uniform("wind_dir", osg::Vec2(1.0f, 0.0f)));
    for (const char* name : {"eye_world", "to_sun", "horizon", "zenith", "deep"})
      shading->addUniform(new osg::Uniform(name, osg::Vec3(0.0f, 0.0f, 1.0f)));
    water_shading_ = shading;
    root_->addChild(geode);
  }
}

// every entity from its look, the machine's own boxes from its looks' parts
void ImageGenerator::build_entities(const scene::SceneDescription& scene) {
  for (const scene::SceneDescription::Entity& e : scene.entities)
    entity_visuals_.push_back(e.visual);
  entity_poses_.assign(scene.entities.size(), core::Pose{});
  // the machine's own entities' boxes, from their looks' parts (an entity drawn from parts alone has no
  // size of its own)
  for (int n = 0; n < scene.machine_entities && n < static_cast<int>(scene.entities.size()); ++n) {
    const scene::SceneDescription::Entity& e = scene.entities[static_cast<std::size_t>(n)];
    core::Vec3 low = e.half_extents_m * -1.0, high = e.half_extents_m;
    if (const auto look = visuals_.find(e.visual); look != visuals_.end())
      for (const VisualPart& part : look->second.parts) {
        const core::Vec3 half = part.size_m ? *part.size_m * 0.5 : e.half_extents_m;
        low = {std::min(low.x, part.centre_m.x - half.x), std::min(low.y, part.centre_m.y - half.y),
               std::min(low.z, part.centre_m.z - half.z)};
        high = {std::max(high.x, part.centre_m.x + half.x), std::max(high.y, part.centre_m.y + half.y),
                std::max(high.z, part.centre_m.z + half.z)};
      }
    machine_boxes_.emplace_back((low + high) * 0.5, (high - low) * 0.5);
  }
  models_ = std::make_unique<ModelCache>();
  description_ = scene;
  for (const scene::SceneDescription::Entity& e : scene.entities) {
    osg::ref_ptr<osg::MatrixTransform> transform = new osg::MatrixTransform();
    draw_entity(*transform, e, scene.indicators);
    add_lit(transform);
    entities_.push_back(transform);
  }
  root_->addChild(shadowed_);
  root_->addChild(unshadowed_);
}

void ImageGenerator::rename_entity(std::size_t index, const std::string& name) {
  if (index >= entities_.size() || description_.entities[index].name == name) return;
  scene::SceneDescription::Entity& e = description_.entities[index];
  // (a look with parts that turn or roll is a machine's part, drawn once: its parts are registered to turn)
  if (const auto look = visuals_.find(e.visual); look != visuals_.end())
    for (const VisualPart& part : look->second.parts)
      if (part.turn || part.slide || part.shape == VisualPart::Shape::kSpreader || !part.rolls_with.empty())
        return;
  e.name = name;
  osg::MatrixTransform& transform = *entities_[index];
  transform.removeChildren(0, transform.getNumChildren());
  draw_entity(transform, e, description_.indicators);
}

// an entity's look as drawn in its frame: its parts (a livery by its name), a container's code where it is
// marked
void ImageGenerator::draw_entity(osg::MatrixTransform& transform_node,
                                 const scene::SceneDescription::Entity& e,
                                 const std::vector<std::string>& indicators) {
  osg::ref_ptr<osg::MatrixTransform> transform = &transform_node;
  ModelCache& models = *models_;
  const auto look = visuals_.find(e.visual);
  osg::ref_ptr<osg::Geode> geode = new osg::Geode();
  MeshBuilder fixed;
  if (look != visuals_.end()) {
    // a spreader or a deckhouse drawn as its parts
    std::vector<VisualPart> parts;
    for (const VisualPart& part : look->second.parts) {
      const std::vector<VisualPart> pieces =
          drawn_parts(part, part.size_m ? *part.size_m : e.half_extents_m * 2.0);
      parts.insert(parts.end(), pieces.begin(), pieces.end());
    }
    for (const VisualPart& part : parts) {
      const core::Vec3 size = part.size_m ? *part.size_m : e.half_extents_m * 2.0;
      const core::Vec3 color =
          part.livery ? look->second.liveries[scene::livery_key(e.name) % look->second.liveries.size()]
                      : part.color;
      const osg::Vec4 paint = finished(rgba(color), part.surface);
      // a part turned or turning has a transform of its own, and is drawn about its origin in it
      const bool own_frame =
          part.yaw_rad != 0.0 || part.turn.has_value() || part.slide.has_value() || !part.rolls_with.empty();
      osg::ref_ptr<osg::MatrixTransform> frame = transform;
      osg::ref_ptr<osg::Geode> drawables = geode;
      core::Vec3 centre = part.centre_m;
      if (own_frame) {
        const osg::Matrixd placed = osg::Matrixd::rotate(part.yaw_rad, osg::Vec3d(0.0, 0.0, 1.0)) *
                                    osg::Matrixd::translate(to_osg(part.centre_m));
        frame = new osg::MatrixTransform(placed);
        drawables = new osg::Geode;
        frame->addChild(drawables);
        transform->addChild(frame);
        centre = {};
        auto indicator = [&](const std::string& name) {
          const auto at = std::find(indicators.begin(), indicators.end(), name);
          return at == indicators.end() ? -1 : static_cast<int>(at - indicators.begin());
        };
        TurningPart moving{frame, placed};
        if (part.turn) {
          moving.turn = *part.turn;
          moving.indicator = indicator(part.turn->indicator);
          if (part.turn->pivot_m) {  // into the part's frame, turned by its yaw
            const core::Vec3 offset = *part.turn->pivot_m - part.centre_m;
            moving.pivot = osg::Matrixd::rotate(-part.yaw_rad, osg::Vec3d(0.0, 0.0, 1.0))
                               .preMult(osg::Vec3d(offset.x, offset.y, offset.z));
          }
        }
        if (part.slide) {
          moving.slide = *part.slide;
          moving.slide_indicator = indicator(part.slide->indicator);
        }
        if (!part.rolls_with.empty()) {
          moving.speed_indicator = indicator(part.rolls_with);
          moving.rolls_unit_mps = part.rolls_unit_mps;
          moving.roll_axis = to_osg(core::cross(core::Vec3{0.0, 0.0, 1.0}, part.rolls_along));
          moving.radius_m = 0.5 * (tyre_axis(size) == 0 ? size.y : size.x);  // its diameter, twice
        }
        if (moving.indicator >= 0 || moving.speed_indicator >= 0 || moving.slide_indicator >= 0)
          turning_parts_.push_back(moving);
      }
      if (part.shape == VisualPart::Shape::kMesh) {
        osg::ref_ptr<osg::Node> mesh = read_mesh(part.mesh);
        if (!mesh) throw std::runtime_error("osgDB could not read the mesh " + part.mesh);
        paint_uncoloured(*mesh, paint);
        use_buffer_objects(*mesh);
        osg::ref_ptr<osg::MatrixTransform> placed =
            new osg::MatrixTransform(osg::Matrixd::scale(part.scale, part.scale, part.scale) *
                                     osg::Matrixd::translate(to_osg(centre)));
        placed->addChild(mesh);
        frame->addChild(placed);
        continue;
      }
      // the fixed parts' boxes, lattices and steelwork drawn as one mesh (a draw each costs more than its
      // triangles); a part in a frame of its own, a mesh of its own
      MeshBuilder own_mesh;
      MeshBuilder& mesh = own_frame ? own_mesh : fixed;
      const auto into_mesh = [&] {
        if (own_frame && !own_mesh.empty()) drawables->addDrawable(own_mesh.build());
      };
      if (part.shape == VisualPart::Shape::kLattice) {
        add_lattice(mesh, centre, size, part.bay_m, part.member_m, paint);
        into_mesh();
        continue;
      }
      if (part.shape == VisualPart::Shape::kBox) {
        mesh.box(to_osg(centre), to_osg(size * 0.5), paint);
        into_mesh();
        continue;
      }
      if (osg::ref_ptr<osg::Geometry> steelwork = structure(part, size, paint)) {
        mesh.append(*steelwork, to_osg(centre));
        into_mesh();
        continue;
      }
      if (part.shape != VisualPart::Shape::kBox) {  // a procedural model, built about its origin
        osg::ref_ptr<osg::Node> model;
        if (part.shape == VisualPart::Shape::kContainer || part.shape == VisualPart::Shape::kTyre) {
          model = models.detailed(part, size, color);
        } else {
          osg::ref_ptr<osg::Geode> holder = new osg::Geode;
          holder->addDrawable(part.shape == VisualPart::Shape::kShell
                                  ? clamshell(size, part.hinge_m, paint)
                                  : hull(size, paint, finished(rgba(part.bottom_color), part.surface),
                                         part.waterline_m,
                                         part.deck_color ? finished(rgba(*part.deck_color), part.surface)
                                                         : osg::Vec4(0, 0, 0, 0),
                                         part.deck_open_from_m, part.deck_open_to_m));
          model = holder;
        }
        osg::ref_ptr<osg::MatrixTransform> placed =
            new osg::MatrixTransform(osg::Matrixd::translate(to_osg(centre)));
        placed->addChild(model);
        frame->addChild(placed);
        continue;
      }
    }
  }
  if (!fixed.empty()) geode->addDrawable(fixed.build());
  if (look != visuals_.end() && look->second.name_marked) {
    // the name (a container's ISO code) where ISO 6346 marks it, each facing out: high on both long sides
    // reading along the box, high on both ends reading across it, and on the roof, larger, for the crane
    // driver looking down (x along the length, y across, z up; text lies in its xy plane reading along x)
    const osg::Vec3 half = to_osg(e.half_extents_m);
    const osg::Quat upright(osg::PI_2, osg::Vec3(1, 0, 0));  // onto the -y side, reading along +x
    const osg::Quat turn_z_90(osg::PI_2, osg::Vec3(0, 0, 1)), turn_z_180(osg::PI, osg::Vec3(0, 0, 1)),
        turn_z_270(-osg::PI_2, osg::Vec3(0, 0, 1));
    const float high = half.z() * 0.55f;
    const struct {
      osg::Quat rotation;
      osg::Vec3 at;
      float size;
    } marks[] = {{upright, {0.0f, -half.y() - 0.01f, high}, 0.32f},
                 {upright * turn_z_180, {0.0f, half.y() + 0.01f, high}, 0.32f},
                 {upright * turn_z_90, {half.x() + 0.01f, 0.0f, high}, 0.2f},  // 2.44 m across
                 {upright * turn_z_270, {-half.x() - 0.01f, 0.0f, high}, 0.2f},
                 {osg::Quat(), {0.0f, 0.0f, half.z() + 0.01f}, 0.45f}};
    for (const auto& mark : marks) {
      osg::ref_ptr<osgText::Text> label = new osgText::Text;
      label->setText(e.name);
      label->setCharacterSize(mark.size);
      label->setColor(osg::Vec4(0.95f, 0.95f, 0.95f, 1.0f));
      label->setAlignment(osgText::Text::CENTER_CENTER);
      label->setAxisAlignment(osgText::Text::USER_DEFINED_ROTATION);
      label->setRotation(mark.rotation);
      label->setPosition(mark.at);
      geode->addDrawable(label);
    }
  }
  transform->addChild(geode);
}

namespace {
// lines of one colour whose points change every frame (none yet)
osg::ref_ptr<osg::Geometry> moving_lines(GLenum mode, const osg::Vec4& colour) {
  osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry();
  geometry->setUseDisplayList(false);
  geometry->setUseVertexBufferObjects(true);
  geometry->setDataVariance(osg::Object::DYNAMIC);
  geometry->setVertexArray(new osg::Vec3Array);
  osg::ref_ptr<osg::Vec4Array> colors = new osg::Vec4Array();
  colors->push_back(colour);
  geometry->setColorArray(colors, osg::Array::BIND_OVERALL);
  geometry->addPrimitiveSet(new osg::DrawArrays(mode, 0, 0));
  return geometry;
}
}  // namespace

// the ropes: one line strip each, moved every frame
void ImageGenerator::build_ropes(const scene::SceneDescription& scene) {
  osg::ref_ptr<osg::Geode> ropes = new osg::Geode();
  ropes->getOrCreateStateSet()->setAttributeAndModes(new osg::LineWidth(2.0f));
  ropes->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
  {
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->addShader(new osg::Shader(osg::Shader::VERTEX, kRopeVertexShader));
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, kRopeFragmentShader));
    ropes->getOrCreateStateSet()->setAttribute(program);
  }
  for (int r = 0; r < scene.rope_count; ++r) {
    osg::ref_ptr<osg::Geometry> geometry = moving_lines(GL_LINE_STRIP, osg::Vec4(0.08f, 0.08f, 0.08f, 1.0f));
    ropes->addDrawable(geometry);
    ropes_.push_back(geometry);
  }
  ropes_geode_ = ropes;
  root_->addChild(ropes);
}

// the festoons: their cables' loops and the carriers' hangers as lines, drawn as the ropes are
void ImageGenerator::set_festoons(const std::vector<Festoon>& festoons) {
  for (const auto& geometry : festoons_)
    ropes_geode_->removeDrawable(geometry);
  festoons_.clear();
  // those whose ends this scene has
  festoon_settings_.clear();
  const auto in_scene = [&](const std::string& look) {
    return std::find(entity_visuals_.begin(), entity_visuals_.end(), look) != entity_visuals_.end();
  };
  for (const Festoon& festoon : festoons)
    if (in_scene(festoon.from_entity) && in_scene(festoon.to_entity)) festoon_settings_.push_back(festoon);
  for (std::size_t n = 0; n < festoon_settings_.size(); ++n) {
    osg::ref_ptr<osg::Geometry> geometry = moving_lines(GL_LINES, osg::Vec4(0.05f, 0.05f, 0.05f, 1.0f));
    ropes_geode_->addDrawable(geometry);
    festoons_.push_back(geometry);
  }
  update_festoons();
}

// each festoon between its ends as they ride their entities: carriers spread evenly on the level track
// between them, a loop of cable from each to the next
void ImageGenerator::update_festoons() {
  constexpr float kHanger = 0.35f, kCableGap = 0.09f, kClosest = 0.2f;
  constexpr int kLoopPoints = 9;
  for (std::size_t n = 0; n < festoons_.size(); ++n) {
    const Festoon& festoon = festoon_settings_[n];
    auto* vertices = static_cast<osg::Vec3Array*>(festoons_[n]->getVertexArray());
    vertices->clear();
    const auto from = std::find(entity_visuals_.begin(), entity_visuals_.end(), festoon.from_entity);
    const auto to = std::find(entity_visuals_.begin(), entity_visuals_.end(), festoon.to_entity);
    if (from != entity_visuals_.end() && to != entity_visuals_.end()) {
      const osg::Vec3 a = to_osg(
                          entity_poses_[static_cast<std::size_t>(from - entity_visuals_.begin())].to_parent(
                              festoon.from_m)),
                      b = to_osg(
                          entity_poses_[static_cast<std::size_t>(to - entity_visuals_.begin())].to_parent(
                              festoon.to_m));
      osg::Vec3 along = b - a;
      along.z() = 0.0f;
      const float length = along.length();
      if (length > 1e-3f) along /= length;
      osg::Vec3 across = along ^ osg::Vec3(0.0f, 0.0f, 1.0f);
      const float spacing = std::max(length / static_cast<float>(festoon.carriers + 1), kClosest);
      // the clamps: the ends and each carrier's hanger's foot
      std::vector<osg::Vec3> clamps{a - osg::Vec3(0.0f, 0.0f, kHanger)};
      for (int k = 1; k <= festoon.carriers; ++k) {
        const osg::Vec3 carrier =
            a + along * (spacing * static_cast<float>(k)) +
            osg::Vec3(0.0f, 0.0f,
                      (b.z() - a.z()) * static_cast<float>(k) / static_cast<float>(festoon.carriers + 1));
        vertices->push_back(carrier);
        vertices->push_back(carrier - osg::Vec3(0.0f, 0.0f, kHanger));
        clamps.push_back(carrier - osg::Vec3(0.0f, 0.0f, kHanger));
      }
      clamps.push_back(b - osg::Vec3(0.0f, 0.0f, kHanger));
      for (int c = 0; c < festoon.cables; ++c) {
        const osg::Vec3 side =
            across * (kCableGap * (static_cast<float>(c) - 0.5f * static_cast<float>(festoon.cables - 1)));
        for (std::size_t k = 0; k + 1 < clamps.size(); ++k) {
          const std::vector<osg::Vec3> loop =
              festoon_loop(clamps[k] + side, clamps[k + 1] + side, festoon.loop_m, kLoopPoints);
          for (std::size_t p = 0; p + 1 < loop.size(); ++p) {
            vertices->push_back(loop[p]);
            vertices->push_back(loop[p + 1]);
          }
        }
      }
    }
    vertices->dirty();
    static_cast<osg::DrawArrays*>(festoons_[n]->getPrimitiveSet(0))
        ->setCount(static_cast<int>(vertices->size()));
    festoons_[n]->dirtyBound();
  }
}

// the jacks: a barrel and a rod each, along +x from their eyes, placed every frame
void ImageGenerator::set_jacks(const std::vector<Jack>& jacks) {
  if (jacks_group_) remove_lit(jacks_group_);
  jacks_.clear();
  jacks_group_ = new osg::Group;
  const auto entity = [&](const std::string& look) {
    return static_cast<std::size_t>(std::find(entity_visuals_.begin(), entity_visuals_.end(), look) -
                                    entity_visuals_.begin());
  };
  const auto along_x = [](double length, double diameter, const osg::Vec4& colour) {
    MeshBuilder mesh;
    mesh.append(*cylinder({length, diameter, diameter}, 16, colour),
                osg::Vec3(static_cast<float>(length / 2), 0, 0));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(mesh.build());
    osg::ref_ptr<osg::MatrixTransform> placed = new osg::MatrixTransform;
    placed->addChild(geode);
    return placed;
  };
  for (const Jack& jack : jacks) {
    DrawnJack drawn{jack, entity(jack.from_entity), entity(jack.to_entity), nullptr, nullptr};
    if (drawn.from >= entity_visuals_.size() || drawn.to >= entity_visuals_.size()) continue;
    drawn.barrel = along_x(jack.barrel_m, jack.diameter_m, finished(rgba(jack.color), Surface::kPaint));
    drawn.rod = along_x(jack.rod_m, 0.55 * jack.diameter_m,
                        finished(osg::Vec4(0.80f, 0.80f, 0.78f, 1.0f), Surface::kSteel));  // chromed
    jacks_group_->addChild(drawn.barrel);
    jacks_group_->addChild(drawn.rod);
    jacks_.push_back(drawn);
  }
  add_lit(jacks_group_);
  update_jacks();
}

// each jack between its eyes as they ride their entities: the barrel from one towards the other, the rod back
void ImageGenerator::update_jacks() {
  for (const DrawnJack& drawn : jacks_) {
    const osg::Vec3d a = to_osg(entity_poses_[drawn.from].to_parent(drawn.jack.from_m)),
                     b = to_osg(entity_poses_[drawn.to].to_parent(drawn.jack.to_m));
    osg::Vec3d along = b - a;
    if (along.normalize() < 1e-6) along = osg::Vec3d(1.0, 0.0, 0.0);
    drawn.barrel->setMatrix(osg::Matrixd::rotate(osg::Vec3d(1.0, 0.0, 0.0), along) *
                            osg::Matrixd::translate(a));
    drawn.rod->setMatrix(osg::Matrixd::rotate(osg::Vec3d(1.0, 0.0, 0.0), -along) *
                         osg::Matrixd::translate(b));
  }
}

// the heads-up display: an orthographic camera drawn last, in pixels
void ImageGenerator::build_hud(const scene::SceneDescription& scene) {
  indicators_ = scene.indicators;
  machine_ = scene.machine;
  osg::ref_ptr<osg::Camera> hud = new osg::Camera;
  hud->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
  hud->setProjectionMatrixAsOrtho2D(0, width_, 0, height_);
  hud->setViewMatrix(osg::Matrix::identity());
  // drawn within the main camera's frame (last, over everything), so the read-back frame holds it
  hud->setClearMask(0);
  hud->setRenderOrder(osg::Camera::NESTED_RENDER);
  hud->getOrCreateStateSet()->setRenderBinDetails(1000, "RenderBin");
  hud->getOrCreateStateSet()->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF);
  hud->setAllowEventFocus(false);
  hud->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
  hud->getOrCreateStateSet()->setMode(GL_FOG, osg::StateAttribute::OFF);
  hud->getOrCreateStateSet()->setMode(GL_BLEND, osg::StateAttribute::ON);
  const float size = std::max(14.0f, static_cast<float>(height_) / 32.0f);
  const auto text = [&](const osg::Vec4& color, const osg::Vec3& at) {
    osg::ref_ptr<osgText::Text> t = new osgText::Text;
    t->setCharacterSize(size);
    t->setColor(color);
    t->setPosition(at);
    // on a translucent dark box: readable over sky and quay (an outlined font costs llvmpipe ~30 ms a frame)
    t->setDrawMode(osgText::Text::TEXT | osgText::Text::FILLEDBOUNDINGBOX);
    t->setBoundingBoxColor(osg::Vec4(0.0f, 0.0f, 0.0f, 0.45f));
    t->setBoundingBoxMargin(size * 0.2f);
    t->setDataVariance(osg::Object::DYNAMIC);
    return t;
  };
  hud_ = text(osg::Vec4(1.0f, 1.0f, 0.9f, 1.0f),
              osg::Vec3(size * 0.6f, static_cast<float>(height_) - size * 1.4f, 0.0f));
  alarm_ = text(osg::Vec4(1.0f, 0.25f, 0.2f, 1.0f),
                osg::Vec3(size * 0.6f, static_cast<float>(height_) - size * 2.8f, 0.0f));
  overlay_ = text(osg::Vec4(1.0f, 1.0f, 0.95f, 1.0f),
                  osg::Vec3(static_cast<float>(width_) / 2.0f, static_cast<float>(height_) * 0.85f, 0.0f));
  overlay_->setAlignment(osgText::Text::CENTER_TOP);
  overlay_->setNodeMask(0u);  // none until set
  overlay_->setBoundingBoxColor(osg::Vec4(0.0f, 0.0f, 0.0f, 0.75f));
  osg::ref_ptr<osg::Geode> lines = new osg::Geode;
  lines->addDrawable(hud_);
  lines->addDrawable(alarm_);
  lines->addDrawable(overlay_);
  timeline_ = new osg::Geometry;
  timeline_->setUseDisplayList(false);
  timeline_->setUseVertexBufferObjects(true);
  timeline_->setDataVariance(osg::Object::DYNAMIC);
  timeline_->setVertexArray(new osg::Vec3Array);
  timeline_->setColorArray(new osg::Vec4Array, osg::Array::BIND_PER_VERTEX);
  timeline_->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 0));
  lines->addDrawable(timeline_);
  inset_quads_ = new osg::Geode;
  inset_quads_->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
  // before the lines, each frame before its picture
  inset_quads_->getOrCreateStateSet()->setRenderBinDetails(999, "TraversalOrderBin");
  hud->addChild(inset_quads_);
  hud->addChild(lines);
  signal_panel_ = std::make_unique<SignalPanel>(width_, height_, size);
  hud->addChild(signal_panel_->node());
  hud_camera_ = hud;
}

// the rain close past the eye: thin translucent streaks over the picture, before the HUD
void ImageGenerator::build_near_rain() {
  near_rain_ = new osg::Camera;
  near_rain_->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
  near_rain_->setProjectionMatrixAsOrtho2D(0, width_, 0, height_);
  near_rain_->setViewMatrix(osg::Matrix::identity());
  near_rain_->setClearMask(0);
  near_rain_->setRenderOrder(osg::Camera::NESTED_RENDER);
  near_rain_->setAllowEventFocus(false);
  osg::StateSet* streak_state = near_rain_->getOrCreateStateSet();
  streak_state->setRenderBinDetails(998, "RenderBin");
  streak_state->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF);
  streak_state->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
  streak_state->setMode(GL_FOG, osg::StateAttribute::OFF);
  streak_state->setMode(GL_BLEND, osg::StateAttribute::ON);
  streak_state->setAttributeAndModes(new osg::LineWidth(1.5f));
  streaks_ = new osg::Geometry;
  streaks_->setUseDisplayList(false);
  streaks_->setUseVertexBufferObjects(true);
  streaks_->setDataVariance(osg::Object::DYNAMIC);
  streaks_->setVertexArray(new osg::Vec3Array);
  streaks_->setColorArray(new osg::Vec4Array, osg::Array::BIND_PER_VERTEX);
  streaks_->addPrimitiveSet(new osg::DrawArrays(GL_LINES, 0, 0));
  osg::ref_ptr<osg::Geode> streak_geode = new osg::Geode;
  streak_geode->addDrawable(streaks_);
  near_rain_->addChild(streak_geode);
  near_rain_->setNodeMask(0u);  // dry until the weather says otherwise
}

// spray: a quad per cell of its grid, placed and faded by its shader
namespace {
// a billboard's corners, as its shader spreads it in the eye's frame
constexpr std::array<std::array<float, 2>, 4> kBillboardCorners{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};

// billboards spread by their own shaders, unlit, blended, in bin `bin` after the scene, seen through each
// other (no depth written): the state of `geode`
osg::StateSet* billboards(osg::Geode& geode, int bin, const char* vertex_shader,
                          const char* fragment_shader) {
  osg::StateSet* state = geode.getOrCreateStateSet();
  state->setRenderBinDetails(bin, "RenderBin");
  state->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
  state->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
  state->setMode(GL_BLEND, osg::StateAttribute::ON);
  state->setAttributeAndModes(new osg::Depth(osg::Depth::LESS, 0.0, 1.0, false));
  osg::ref_ptr<osg::Program> program = new osg::Program;
  program->addShader(new osg::Shader(osg::Shader::VERTEX, vertex_shader));
  program->addShader(new osg::Shader(osg::Shader::FRAGMENT, fragment_shader));
  state->setAttribute(program);
  return state;
}
}  // namespace

void ImageGenerator::build_spray() {
  osg::ref_ptr<osg::Geometry> puffs = new osg::Geometry;
  osg::ref_ptr<osg::Vec3Array> cells = new osg::Vec3Array;
  osg::ref_ptr<osg::Vec2Array> corners = new osg::Vec2Array;
  for (int j = 0; j < kSprayCells; ++j)
    for (int i = 0; i < kSprayCells; ++i)
      for (const auto& [u, v] : kBillboardCorners) {
        cells->push_back(osg::Vec3(static_cast<float>(i), static_cast<float>(j), 0.0f));
        corners->push_back(osg::Vec2(u, v));
      }
  puffs->setVertexArray(cells);
  puffs->setTexCoordArray(0, corners, osg::Array::BIND_PER_VERTEX);
  puffs->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, static_cast<int>(cells->size())));
  puffs->setCullingActive(false);  // placed by its shader round the eye
  spray_ = new osg::Geode;
  spray_->addDrawable(puffs);
  osg::StateSet* state = billboards(*spray_, kSprayBin, kSprayVertexShader, kSprayFragmentShader);
  for (const char* name : {"time_s", "spray_share", "spray_height", "water_level", "quay_edge", "sky_light"})
    state->addUniform(new osg::Uniform(name, 0.0f));
  for (const char* name : {"first_cell", "wind"})
    state->addUniform(new osg::Uniform(name, osg::Vec2()));
  spray_->setNodeMask(0u);  // calm until the wind says otherwise
  root_->addChild(spray_);
}

// the lit lamps' glows: one billboard each, placed every frame by update_floodlights
void ImageGenerator::build_lamp_glows() {
  osg::ref_ptr<osg::Geometry> glows = new osg::Geometry;
  glows->setUseDisplayList(false);
  glows->setUseVertexBufferObjects(true);
  glows->setDataVariance(osg::Object::DYNAMIC);
  // one quad's room from the start, drawn only when a lamp is lit
  glows->setVertexArray(new osg::Vec3Array(4));
  glows->setColorArray(new osg::Vec4Array(4), osg::Array::BIND_PER_VERTEX);
  glows->setTexCoordArray(0, new osg::Vec2Array(4), osg::Array::BIND_PER_VERTEX);
  glows->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 0));
  glows->setCullingActive(false);  // spread by its shader
  lamp_glows_ = new osg::Geode;
  lamp_glows_->addDrawable(glows);
  billboards(*lamp_glows_, kLampBin, kLampVertexShader, kLampFragmentShader)
      ->setAttributeAndModes(new osg::BlendFunc(GL_ONE, GL_ONE));  // light added
  lamp_glows_->setNodeMask(0u);
  root_->addChild(lamp_glows_);
}

void ImageGenerator::build(const scene::SceneDescription& scene) {
  root_ = new osg::Group;
  build_lighting();
  build_sky();
  build_quay_and_water();
  build_entities(scene);
  build_ropes(scene);
  build_hud(scene);
  build_near_rain();
  build_spray();
  build_lamp_glows();
  frame_ = new osg::Group;
  frame_->addChild(root_);
  frame_->addChild(near_rain_);
  frame_->addChild(hud_camera_);
}

// entities where the snapshot has them; parts turning with their indicators, tyres rolling
void ImageGenerator::update_entities(const scene::Snapshot& s) {
  for (int n = 0; n < s.entity_count; ++n) {
    const scene::Snapshot::Entity& e = s.entities[static_cast<std::size_t>(n)];
    if (e.index < entities_.size()) {
      entities_[e.index]->setNodeMask((e.flags & scene::Snapshot::kHidden) != 0 ? 0u : ~0u);
      entities_[e.index]->setMatrix(to_osg(e.pose));
      entity_poses_[e.index] = e.pose;
    }
  }
  // a grab's shells opening and a wheel steering by their indicators, tyres rolling by their machine's speed
  // over the time since the last snapshot (none across a jump: a seek, a restart)
  const double since_s = s.time_s - rolled_at_s_;
  const bool rolling = rolled_at_s_ >= 0.0 && since_s > 0.0 && since_s <= kLongestRoll_s;
  rolled_at_s_ = s.time_s;
  auto indicator_at = [&](int index) {
    return index >= 0 && index < s.indicator_count ? s.indicators[static_cast<std::size_t>(index)] : 0.0;
  };
  for (TurningPart& part : turning_parts_) {
    osg::Matrixd turned = part.placed;
    if (part.indicator >= 0) {
      const double raw = indicator_at(part.indicator);
      const double value = part.turn.arcsine ? std::clamp(raw, 0.0, 1.0) : raw;
      const double angle =
          part.turn.arcsine ? std::asin(value * std::sin(part.turn.max_rad)) : value * part.turn.max_rad;
      turned = osg::Matrixd::translate(-part.pivot) * osg::Matrixd::rotate(angle, to_osg(part.turn.axis)) *
               osg::Matrixd::translate(part.pivot) * turned;
    }
    if (part.speed_indicator >= 0) {
      if (rolling)
        part.rolled_rad = std::fmod(part.rolled_rad + indicator_at(part.speed_indicator) *
                                                          part.rolls_unit_mps * since_s / part.radius_m,
                                    2.0 * kPi);
      turned = osg::Matrixd::rotate(part.rolled_rad, part.roll_axis) * turned;
    }
    if (part.slide_indicator >= 0)
      turned = turned * osg::Matrixd::translate(to_osg(
                            part.slide.along * (indicator_at(part.slide_indicator) - part.slide.from)));
    part.transform->setMatrix(turned);
  }
}

// each rope's polyline
void ImageGenerator::update_ropes(const scene::Snapshot& s) {
  for (std::size_t r = 0; r < ropes_.size(); ++r) {
    auto* vertices = static_cast<osg::Vec3Array*>(ropes_[r]->getVertexArray());
    vertices->clear();
    if (static_cast<int>(r) < s.rope_count)
      for (int p = 0; p < s.rope_points[r]; ++p)
        vertices->push_back(to_osg(s.points[s.rope_first[r] + static_cast<std::size_t>(p)]));
    vertices->dirty();
    static_cast<osg::DrawArrays*>(ropes_[r]->getPrimitiveSet(0))
        ->setCount(static_cast<int>(vertices->size()));
    ropes_[r]->dirtyBound();
  }
}

// the sun, the sky, fog and rain from the time of day and the weather
void ImageGenerator::update_sky_and_weather(const scene::Snapshot& s) {
  // the sun and the sky from the time of day; fog from the visibility (Koschmieder: 2 % contrast at V)
  const core::Vec3 to_sun = sun_direction(s.time_of_day_h, s.day_of_year, s.latitude_deg, sun_elevation_);
  to_sun_ = to_sun;
  const double daylight = std::clamp(std::sin(sun_elevation_) * 2.5, 0.0, 1.0);
  // the weather as the eye meets it: rain falls from cloud that hides the sun (overcast from 8 mm/h on) and
  // scatters light (extinction 0.29 R^0.67 per km, R in mm/h: about 1 km of visibility in 40 mm/h); fog and
  // rain grey the sky from 5 km of visibility down to 500 m
  overcast_ = std::clamp(s.rain_mm_per_h / 8.0, 0.0, 1.0);
  const double extinction_per_m =
      3.912 / std::max(s.visibility_m, 1.0) + 0.29e-3 * std::pow(std::max(s.rain_mm_per_h, 0.0), 0.67);
  const double visibility_m = 3.912 / extinction_per_m;
  // the cloud deck: fair-weather cloud over the share of the sky its oktas say (the threshold its densities
  // pass over that share), rain's thick deck over the sky as the rain says, whichever is the thicker; the sky
  // between the clouds greys as the cover closes from 6 oktas to 8 (an overcast sky is grey)
  const double cover = std::clamp(s.cloud_oktas / 8.0, 0.0, 1.0);
  const double edge = kFairCloudEdge + (kRainCloudEdge - kFairCloudEdge) * overcast_;
  const double half_opaque = 0.5 * edge;  // the density past the threshold a cloud shows at
  const double cover_threshold =
      cover > 0.0 ? cloud_densities_[static_cast<std::size_t>(
                        (1.0 - cover) * static_cast<double>(cloud_densities_.size() - 1))] -
                        half_opaque
                  : 2.0;
  const double threshold = std::min(cover_threshold, overcast_ > 0.0 ? 0.9 - overcast_ : 2.0);
  cloud_drift_m_ = {2.0 * s.wind_mps.x * s.time_s, 2.0 * s.wind_mps.y * s.time_s};
  const double fog_grey = std::clamp((5000.0 - visibility_m) / 4500.0, 0.0, 1.0);
  grey_ = std::max({overcast_, fog_grey, std::clamp(4.0 * cover - 3.0, 0.0, 1.0)});
  // a cloud between the cab and the sun hides the sun's disc and the water's glint from the cab
  sun_clouded_ = 0.0;
  if (threshold < 1.5 && to_sun.z > 0.01) {
    const double reach = kCloudBase_m / to_sun.z;
    const double density = cloud_density(s.cab.pose.position.x - cloud_drift_m_.first + to_sun.x * reach,
                                         s.cab.pose.position.y - cloud_drift_m_.second + to_sun.y * reach);
    sun_clouded_ = std::clamp((density - threshold) / (2.0 * half_opaque), 0.0, 1.0);
  }
  const SkyShade shade = SkyShade(to_sun, sun_elevation_, grey_, overcast_, sun_clouded_);
  const core::Vec3 sky = shade.horizon;
  osg::Light* light = sun_->getLight();
  light->setPosition(osg::Vec4(to_osg(to_sun), 0.0f));
  // the clear sky's sun and sky light; under cloud or in fog the sun's direct light gives way to the sky's
  // diffuse light: soft, shadowless
  // (rain's deck and fog everywhere; fair-weather cloud where it shades, per pixel: cloud_deck_)
  const core::Vec3 diffuse = shade.daylight.sun_light() * (1.0 - 0.85 * std::max(overcast_, fog_grey));
  const core::Vec3 ambient = shade.veiled(shade.daylight.sky_light()) * (1.0 + 0.5 * grey_);
  light->setDiffuse(rgba(diffuse));
  light->setAmbient(rgba(ambient));
  sun_seen_->set(static_cast<float>(shade.sun_visible));  // no glint from a sun hidden by cloud or fog
  viewer_->getCamera()->setClearColor(rgba(sky));
  for (std::size_t n = 0; n < sky_directions_->size(); ++n) {
    const osg::Vec3& d = (*sky_directions_)[n];
    (*sky_colors_)[n] = shade.towards({d.x(), d.y(), d.z()});
  }
  sky_colors_->dirty();
  update_night_sky(s, shade);
  // the deck drifts at twice the surface wind (the wind's rise with height). Rain clouds are grey of the
  // veiled sky's brightness, their bases darker where thicker; fair-weather cloud is lit by the sun and the
  // sky (white in the sun's colour where thin, a grey base where thick)
  clouds_->setNodeMask(threshold < 1.5 ? ~0u : 0u);
  cloud_uniforms_[0]->set(static_cast<float>(threshold));
  if ((cover > 0.0) != cloud_shade_) {  // the lit programs that shade under cloud, or those that need not
    cloud_shade_ = cover > 0.0;
    set_surface_detail(surface_detail_);
  }
  cloud_deck_->set(osg::Vec4(static_cast<float>(cover_threshold), static_cast<float>(half_opaque),
                             static_cast<float>(cloud_drift_m_.first),
                             static_cast<float>(cloud_drift_m_.second)));
  const double zenith_grey = 0.30 * shade.zenith.x + 0.59 * shade.zenith.y + 0.11 * shade.zenith.z;
  const core::Vec3 lit = shade.daylight.sun_light() + shade.daylight.sky_light();
  const core::Vec3 fair{std::min(lit.x, 0.95), std::min(lit.y, 0.95), std::min(lit.z, 0.95)};
  const core::Vec3 light_base = core::Vec3{1.0, 1.0, 1.02} * (1.25 * zenith_grey);
  const core::Vec3 dark_base = core::Vec3{1.0, 1.0, 1.03} * (0.65 * zenith_grey);
  cloud_uniforms_[2]->set(to_osg(fair + (light_base - fair) * overcast_));
  cloud_uniforms_[3]->set(to_osg(fair * 0.62 + (dark_base - fair * 0.62) * overcast_));
  cloud_uniforms_[4]->set(to_osg(shade.horizon));
  cloud_uniforms_[7]->set(to_osg(to_sun));
  cloud_uniforms_[8]->set(to_osg(shade.daylight.sun_light() * (0.8 * (1.0 - overcast_))));
  cloud_uniforms_[5]->set(static_cast<float>(edge));
  cloud_uniforms_[6]->set(
      static_cast<float>(kFairCloudDepth + (kRainCloudDepth - kFairCloudDepth) * overcast_));
  fog_->setColor(rgba(sky));
  fog_->setDensity(static_cast<float>(extinction_per_m));
  visibility_m_ = visibility_m;
  rain_mm_per_h_ = s.rain_mm_per_h;
  // rain: particles falling with the wind, and the quay darkens as it wets (assumed: -35 % when wet through)
  const double intensity = std::clamp(s.rain_mm_per_h / 50.0, 0.0, 1.0);
  rain_->setNodeMask(intensity > 0.0 ? ~0u : 0u);
  if (intensity > 0.0) {
    rain_->rain(static_cast<float>(intensity));
    // streaks a person sees: osgParticle's drops are a hair's width, grey on grey (0.01-0.03 m)
    rain_->setParticleSize(static_cast<float>(0.03 + 0.04 * intensity));
    // a drop shows the sky's light it refracts and reflects: a little brighter than the horizon behind it by
    // day, dark at night (a floodlight's pool lights the ground, not the drops: their glare is left out)
    const core::Vec3 drop = shade.horizon * 1.15;
    rain_->setParticleColor(osg::Vec4(static_cast<float>(std::min(drop.x, 1.0)),
                                      static_cast<float>(std::min(drop.y, 1.0)),
                                      static_cast<float>(std::min(drop.z, 1.0)), 0.55f));
    rain_->setWind(to_osg(s.wind_mps));
    rain_->getFog()->setDensity(fog_->getDensity());
  }
  // every surface turned up wet through from 2 mm/h (the lit shader darkens it under its film), the quay
  // with its water film; splashes that show, 0.75 a square metre and second per mm/h (assumed: the larger
  // drops' crowns; 20 mm/h brings ~1,300 drops a square metre and second in all)
  const double wetness = std::clamp(s.rain_mm_per_h / 2.0, 0.0, 1.0);
  wetness_->set(static_cast<float>(wetness));
  for (const osg::ref_ptr<osg::StateSet>& quay : quay_states_)
    if (wetness > 0.0)
      quay->setAttribute(lit_programs_[1][surface_detail_][cloud_shade_]);
    else
      quay->removeAttribute(osg::StateAttribute::PROGRAM);
  film_[0]->set(static_cast<float>(0.75 * std::max(s.rain_mm_per_h, 0.0)));
  film_[1]->set(static_cast<float>(s.time_s));
  film_[2]->set(to_osg(shade.horizon));
  film_[3]->set(to_osg(shade.zenith));
  water_shading_->getUniform("horizon")->set(to_osg(shade.horizon));  // the sky the water mirrors
  water_shading_->getUniform("zenith")->set(to_osg(shade.zenith));
  daylight_ = daylight;
}

// the floodlights and the machines' lamps
void ImageGenerator::update_floodlights(const scene::Snapshot& s) {
  // floodlights from dusk to dawn: the quay's, and the lamps riding entities in the scene while the machine's
  // supply is on; OpenGL's seven lights go to them in the look file's order
  const bool dark = sun_elevation_ < 0.02;
  std::size_t lit_lamps = 0;
  osg::Geometry& glows = *lamp_glows_->getDrawable(0)->asGeometry();
  auto* glow_at = static_cast<osg::Vec3Array*>(glows.getVertexArray());
  auto* glow_colour = static_cast<osg::Vec4Array*>(glows.getColorArray());
  auto* glow_corner = static_cast<osg::Vec2Array*>(glows.getTexCoordArray(0));
  glow_at->clear();
  glow_colour->clear();
  glow_corner->clear();
  for (const Floodlight& lamp : floodlight_settings_) {
    if (!dark || lit_lamps == floodlights_.size()) break;
    core::Vec3 at = lamp.position_m;
    if (!lamp.entity.empty()) {
      const auto it = std::find(entity_visuals_.begin(), entity_visuals_.end(), lamp.entity);
      if (it == entity_visuals_.end() || s.power_off) continue;
      at = entity_poses_[static_cast<std::size_t>(it - entity_visuals_.begin())].to_parent(lamp.position_m);
    }
    osg::Light* slot = floodlights_[lit_lamps++]->getLight();
    slot->setPosition(osg::Vec4(to_osg(at), 1.0f));
    // its glow: at the lamp, or at each lens of its mast's head
    const std::vector<osg::Vec3> lenses =
        lamp.mast ? light_mast_lenses() : std::vector<osg::Vec3>{osg::Vec3()};
    for (const osg::Vec3& lens : lenses)
      for (const auto& [u, v] : kBillboardCorners) {
        glow_at->push_back(to_osg(at) + lens);
        glow_colour->push_back(rgba(lamp.color));
        glow_corner->push_back(osg::Vec2(u, v));
      }
    slot->setDiffuse(rgba(lamp.color));
    // a tenth of the light at its range: 1 / (1 + q r^2) = 0.1
    slot->setQuadraticAttenuation(static_cast<float>(9.0 / (lamp.range_m * lamp.range_m)));
  }
  for (std::size_t n = 0; n < floodlights_.size(); ++n)
    root_->getOrCreateStateSet()->setMode(GL_LIGHT1 + static_cast<GLenum>(n),
                                          n < lit_lamps ? osg::StateAttribute::ON : osg::StateAttribute::OFF);
  floodlights_on_->set(static_cast<int>(lit_lamps));
  static_cast<osg::DrawArrays*>(glows.getPrimitiveSet(0))->setCount(static_cast<int>(glow_at->size()));
  // one quad's room at least, drawn only when a lamp is lit (see build_lamp_glows)
  glow_at->resize(std::max<std::size_t>(glow_at->size(), 4));
  glow_colour->resize(glow_at->size());
  glow_corner->resize(glow_at->size());
  for (osg::Array* array : {static_cast<osg::Array*>(glow_at), static_cast<osg::Array*>(glow_colour),
                            static_cast<osg::Array*>(glow_corner)})
    array->dirty();
  lamp_glows_->setNodeMask(lit_lamps > 0 ? ~0u : 0u);
}

// the HUD's lines
void ImageGenerator::update_hud(const scene::Snapshot& s) {
  // the HUD: time, wind, then the machine's indicators the look file names; alarms on their own line
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "t %.1f s   wind %.1f m/s", s.time_s,
                std::hypot(s.wind_mps.x, s.wind_mps.y));
  std::string line = buffer;
  const auto indicator = [&](const std::string& name) -> std::optional<double> {
    const auto at = std::find(indicators_.begin(), indicators_.end(), name);
    const auto index = static_cast<int>(at - indicators_.begin());
    if (at == indicators_.end() || index >= s.indicator_count) return std::nullopt;
    return s.indicators[static_cast<std::size_t>(index)];
  };
  for (const HudItem& item : hud_items_) {
    const std::optional<double> value = indicator(item.indicator);
    if (!value) continue;
    if (!item.shown_while.empty() && !(indicator(item.shown_while).value_or(0.0) > 0.5)) continue;
    if (!item.shown_on(machine_)) continue;
    const double v = *value * item.scale;
    if (item.lamp) {
      if (v > 0.5) line += "   " + item.label;
      continue;
    }
    if (!item.words.empty()) {
      const long k = std::lround(v) - item.words_from;
      if (k >= 0 && k < static_cast<long>(item.words.size()))
        line += "   " + item.label + " " + item.words[static_cast<std::size_t>(k)];
      continue;
    }
    // a value that rounds to zero shows as 0, not -0.0
    const double shown = std::abs(v) < 0.5 * std::pow(10.0, -item.decimals) ? 0.0 : v;
    std::snprintf(buffer, sizeof buffer, "   %s %.*f %s", item.label.c_str(), item.decimals, shown,
                  item.unit.c_str());
    line += buffer;
  }
  std::string alarm;
  if (s.emergency_stop && !s.power_off) alarm += "EMERGENCY STOP: DRIVES OFF, BRAKES SET   ";
  if (s.held) alarm += "FROZEN BY THE INSTRUCTOR   ";
  if (s.power_off) alarm += "POWER FAILURE: DRIVES OFF, BRAKES SET   ";
  if (s.awaiting_zero) alarm += "POWER BACK: ALL LEVERS TO ZERO   ";
  if (s.devices_missing > 0) alarm += "INPUT DEVICE MISSING: ITS CONTROLS ARE NEUTRAL   ";
  if (s.diverged) alarm += "SIMULATION STOPPED   ";
  update_timeline(s.time_s);
  signal_panel_->update(s);
  hud_line_ = line + (alarm.empty() ? "" : "\n" + alarm);
  // each line at its size, smaller where it would run off a narrow picture
  const float size = std::max(14.0f, static_cast<float>(height_) / 32.0f);
  // an alarm in force is a red band across the picture (white on red), not a line to be missed
  const bool alarming = !alarm.empty();
  alarm_->setColor(alarming ? osg::Vec4(1.0f, 1.0f, 1.0f, 1.0f) : osg::Vec4(1.0f, 0.25f, 0.2f, 1.0f));
  alarm_->setBoundingBoxColor(alarming ? osg::Vec4(0.80f, 0.05f, 0.05f, 0.85f)
                                       : osg::Vec4(0.0f, 0.0f, 0.0f, 0.45f));
  for (const auto& [text, content] :
       {std::pair{hud_.get(), line},
        std::pair{alarm_.get(), alarm.empty() ? caption_ : alarm + "\n" + caption_}}) {
    if (text->getText().createUTF8EncodedString() == content) continue;  // laid out already
    if (text->getCharacterHeight() != size) text->setCharacterSize(size);
    text->setText(content);
    const osg::BoundingBox& box = text->getBoundingBox();
    const float room = static_cast<float>(width_) - 1.2f * size, wide = box.xMax() - box.xMin();
    if (box.valid() && wide > room) text->setCharacterSize(size * room / wide);
  }
}

void ImageGenerator::update(const scene::Snapshot& s) {
  update_entities(s);
  update_ropes(s);
  update_festoons();
  update_jacks();
  cab_ = s.cab;
  sea_ = s.sea;
  time_s_ = s.time_s;
  wind_mps_ = s.wind_mps;
  update_sky_and_weather(s);
  update_floodlights(s);
  far_water_->setMatrix(osg::Matrixd::translate(0.0, 0.0, s.sea.water_level_m));
  update_hud(s);
}

void ImageGenerator::set_overlay(const std::string& text) {
  overlay_->setText(text);
  overlay_->setNodeMask(text.empty() ? 0u : ~0u);  // its panel too
  // as large as fits the picture's width and 80 % of its height
  const float size = std::max(12.0f, static_cast<float>(height_) / 36.0f);
  overlay_->setCharacterSize(size);
  const osg::BoundingBox& box = overlay_->getBoundingBox();
  if (box.valid()) {
    const float wide = box.xMax() - box.xMin(), tall = box.yMax() - box.yMin();
    const float fit = std::min(0.95f * static_cast<float>(width_) / std::max(wide, 1.0f),
                               0.8f * static_cast<float>(height_) / std::max(tall, 1.0f));
    if (fit < 1.0f) overlay_->setCharacterSize(size * fit);
  }
}

void ImageGenerator::set_timeline(double from_s, double to_s, std::vector<TimelineMark> marks) {
  timeline_from_s_ = from_s;
  timeline_to_s_ = to_s;
  timeline_marks_ = std::move(marks);
}

void ImageGenerator::update_timeline(double now_s) {
  auto& vertices = static_cast<osg::Vec3Array&>(*timeline_->getVertexArray());
  auto& colors = static_cast<osg::Vec4Array&>(*timeline_->getColorArray());
  vertices.clear();
  colors.clear();
  const double span = timeline_to_s_ - timeline_from_s_;
  if (span > 0.0) {
    // the bar: a dark track the width of the picture less a margin, filled up to now, a tick per mark
    const float margin = static_cast<float>(width_) * 0.03f, y0 = static_cast<float>(height_) * 0.03f,
                y1 = y0 + std::max(6.0f, static_cast<float>(height_) * 0.02f);
    const float length = static_cast<float>(width_) - 2.0f * margin;
    const auto x_at = [&](double t) {
      return margin + length * static_cast<float>(std::clamp((t - timeline_from_s_) / span, 0.0, 1.0));
    };
    const auto quad = [&](float xa, float xb, float ya, float yb, const osg::Vec4& c) {
      for (const osg::Vec3& v : {osg::Vec3(xa, ya, 0.0f), osg::Vec3(xb, ya, 0.0f), osg::Vec3(xb, yb, 0.0f),
                                 osg::Vec3(xa, yb, 0.0f)}) {
        vertices.push_back(v);
        colors.push_back(c);
      }
    };
    quad(margin, margin + length, y0, y1, osg::Vec4(0.0f, 0.0f, 0.0f, 0.55f));
    quad(margin, x_at(now_s), y0, y1, osg::Vec4(0.85f, 0.85f, 0.8f, 0.8f));
    const float tick = std::max(1.5f, static_cast<float>(width_) * 0.002f);
    for (const TimelineMark& mark : timeline_marks_) {
      const float x = x_at(mark.time_s);
      quad(x - tick, x + tick, y0 - (y1 - y0) * 0.5f, y1 + (y1 - y0) * 0.5f, rgba(mark.color));
    }
  }
  vertices.dirty();
  colors.dirty();
  static_cast<osg::DrawArrays*>(timeline_->getPrimitiveSet(0))->setCount(static_cast<int>(vertices.size()));
  timeline_->dirtyBound();
}

void ImageGenerator::update_night_sky(const scene::Snapshot& s, const SkyShade& shade) {
  // stars show from nautical dusk on (sun 4-12 deg down), dimmed by haze and fog
  const double dark = std::clamp((-sun_elevation_ * 180.0 / kPi - 4.0) / 8.0, 0.0, 1.0) *
                      std::clamp(s.visibility_m / 8000.0, 0.0, 1.0);
  const double lat = s.latitude_deg * kPi / 180.0, sidereal = sidereal_angle(s.time_of_day_h, s.day_of_year);
  auto& star_vertices = static_cast<osg::Vec3Array&>(*stars_->getVertexArray());
  auto& star_colours = static_cast<osg::Vec4Array&>(*stars_->getColorArray());
  for (std::size_t n = 0; n < star_positions_.size(); ++n) {
    const auto& [right_ascension, declination, brightness] = star_positions_[n];
    const core::Vec3 d = sky_direction(sidereal - right_ascension, declination, lat);
    star_vertices[n] = to_osg(d * kDomeRadius_m);
    const float b = static_cast<float>(brightness * dark * std::clamp(d.z * 8.0, 0.0, 1.0));  // haze low down
    const osg::Vec4 behind = shade.towards(d);  // the dome's colour there
    star_colours[n].set(behind.r() + b, behind.g() + b, behind.b() + b, 1.0f);
  }
  star_vertices.dirty();
  star_colours.dirty();
  stars_->dirtyBound();

  // the moon: a disc 0.52 deg across, each point lit where the sphere behind it faces the sun
  double illuminated = 0.0;
  const core::Vec3 to_moon = moon_direction(s.time_of_day_h, s.day_of_year, s.latitude_deg, illuminated);
  core::Vec3 across =
      std::abs(to_moon.z) < 0.9 ? core::Vec3{-to_moon.y, to_moon.x, 0.0} : core::Vec3{1, 0, 0};
  across = across * (1.0 / std::sqrt(dot(across, across)));
  const core::Vec3 up = cross(to_moon, across);
  const double radius = kDomeRadius_m * std::tan(0.26 * kPi / 180.0);
  const double daylight = std::clamp(std::sin(sun_elevation_) * 2.5 + 0.3, 0.0, 1.0);
  auto& moon_vertices = static_cast<osg::Vec3Array&>(*moon_->getVertexArray());
  auto& moon_colours = static_cast<osg::Vec4Array&>(*moon_->getColorArray());
  std::size_t k = 0;
  const auto point = [&](int ring, int segment) {
    const double r = static_cast<double>(ring) / kMoonRings, a = 2.0 * kPi * segment / kMoonSegments;
    const double u = r * std::cos(a), v = r * std::sin(a);
    // the sphere's normal there: towards the viewer (-to_moon) and out across the disc
    const core::Vec3 normal = across * u + up * v - to_moon * std::sqrt(std::max(1.0 - r * r, 0.0));
    const double lit = std::clamp(dot(normal, to_sun_) * 6.0, 0.0, 1.0) * 0.9 + 0.04;  // and earthshine
    const double l = lit * (1.0 - 0.75 * daylight);
    moon_vertices[k] = to_osg(to_moon * kDomeRadius_m + (across * u + up * v) * radius);
    moon_colours[k] = osg::Vec4(static_cast<float>(std::max(l, shade.horizon.x)),
                                static_cast<float>(std::max(l, shade.horizon.y)),
                                static_cast<float>(std::max(l * 0.95, shade.horizon.z)), 1.0f);
    ++k;
  };
  for (int ring = 0; ring < kMoonRings; ++ring)
    for (int segment = 0; segment < kMoonSegments; ++segment) {
      point(ring, segment);
      point(ring + 1, segment);
      point(ring + 1, segment + 1);
      point(ring, segment);
      point(ring + 1, segment + 1);
      point(ring, segment + 1);
    }
  moon_vertices.dirty();
  moon_colours.dirty();
  moon_->dirtyBound();
}

void ImageGenerator::add_lit(osg::Node* node) {
  shadowed_->addChild(node);
  unshadowed_->addChild(node);
}

void ImageGenerator::remove_lit(osg::Node* node) {
  shadowed_->removeChild(node);
  unshadowed_->removeChild(node);
}

void ImageGenerator::set_scenery(const std::vector<SceneryPart>& parts) {
  if (scenery_) remove_lit(scenery_);
  scenery_ = new osg::Group;
  osg::ref_ptr<osg::Geode> standing = new osg::Geode, flat = new osg::Geode;  // flat: markings, no shadow
  flat->setNodeMask(kReceivesOnly);
  for (const SceneryPart& part : parts)
    for (int k = 0; k < part.repeat; ++k) {
      const osg::Vec3 centre = to_osg(part.centre_m + part.step_m * static_cast<double>(k));
      osg::ref_ptr<osg::Shape> shape;
      if (part.shape == SceneryPart::Shape::kCylinder)
        shape = new osg::Cylinder(centre, static_cast<float>(part.size_m.x / 2.0),
                                  static_cast<float>(part.size_m.z));
      else
        shape = new osg::Box(centre, static_cast<float>(part.size_m.x), static_cast<float>(part.size_m.y),
                             static_cast<float>(part.size_m.z));
      osg::ref_ptr<osg::ShapeDrawable> drawable = new osg::ShapeDrawable(shape);
      drawable->setColor(finished(rgba(part.color), part.surface));
      drawable->setUseDisplayList(false);  // buffer objects, as everything else (use_buffer_objects)
      drawable->setUseVertexBufferObjects(true);
      (part.size_m.z < 0.05 ? flat : standing)->addDrawable(drawable);
    }
  scenery_->addChild(standing);
  scenery_->addChild(flat);
  add_lit(scenery_);
}

void ImageGenerator::set_floodlights(const std::vector<Floodlight>& lights) {
  for (const auto& light : floodlights_)
    root_->removeChild(light);
  floodlights_.clear();
  floodlight_settings_ = lights;
  if (masts_) remove_lit(masts_);
  masts_ = new osg::Group;
  for (const Floodlight& light : lights) {
    if (!light.mast) continue;
    osg::ref_ptr<osg::MatrixTransform> at =
        new osg::MatrixTransform(osg::Matrixd::translate(to_osg(light.position_m)));
    osg::ref_ptr<osg::Geode> mast = new osg::Geode;
    mast->addDrawable(light_mast(light.position_m.z));
    at->addChild(mast);
    masts_->addChild(at);
  }
  add_lit(masts_);
  for (std::size_t n = 0; n < lights.size() && n < kFloodlightSlots; ++n) {  // placed and lit in update()
    osg::ref_ptr<osg::LightSource> source = new osg::LightSource;
    osg::Light* light = source->getLight();
    light->setLightNum(static_cast<int>(n) + 1);
    light->setAmbient(osg::Vec4(0, 0, 0, 1));
    light->setSpecular(osg::Vec4(0, 0, 0, 1));
    light->setConstantAttenuation(1.0f);
    root_->addChild(source);
    floodlights_.push_back(source);
  }
}

void ImageGenerator::mesh_bulk_tile(const scene::BulkView::Grid& grid, int ti, int tj, osg::Geometry& tile) {
  // vertices at the cell centres of the tile and one row and column beyond (tiles join), quads only where
  // there is material
  const int i0 = ti * grid.tile_cells, j0 = tj * grid.tile_cells;
  const int i1 = std::min(i0 + grid.tile_cells, grid.cells_x - 1),
            j1 = std::min(j0 + grid.tile_cells, grid.cells_y - 1);
  const auto h = [&](int i, int j) {
    return grid.heights[static_cast<std::size_t>(std::clamp(j, 0, grid.cells_y - 1) * grid.cells_x +
                                                 std::clamp(i, 0, grid.cells_x - 1))];
  };
  auto& vertices = static_cast<osg::Vec3Array&>(*tile.getVertexArray());
  auto& normals = static_cast<osg::Vec3Array&>(*tile.getNormalArray());
  auto& quads = static_cast<osg::DrawElementsUInt&>(*tile.getPrimitiveSet(0));
  vertices.clear();
  normals.clear();
  quads.clear();
  const int columns = i1 - i0 + 1;
  const float cell = static_cast<float>(grid.cell_m);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      vertices.push_back(
          osg::Vec3((static_cast<float>(i) + 0.5f) * cell, (static_cast<float>(j) + 0.5f) * cell, h(i, j)));
      osg::Vec3 n(-(h(i + 1, j) - h(i - 1, j)) / (2.0f * cell), -(h(i, j + 1) - h(i, j - 1)) / (2.0f * cell),
                  1.0f);
      n.normalize();
      normals.push_back(n);
    }
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i) {
      if (h(i, j) <= 0.0f && h(i + 1, j) <= 0.0f && h(i, j + 1) <= 0.0f && h(i + 1, j + 1) <= 0.0f) continue;
      const unsigned a = static_cast<unsigned>((j - j0) * columns + (i - i0));
      for (const unsigned v :
           {a, a + 1, a + 1 + static_cast<unsigned>(columns), a + static_cast<unsigned>(columns)})
        quads.push_back(v);
    }
  vertices.dirty();
  normals.dirty();
  quads.dirty();
  tile.dirtyBound();
  ++bulk_tiles_meshed_;
}

void ImageGenerator::update_bulk(const scene::BulkView& view) {
  const auto look = visuals_.find("bulk");
  const core::Vec3 colour = look != visuals_.end() && !look->second.parts.empty()
                                ? look->second.parts[0].color
                                : core::Vec3{0.2, 0.2, 0.2};
  for (std::size_t g = bulk_grids_.size(); g < view.grids.size(); ++g) {
    const scene::BulkView::Grid& grid = view.grids[g];
    BulkGridNode node;
    node.frame = new osg::MatrixTransform;
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    osg::ref_ptr<osg::Vec4Array> colours = new osg::Vec4Array;
    colours->push_back(rgba(colour));
    for (int t = 0; t < grid.tiles_x * grid.tiles_y; ++t) {
      osg::ref_ptr<osg::Geometry> tile = new osg::Geometry;
      tile->setUseDisplayList(false);
      tile->setUseVertexBufferObjects(true);
      tile->setDataVariance(osg::Object::DYNAMIC);
      tile->setVertexArray(new osg::Vec3Array);
      tile->setNormalArray(new osg::Vec3Array, osg::Array::BIND_PER_VERTEX);
      tile->setColorArray(colours, osg::Array::BIND_OVERALL);
      tile->addPrimitiveSet(new osg::DrawElementsUInt(GL_QUADS));
      geode->addDrawable(tile);
      node.tiles.push_back(tile);
    }
    node.versions.assign(node.tiles.size(), 0);
    node.frame->addChild(geode);
    add_lit(node.frame);
    bulk_grids_.push_back(node);
    for (int t = 0; t < grid.tiles_x * grid.tiles_y; ++t) {  // everything once
      mesh_bulk_tile(grid, t % grid.tiles_x, t / grid.tiles_x, *node.tiles[static_cast<std::size_t>(t)]);
      bulk_grids_.back().versions[static_cast<std::size_t>(t)] =
          grid.tile_version[static_cast<std::size_t>(t)];
    }
  }
  for (std::size_t g = 0; g < view.grids.size(); ++g) {
    const scene::BulkView::Grid& grid = view.grids[g];
    BulkGridNode& node = bulk_grids_[g];
    node.frame->setMatrix(to_osg(grid.pose));
    for (std::size_t t = 0; t < node.tiles.size() && t < grid.tile_version.size(); ++t)
      if (node.versions[t] != grid.tile_version[t]) {
        mesh_bulk_tile(grid, static_cast<int>(t) % grid.tiles_x, static_cast<int>(t) / grid.tiles_x,
                       *node.tiles[t]);
        node.versions[t] = grid.tile_version[t];
      }
  }
  // the material in flight: points, a cell or two across
  if (!parcels_) {
    parcels_ = new osg::Geometry;
    parcels_->setUseDisplayList(false);
    parcels_->setUseVertexBufferObjects(true);
    parcels_->setDataVariance(osg::Object::DYNAMIC);
    parcels_->setVertexArray(new osg::Vec3Array);
    osg::ref_ptr<osg::Vec4Array> colours = new osg::Vec4Array;
    colours->push_back(rgba(colour * 0.8));
    parcels_->setColorArray(colours, osg::Array::BIND_OVERALL);
    parcels_->addPrimitiveSet(new osg::DrawArrays(GL_POINTS, 0, 0));
    parcels_->setCullingActive(false);
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(parcels_);
    geode->getOrCreateStateSet()->setAttributeAndModes(new osg::Point(4.0f));
    geode->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    root_->addChild(geode);
  }
  auto& points = static_cast<osg::Vec3Array&>(*parcels_->getVertexArray());
  points.clear();
  for (const scene::BulkView::Parcel& p : view.parcels)
    points.push_back(to_osg(p.position_m));
  points.dirty();
  static_cast<osg::DrawArrays*>(parcels_->getPrimitiveSet(0))->setCount(static_cast<int>(points.size()));
  parcels_->dirtyBound();
}

void ImageGenerator::set_view(const View& view) {
  view_ = view;
}

void ImageGenerator::place_camera() {
  hud_camera_->setNodeMask(view_.hud ? ~0u : 0u);
  osg::Camera* camera = viewer_->getCamera();
  const double aspect = static_cast<double>(width_) * view_.pixel_aspect / height_;
  const bool cab_view = view_.kind == View::Kind::kCab;
  const double fov_vertical =
      cab_view && view_.fov_from_sight ? cab_.sight.fov_vertical_rad : view_.fov_vertical_rad;
  // a cab view's and a free camera's near plane just in front of the eye (the bonnet, the mirror arms and the
  // floor window's edge are a metre away, a free camera may stand low over the quay: a near plane computed
  // from the whole harbour's bounds, some 3 m, cut them off and showed the water under the quay); the chase
  // view lets it follow the scene's bounds
  const bool near_eye = cab_view || view_.kind == View::Kind::kFree;
  camera->setComputeNearFarMode(near_eye ? osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR
                                         : osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES);
  camera->setProjectionMatrixAsPerspective(fov_vertical * 180.0 / kPi, aspect, kCabNear_m, 6000.0);
  camera->setViewport(0, 0, width_, height_);
  const core::Pose& cab = cab_.pose;
  // a cab view's direction in the cab: its offsets, from the design line of sight where it says so
  const double view_yaw = view_.yaw_rad + (view_.from_sight ? cab_.sight.yaw_rad : 0.0),
               view_pitch = view_.pitch_rad + (view_.from_sight ? cab_.sight.pitch_rad : 0.0);
  if (cab_view && view_.off_axis) {
    // the screen is a window in front of the design eye, square to the view; the head moves the eye behind
    // it, and turning it (times the gain) or looking round turns the window with it
    const double yaw = view_yaw, pitch = view_pitch;
    core::Vec3 forward_local{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                             std::sin(pitch)};
    core::Vec3 right_local{std::sin(yaw), -std::cos(yaw), 0.0};
    core::Vec3 up_local{-std::sin(pitch) * std::cos(yaw), -std::sin(pitch) * std::sin(yaw), std::cos(pitch)};
    look_round(forward_local, up_local, right_local,
               cab_.look_yaw_rad + view_.head_turn_gain * cab_.head_yaw_pitch_roll_rad.x,
               cab_.look_pitch_rad + view_.head_turn_gain * cab_.head_yaw_pitch_roll_rad.y);
    const core::Vec3& head = cab_.head_offset_m;
    const double ahead = dot(head, forward_local), right = dot(head, right_local), up = dot(head, up_local);
    const double d = std::max(view_.screen_distance_m - ahead, 0.05);  // eye to the screen's plane
    const double half_height = view_.screen_distance_m * std::tan(fov_vertical / 2.0);
    const double half_width = half_height * aspect, near = kCabNear_m, scale = near / d;
    camera->setProjectionMatrixAsFrustum((-half_width - right) * scale, (half_width - right) * scale,
                                         (-half_height - up) * scale, (half_height - up) * scale, near,
                                         6000.0);
    const core::Vec3 eye = cab.to_parent(cab_.eye_m + head);
    camera->setViewMatrixAsLookAt(to_osg(eye), to_osg(eye + cab.direction_to_parent(forward_local)),
                                  to_osg(cab.direction_to_parent(up_local)));
  } else if (cab_view) {
    if (view_.frustum_rad) {
      const auto& [left, right, bottom, top] = *view_.frustum_rad;
      const double near = kCabNear_m;
      camera->setProjectionMatrixAsFrustum(near * std::tan(left), near * std::tan(right),
                                           near * std::tan(bottom), near * std::tan(top), near, 6000.0);
    }
    // the eye in the cab (plus the head's offset), looking along the cab's x turned by the view's offsets
    const core::Vec3 eye = cab.to_parent(cab_.eye_m + cab_.head_offset_m);
    const double yaw = view_yaw + cab_.head_yaw_pitch_roll_rad.x,
                 pitch = view_pitch + cab_.head_yaw_pitch_roll_rad.y;
    const core::Vec3 local{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
    // up square to the view, then turned about it by the view's and the head's roll (positive: the right
    // side down, the picture turning anticlockwise)
    const core::Vec3 level_up{-std::sin(pitch) * std::cos(yaw), -std::sin(pitch) * std::sin(yaw),
                              std::cos(pitch)};
    core::Vec3 right = cross(local, level_up);
    const double roll = view_.roll_rad + cab_.head_yaw_pitch_roll_rad.z;
    core::Vec3 up_local = level_up * std::cos(roll) + right * std::sin(roll);
    right = cross(local, up_local);
    core::Vec3 forward_local = local;
    look_round(forward_local, up_local, right, cab_.look_yaw_rad, cab_.look_pitch_rad);
    const core::Vec3 forward = cab.direction_to_parent(forward_local);
    camera->setViewMatrixAsLookAt(to_osg(eye), to_osg(eye + forward),
                                  to_osg(cab.direction_to_parent(up_local)));
  } else if (view_.kind == View::Kind::kEntity) {
    const auto camera_it = std::find_if(cameras_.begin(), cameras_.end(),
                                        [&](const EntityCamera& c) { return c.name == view_.camera; });
    const std::optional<CameraPose> pose =
        camera_it == cameras_.end() ? std::nullopt : camera_pose(*camera_it);
    if (!pose) throw std::invalid_argument("no camera '" + view_.camera + "' on an entity of this scene");
    camera->setProjectionMatrixAsPerspective(camera_it->fov_vertical_rad * 180.0 / kPi, aspect, 0.3, 6000.0);
    camera->setViewMatrixAsLookAt(to_osg(pose->eye), to_osg(pose->eye + pose->look), to_osg(pose->up));
  } else if (view_.kind == View::Kind::kFree) {
    const core::Vec3 forward{std::cos(view_.pitch_rad) * std::cos(view_.yaw_rad),
                             std::cos(view_.pitch_rad) * std::sin(view_.yaw_rad), std::sin(view_.pitch_rad)};
    camera->setViewMatrixAsLookAt(to_osg(view_.position_m), to_osg(view_.position_m + forward),
                                  osg::Vec3(0, 0, 1));
  } else {
    // the machine framed whole: its entities' boxes as they stand, seen from behind its cab and above,
    // as far away as fits them in the picture; in fog no further than a third of the visibility (it fades,
    // it does not vanish into a blank frame)
    core::Vec3 low{1e9, 1e9, 1e9}, high{-1e9, -1e9, -1e9};
    for (std::size_t n = 0; n < machine_boxes_.size() && n < entity_poses_.size(); ++n) {
      const auto& [centre, half] = machine_boxes_[n];
      for (int corner = 0; corner < 8; ++corner) {
        const core::Vec3 p = entity_poses_[n].to_parent(centre + core::Vec3{corner & 1 ? half.x : -half.x,
                                                                            corner & 2 ? half.y : -half.y,
                                                                            corner & 4 ? half.z : -half.z});
        low = {std::min(low.x, p.x), std::min(low.y, p.y), std::min(low.z, p.z)};
        high = {std::max(high.x, p.x), std::max(high.y, p.y), std::max(high.z, p.z)};
      }
    }
    const bool boxed = low.x <= high.x;
    const core::Vec3 target = boxed ? (low + high) * 0.5 : cab.position;
    const double radius = boxed ? std::max(2.0, 0.5 * std::sqrt(dot(high - low, high - low))) : 20.0;
    const double fits = 1.15 * radius / std::sin(0.5 * std::min(fov_vertical, fov_vertical * aspect));
    const double distance = view_.chase_distance_m > 0.0
                                ? view_.chase_distance_m
                                : std::min(fits, std::max(12.0, visibility_m_ / 3.0));
    // behind the cab (its -x) and to its left, 25 degrees up
    const core::Vec3 back_left = cab.direction_to_parent({-1.0, 0.5, 0.0});
    const core::Vec3 level{back_left.x, back_left.y, 0.0};
    const double length = std::sqrt(dot(level, level));
    const core::Vec3 away = length > 1e-6 ? level * (1.0 / length) : core::Vec3{-1.0, 0.0, 0.0};
    const double up = 0.42;  // sin 25 degrees
    const core::Vec3 eye =
        target + away * (distance * std::sqrt(1.0 - up * up)) + core::Vec3{0.0, 0.0, distance * up};
    camera->setViewMatrixAsLookAt(to_osg(eye), to_osg(target), osg::Vec3(0, 0, 1));
  }
  if (view_.eye_offset_m != 0.0) {
    // one eye of a stereo pair: moved along the view's right axis, its frustum shifted the other way so that
    // the window at the convergence distance stays where it was (parallel axes, asymmetric frusta)
    double left, right, bottom, top, near, far;
    camera->getProjectionMatrixAsFrustum(left, right, bottom, top, near, far);
    const double shift = view_.eye_offset_m * near / view_.convergence_m;
    camera->setProjectionMatrixAsFrustum(left - shift, right - shift, bottom, top, near, far);
    camera->setViewMatrix(camera->getViewMatrix() * osg::Matrixd::translate(-view_.eye_offset_m, 0.0, 0.0));
  }
}

View view_named(const std::string& name) {
  View v;
  if (name == "cab") {
    v.from_sight = v.fov_from_sight = true;  // the machine's design view
    v.pitch_rad = 0.0;
    return v;
  }
  v.kind = name == "chase" ? View::Kind::kChase : name == "free" ? View::Kind::kFree : View::Kind::kEntity;
  if (v.kind == View::Kind::kFree) v.pitch_rad = -0.35, v.yaw_rad = 0.9;  // over the quay towards the crane
  if (v.kind == View::Kind::kEntity) v.camera = name;
  return v;
}

std::vector<std::string> ImageGenerator::view_names() const {
  std::vector<std::string> names{"cab", "chase", "free"};
  for (const EntityCamera& c : cameras_)
    if (std::find(entity_visuals_.begin(), entity_visuals_.end(), c.entity) != entity_visuals_.end())
      names.push_back(c.name);
  return names;
}

void ImageGenerator::update_water(const osg::Vec3d& eye) {
  // the wind sea for the wind as it blows now (synthesised again when it has changed by a quarter)
  const double wind = std::hypot(wind_mps_.x, wind_mps_.y);
  if (!wind_sea_ || std::abs(wind - wind_sea_speed_mps_) > 0.25 * wind_sea_speed_mps_ + 0.5) {
    const Jonswap spectrum = Jonswap::fetch_limited(wind, kFetch_m);
    const double peak_wavelength = 2.0 * kPi * 9.81 / (spectrum.omega_peak_radps * spectrum.omega_peak_radps);
    wind_sea_ = std::make_unique<OceanPatch>(64, 10.0 * peak_wavelength, spectrum,
                                             std::atan2(wind_mps_.y, wind_mps_.x), 0x5EA);
    wind_sea_speed_mps_ = wind;
  }
  wind_sea_->evaluate(time_s_);
  // whitecaps: the share of the sea white with foam is Monahan & O'Muircheartaigh's (1980) W = 3.84e-6
  // U^3.41 (1 % at 10 m/s, 11 % at 20 m/s), crests breaking now and the foam they leave behind together
  // (Monahan & Lu 1990's stages A and B); we give the crests half of it. The wind sea breaks where it is
  // steepest: the crests' foam covers the slopes above which that half of the patch lies now
  const double breaking = std::min(3.84e-6 * std::pow(wind, 3.41), 0.5);
  const double crest_share = kCrestShareOfWhitecaps * breaking;
  foam_slope_ = std::numeric_limits<double>::infinity();
  if (breaking > 1e-4) {
    foam_samples_.clear();
    const int n = wind_sea_->size();
    const double cell = wind_sea_->length_m() / n;
    // sampled between the patch's grid points, as the water's vertices sample it (bilinear: its extremes lie
    // on the grid points, so a quantile of those alone is steeper than the drawn sea reaches)
    for (int j = 0; j < 2 * n; ++j)
      for (int i = 0; i < 2 * n; ++i) {
        const double x = (0.5 * i + 0.25) * cell, y = (0.5 * j + 0.25) * cell;
        foam_samples_.push_back(std::hypot(wind_sea_->slope_x_at(x, y), wind_sea_->slope_y_at(x, y)));
      }
    const auto at =
        foam_samples_.begin() +
        static_cast<std::ptrdiff_t>((1.0 - crest_share) * static_cast<double>(foam_samples_.size() - 1));
    std::nth_element(foam_samples_.begin(), at, foam_samples_.end());
    foam_slope_ = *at;
  }
  // the shading's uniforms: the eye, the deep water's colour (the sky it mirrors: update_sky_and_weather)
  const auto set = [&](const char* name, const auto& value) { water_shading_->getUniform(name)->set(value); };
  // no glint under cloud (the one over the cab hides the sun from it) or in fog
  set("daylight", static_cast<float>(daylight_ * (1.0 - grey_) * (1.0 - sun_clouded_)));
  // the light on foam and spray: daylight, and the floodlights' share at night
  const float foam_light = static_cast<float>(0.12 + 0.88 * daylight_ * (1.0 - 0.4 * grey_));
  set("sky_light", foam_light);
  set("breaking", static_cast<float>(breaking));
  set("crest_share", static_cast<float>(crest_share));
  set("time_s", static_cast<float>(time_s_));
  set("wind_dir",
      wind > 1e-6 ? osg::Vec2(static_cast<float>(wind_mps_.x / wind), static_cast<float>(wind_mps_.y / wind))
                  : osg::Vec2(1.0f, 0.0f));
  set("eye_world", osg::Vec3(eye));
  set("to_sun", to_osg(to_sun_));
  set("deep", to_osg(core::Vec3{0.02 + 0.03 * daylight_, 0.06 + 0.10 * daylight_, 0.08 + 0.12 * daylight_}));
  // spray from 15 m/s (Beaufort 7-8: crests begin to break into spindrift) growing to a puff in 60 % of the
  // cells at 28 m/s (Beaufort 10: spray affects visibility) and thrown higher the stronger the wind (2 m at
  // 15 m/s, 0.25 m more a m/s): the Beaufort scale's descriptions, the figures assumed
  const double spray = std::clamp((wind - 15.0) / 13.0, 0.0, 1.0);
  spray_->setNodeMask(spray > 0.0 ? ~0u : 0u);
  if (spray > 0.0) {
    osg::StateSet* state = spray_->getStateSet();
    const auto cell_of = [](double v) { return 5.0 * std::floor(v / 5.0) - 5.0 * (kSprayCells / 2); };
    state->getUniform("first_cell")
        ->set(osg::Vec2(static_cast<float>(cell_of(eye.x())), static_cast<float>(cell_of(eye.y()))));
    state->getUniform("time_s")->set(static_cast<float>(time_s_));
    state->getUniform("spray_share")->set(static_cast<float>(0.6 * spray));
    state->getUniform("spray_height")->set(static_cast<float>(2.0 + 0.25 * (wind - 15.0)));
    state->getUniform("wind")->set(
        osg::Vec2(static_cast<float>(wind_mps_.x), static_cast<float>(wind_mps_.y)));
    state->getUniform("water_level")->set(static_cast<float>(sea_.water_level_m));
    state->getUniform("quay_edge")->set(static_cast<float>(kQuayEdge_m));
    state->getUniform("sky_light")->set(foam_light);
  }

  const double finest = wind_sea_->length_m() / wind_sea_->size();
  const double level = sea_.water_level_m;
  auto& vertices = static_cast<osg::Vec3Array&>(*water_->getVertexArray());
  auto& slopes = static_cast<osg::Vec2Array&>(*water_->getTexCoordArray(0));
  auto& foam = static_cast<osg::Vec2Array&>(*water_->getTexCoordArray(1));
  // a projected grid (Johanson 2004): rays through a grid over the screen (a little wider) meet the still
  // water; rays that miss it end at the far distance, so every cell covers about the same part of the image
  const osg::Camera& camera = *viewer_->getCamera();
  const osg::Matrixd to_world = osg::Matrixd::inverse(camera.getViewMatrix() * camera.getProjectionMatrix());
  const int row = kWaterColumns + 1;
  water_base_.resize(static_cast<std::size_t>(row * (kWaterRows + 1)));
  for (int j = 0; j <= kWaterRows; ++j)
    for (int i = 0; i <= kWaterColumns; ++i) {
      const double u = -1.1 + 2.2 * i / kWaterColumns, v = -1.1 + 2.2 * j / kWaterRows;
      const osg::Vec3d through = osg::Vec3d(u, v, 1.0) * to_world;  // on the far plane
      osg::Vec3d ray = through - eye;
      ray.normalize();
      const double t = std::abs(ray.z()) > 1e-9 ? (level - eye.z()) / ray.z() : -1.0;
      osg::Vec3d hit;
      if (t > 0.0 && t < kWaterFar_m) {
        hit = eye + ray * t;
      } else {
        osg::Vec3d flat(ray.x(), ray.y(), 0.0);
        if (flat.normalize() < 1e-9) flat.set(1.0, 0.0, 0.0);
        hit = osg::Vec3d(eye.x(), eye.y(), level) + flat * kWaterFar_m;
      }
      water_base_[static_cast<std::size_t>(j * row + i)] = {hit.x(), hit.y()};
    }
  for (int j = 0; j <= kWaterRows; ++j)
    for (int i = 0; i <= kWaterColumns; ++i) {
      const auto base = [&](int a, int b) {
        return water_base_[static_cast<std::size_t>(std::min(b, kWaterRows) * row +
                                                    std::min(a, kWaterColumns))];
      };
      const auto [x, y] = base(i, j);
      const double cell = std::max(std::hypot(base(i + 1, j).first - x, base(i + 1, j).second - y),
                                   std::hypot(base(i, j + 1).first - x, base(i, j + 1).second - y));
      // the wind sea fades where the mesh is too coarse to carry it
      const double fade = std::clamp(2.0 - cell / (2.0 * finest), 0.0, 1.0);
      const double dx = 0.5;  // the swell's slope by central differences
      const double swell = swell_elevation_m(sea_, time_s_, x, y);
      const double swell_sx =
          (swell_elevation_m(sea_, time_s_, x + dx, y) - swell_elevation_m(sea_, time_s_, x - dx, y)) /
          (2 * dx);
      const double swell_sy =
          (swell_elevation_m(sea_, time_s_, x, y + dx) - swell_elevation_m(sea_, time_s_, x, y - dx)) /
          (2 * dx);
      const std::size_t k = static_cast<std::size_t>(j * row + i);
      vertices[k].set(static_cast<float>(x + fade * wind_sea_->displacement_x_at(x, y)),
                      static_cast<float>(y + fade * wind_sea_->displacement_y_at(x, y)),
                      static_cast<float>(level + swell + fade * wind_sea_->height_at(x, y)));
      const double wind_slope = std::hypot(wind_sea_->slope_x_at(x, y), wind_sea_->slope_y_at(x, y));
      slopes[k].set(static_cast<float>(swell_sx + fade * wind_sea_->slope_x_at(x, y)),
                    static_cast<float>(swell_sy + fade * wind_sea_->slope_y_at(x, y)));
      // the crests' foam: half way at the breaking slope, none at 0.75 of it, full at 1.25
      foam[k].set(
          static_cast<float>(std::clamp(0.5 + (wind_slope - foam_slope_) / (0.5 * foam_slope_), 0.0, 1.0)),
          static_cast<float>(fade));
    }
  vertices.dirty();
  slopes.dirty();
  foam.dirty();
  water_->dirtyBound();
}

void ImageGenerator::update_near_rain(const osg::Vec3d& eye) {
  // the drops within a few metres of the eye cross the picture in a frame: streaks the way such a drop moves
  // on the picture as it falls (at 7 m/s, drifting with the wind: straight down the picture looking ahead,
  // towards the nadir looking down); as many as the rain is heavy (400 in a 1280x720 picture at 50 mm/h),
  // placed afresh every 0.1 s
  const double intensity = std::clamp(rain_mm_per_h_ / 50.0, 0.0, 1.0);
  near_rain_->setNodeMask(intensity > 0.0 ? ~0u : 0u);
  if (intensity <= 0.0) return;
  auto& vertices = static_cast<osg::Vec3Array&>(*streaks_->getVertexArray());
  auto& colours = static_cast<osg::Vec4Array&>(*streaks_->getColorArray());
  vertices.clear();
  colours.clear();
  const osg::Camera& camera = *viewer_->getCamera();
  const osg::Matrixd to_clip = camera.getViewMatrix() * camera.getProjectionMatrix();
  const osg::Matrixd from_clip = osg::Matrixd::inverse(to_clip);
  const osg::Vec3d fall =
      osg::Vec3d(wind_mps_.x, wind_mps_.y, -7.0) / std::hypot(std::hypot(wind_mps_.x, wind_mps_.y), 7.0);
  const double w = width_, h = height_;
  const auto on_picture = [&](const osg::Vec3d& p, osg::Vec2d& at) {
    const osg::Vec4d clip = osg::Vec4d(p, 1.0) * to_clip;
    if (clip.w() <= 1e-9) return false;
    at = {(clip.x() / clip.w() + 1.0) / 2.0 * w, (clip.y() / clip.w() + 1.0) / 2.0 * h};
    return true;
  };
  const auto count = static_cast<int>(400.0 * intensity * (w * h) / (1280.0 * 720.0));
  const auto epoch = static_cast<std::uint64_t>(std::max(time_s_, 0.0) * 10.0);
  std::uint64_t seed = 0x9e3779b97f4a7c15ULL ^ (epoch * 0xbf58476d1ce4e5b9ULL);
  const auto uniform = [&seed] {
    seed ^= seed << 13;
    seed ^= seed >> 7;
    seed ^= seed << 17;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  for (int k = 0; k < count; ++k) {
    // a drop 2-4 m out along this pixel's ray, and where it is a moment later: the streak's way on the
    // picture
    const double x = uniform() * w, y = uniform() * h;
    const osg::Vec3d through = osg::Vec3d(2.0 * x / w - 1.0, 2.0 * y / h - 1.0, 1.0) * from_clip;
    osg::Vec3d ray = through - eye;
    ray.normalize();
    const osg::Vec3d drop = eye + ray * (2.0 + 2.0 * uniform());
    osg::Vec2d from, to;
    if (!on_picture(drop, from) || !on_picture(drop + fall * 0.2, to)) continue;
    osg::Vec2d way = to - from;
    const double d = way.length();
    if (d < 1e-9) continue;
    way *= (0.03 + 0.05 * uniform()) * h / d;
    const float alpha = static_cast<float>(0.18 + 0.22 * uniform());
    vertices.push_back(osg::Vec3(static_cast<float>(from.x()), static_cast<float>(from.y()), 0.0f));
    vertices.push_back(
        osg::Vec3(static_cast<float>(from.x() + way.x()), static_cast<float>(from.y() + way.y()), 0.0f));
    colours.push_back(osg::Vec4(0.80f, 0.83f, 0.87f, 0.0f));  // a streak fades in along its length
    colours.push_back(osg::Vec4(0.80f, 0.83f, 0.87f, alpha));
  }
  vertices.dirty();
  colours.dirty();
  static_cast<osg::DrawArrays*>(streaks_->getPrimitiveSet(0))->setCount(static_cast<int>(vertices.size()));
  streaks_->dirtyBound();
}

std::vector<std::pair<osg::Vec3, osg::Vec3>> ImageGenerator::rain_streaks() const {
  std::vector<std::pair<osg::Vec3, osg::Vec3>> out;
  if (near_rain_->getNodeMask() == 0u) return out;
  const auto& vertices = static_cast<const osg::Vec3Array&>(*streaks_->getVertexArray());
  for (std::size_t k = 0; k + 1 < vertices.size(); k += 2)
    out.emplace_back(vertices[k], vertices[k + 1]);
  return out;
}

std::optional<ImageGenerator::CameraPose> ImageGenerator::camera_pose(const EntityCamera& camera) const {
  const auto entity = std::find(entity_visuals_.begin(), entity_visuals_.end(), camera.entity);
  if (entity == entity_visuals_.end()) return std::nullopt;
  const core::Pose& pose = entity_poses_[static_cast<std::size_t>(entity - entity_visuals_.begin())];
  return CameraPose{pose.to_parent(camera.at_m), pose.direction_to_parent(camera.look),
                    pose.direction_to_parent(camera.up)};
}

void ImageGenerator::set_insets(const std::vector<Inset>& insets) {
  for (InsetView& v : insets_)
    frame_->removeChild(v.render);
  inset_quads_->removeDrawables(0, inset_quads_->getNumDrawables());
  insets_.clear();
  for (const Inset& inset : insets) {
    const auto camera = std::find_if(cameras_.begin(), cameras_.end(),
                                     [&](const EntityCamera& c) { return c.name == inset.camera; });
    if (camera == cameras_.end() ||
        std::find(entity_visuals_.begin(), entity_visuals_.end(), camera->entity) == entity_visuals_.end())
      continue;  // a camera of another machine
    InsetView v{inset, *camera, std::max(16, static_cast<int>(std::lround(inset.width * width_))),
                std::max(16, static_cast<int>(std::lround(inset.height * height_))), new osg::Camera};
    // the world drawn into a texture of its own before the frame, then shown as a quad under the HUD's lines
    osg::ref_ptr<osg::Texture2D> texture = new osg::Texture2D;
    texture->setTextureSize(v.width, v.height);
    texture->setInternalFormat(GL_RGB);
    texture->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR);
    texture->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    v.render->setRenderOrder(osg::Camera::PRE_RENDER);
    v.render->setCullMask(~(kMainView | kCastsShadow));  // the lit scene without a shadow pass of its own
    v.render->setInheritanceMask(v.render->getInheritanceMask() & ~osg::CullSettings::CULL_MASK);
    v.render->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
    v.render->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    v.render->setViewport(0, 0, v.width, v.height);
    v.render->setClearMask(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    v.render->setClearColor(osg::Vec4(0.5f, 0.6f, 0.7f, 1.0f));
    v.render->attach(osg::Camera::COLOR_BUFFER, texture.get());
    v.render->addChild(root_);
    frame_->insertChild(0, v.render);
    const float x0 = static_cast<float>(inset.left * width_), y0 = static_cast<float>(inset.bottom * height_);
    const float w = static_cast<float>(v.width), h = static_cast<float>(v.height);
    // a mirror shows what is behind reversed left to right: its texture read from right to left
    osg::ref_ptr<osg::Geometry> quad = osg::createTexturedQuadGeometry(
        osg::Vec3(x0, y0, 0.0f), osg::Vec3(w, 0.0f, 0.0f), osg::Vec3(0.0f, h, 0.0f),
        inset.mirror ? 1.0f : 0.0f, 0.0f, inset.mirror ? 0.0f : 1.0f, 1.0f);
    quad->getOrCreateStateSet()->setTextureAttributeAndModes(0, texture.get(), osg::StateAttribute::ON);
    // a dark frame round it
    osg::ref_ptr<osg::Geometry> frame =
        osg::createTexturedQuadGeometry(osg::Vec3(x0 - 2.0f, y0 - 2.0f, 0.0f),
                                        osg::Vec3(w + 4.0f, 0.0f, 0.0f), osg::Vec3(0.0f, h + 4.0f, 0.0f));
    osg::ref_ptr<osg::Vec4Array> black = new osg::Vec4Array;
    black->push_back(osg::Vec4(0.05f, 0.05f, 0.05f, 1.0f));
    frame->setColorArray(black, osg::Array::BIND_OVERALL);
    inset_quads_->addDrawable(frame);
    inset_quads_->addDrawable(quad);
    insets_.push_back(std::move(v));
  }
}

std::vector<Inset> ImageGenerator::insets() const {
  std::vector<Inset> out;
  for (const InsetView& v : insets_)
    out.push_back(v.inset);
  return out;
}

void ImageGenerator::place_insets() {
  // a cab's monitors and mirrors, seen from the cab only
  const bool shown = view_.kind == View::Kind::kCab && view_.insets;
  inset_quads_->setNodeMask(shown ? ~0u : 0u);
  for (InsetView& v : insets_) {
    const std::optional<CameraPose> pose = camera_pose(v.camera);
    v.render->setNodeMask(shown && pose ? ~0u : 0u);
    if (!pose) continue;
    v.render->setProjectionMatrixAsPerspective(v.camera.fov_vertical_rad * 180.0 / kPi,
                                               static_cast<double>(v.width) / v.height, 0.3, 6000.0);
    v.render->setViewMatrixAsLookAt(to_osg(pose->eye), to_osg(pose->eye + pose->look), to_osg(pose->up));
  }
}

std::optional<std::pair<double, double>> ImageGenerator::project_inset(std::size_t n,
                                                                       const core::Vec3& world) const {
  const InsetView& v = insets_.at(n);
  const osg::Vec4d clip = osg::Vec4d(world.x, world.y, world.z, 1.0) * v.render->getViewMatrix() *
                          v.render->getProjectionMatrix();
  if (clip.w() <= 0.0) return std::nullopt;
  double x = clip.x() / clip.w();
  const double y = clip.y() / clip.w();
  if (std::abs(x) > 1.0 || std::abs(y) > 1.0) return std::nullopt;
  if (v.inset.mirror) x = -x;
  return std::pair{v.inset.left * width_ + (x + 1.0) / 2.0 * v.width,
                   height_ - (v.inset.bottom * height_ + (y + 1.0) / 2.0 * v.height)};
}

const osg::Image& ImageGenerator::render() {
  place_camera();
  place_insets();
  osg::Vec3d eye, centre, up;
  viewer_->getCamera()->getViewMatrixAsLookAt(eye, centre, up);
  sky_->setMatrix(osg::Matrixd::translate(eye));
  cloud_uniforms_[1]->set(osg::Vec2(static_cast<float>(eye.x() - cloud_drift_m_.first),
                                    static_cast<float>(eye.y() - cloud_drift_m_.second)));
  update_water(eye);
  update_near_rain(eye);
  viewer_->frame();
  if (multisamples_ > 1) read_multisampled();
  return *image_;
}

bool ImageGenerator::write_png(const std::string& path) const {
  return osgDB::writeImageFile(*image_, path);  // the PNG writer turns OpenGL's bottom-first rows over
}

std::optional<std::pair<double, double>> ImageGenerator::project(const core::Vec3& world) const {
  const osg::Camera* camera = viewer_->getCamera();
  const osg::Vec4d clip =
      osg::Vec4d(world.x, world.y, world.z, 1.0) * camera->getViewMatrix() * camera->getProjectionMatrix();
  if (clip.w() <= 0.0) return std::nullopt;
  const double x = clip.x() / clip.w(), y = clip.y() / clip.w();
  return std::pair{(x + 1.0) / 2.0 * width_, (1.0 - y) / 2.0 * height_};
}

}  // namespace harbour::ig
