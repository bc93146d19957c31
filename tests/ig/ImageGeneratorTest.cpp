// The image generator drawing hand-made published states (it reads nothing else): measured properties of
// the pictures, headless through EGL on llvmpipe.
#include "harbour/ig/ImageGenerator.h"

#include <gtest/gtest.h>

#include <osg/Image>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/io/DataError.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/sim/Simulation.h"

namespace harbour::ig {
namespace {

constexpr int kWidth = 320, kHeight = 240;

// a scene of its own: a "camera mast" whose cab the view rides, and two 40 ft boxes
scene::SceneDescription scene() {
  scene::SceneDescription d;
  d.machine = "test";
  d.entities.push_back({"mast", "none", {}});
  d.entities.push_back({"near box", "test.box", {6.1, 1.22, 1.3}});
  d.entities.push_back({"far box", "test.box", {6.1, 1.22, 1.3}});
  d.rope_count = 1;
  return d;
}

std::map<std::string, Visual> looks() {
  Visual box;
  VisualPart
      part;  // a box end on: a panel square to the view, so its pixels centre on its centre's projection
  part.size_m = core::Vec3{0.2, 2.44, 2.6};
  part.color = {0.9, 0.1, 0.1};
  box.parts.push_back(part);
  return {{"test.box", box}};
}

// the cab at 10 m looking along +x, level; boxes ahead at `near_x` and `far_x`, lifted into the sky's view
scene::Snapshot state(double near_x, double far_x, double visibility_m, double time_of_day_h) {
  scene::Snapshot s;
  s.time_of_day_h = time_of_day_h;
  s.visibility_m = visibility_m;
  s.cab.pose.position = {0.0, 0.0, 10.0};
  s.entity_count = 3;
  s.entities[0] = {0, 0, {}};
  s.entities[1] = {1, 0, {core::Mat3::identity(), {near_x, 0.0, 14.0}}};
  s.entities[2] = {2, 0, {core::Mat3::identity(), {far_x, 0.0, 14.0 + (far_x - near_x) * 0.04}}};
  return s;
}

View level() {
  View v;
  v.pitch_rad = 0.0;
  v.fov_vertical_rad = 0.6;
  return v;
}

osg::Vec3 pixel(const osg::Image& image, double x, double y_from_top) {
  const int col = std::clamp(static_cast<int>(std::lround(x)), 0, image.s() - 1);
  const int row = std::clamp(image.t() - 1 - static_cast<int>(std::lround(y_from_top)), 0, image.t() - 1);
  const unsigned char* p = image.data(col, row);
  return {p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f};
}

double luminance(const osg::Vec3& c) {
  return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z();
}

// the shipped looks' safety yellow (grab shells, spreaders), lit or shaded
bool safety_yellow(const osg::Vec3& p) {
  return p.x() > 0.25 && p.y() > 0.6 * p.x() && p.z() < 0.45 * p.x();
}

// each pixel's luminance as the median of its 3x3 neighbourhood, rows from the top: the rain's drops falling
// past, a pixel or two wide, go
std::vector<double> median_luminance(const osg::Image& image) {
  std::vector<double> l(static_cast<std::size_t>(image.s() * image.t()));
  for (int y = 0; y < image.t(); ++y)
    for (int x = 0; x < image.s(); ++x) {
      std::array<double, 9> around{};
      for (std::size_t k = 0; k < around.size(); ++k)
        around[k] = luminance(pixel(image, x + static_cast<int>(k % 3) - 1, y + static_cast<int>(k / 3) - 1));
      std::nth_element(around.begin(), around.begin() + 4, around.end());
      l[static_cast<std::size_t>(y * image.s() + x)] = around[4];
    }
  return l;
}

// each pixel's luminance, rows from the top
std::vector<double> luminances(const osg::Image& image) {
  std::vector<double> l;
  for (int y = 0; y < image.t(); ++y)
    for (int x = 0; x < image.s(); ++x)
      l.push_back(luminance(pixel(image, x, y)));
  return l;
}

double mean_luminance(const osg::Image& image) {
  double sum = 0.0;
  for (int y = 0; y < image.t(); ++y)
    for (int x = 0; x < image.s(); ++x)
      sum += luminance(pixel(image, x, y));
  return sum / (image.s() * image.t());
}

TEST(ImageGenerator, TheSkyIsBrighterAtNoonThanAtDuskAndDarkAtNight) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(level());
  double noon = 0, dusk = 0, night = 0;
  for (auto [t, out] : {std::pair{12.0, &noon}, std::pair{18.3, &dusk}, std::pair{23.0, &night}}) {
    ig.update(state(40.0, 200.0, 20000.0, t));
    *out = mean_luminance(ig.render());
  }
  std::printf("mean luminance: noon %.3f, dusk %.3f, night %.3f (%s)\n", noon, dusk, night,
              ig.renderer().c_str());
  EXPECT_GT(noon, dusk * 1.3);
  EXPECT_GT(dusk, night * 3.0);
  EXPECT_LT(night, 0.05);
}

// Twilight lasts as long as the sun's depression says. Looking straight up through an evening, the zenith's
// brightness in the picture (the median of its middle, stars aside) is bisected for the moment it falls to
// what it shows at 40° N on the March equinox when the sun is 6° down (civil twilight's end). At 60° N at
// midsummer that moment is where the textbook's sun, sin h = sin φ sin δ + cos φ cos δ cos H (Cooper's
// declination), stands 6° down too (within 0.25°, the picture's 8-bit step) — two hours after sunset there
// against half an hour at 40° N.
TEST(ImageGenerator, TwilightLastsAsLongAsTheSunsDepressionSays) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  View up = level();
  up.hud = false;
  up.pitch_rad = std::numbers::pi / 2.0;
  ig.set_view(up);
  const auto zenith_brightness = [&](double latitude_deg, double day_of_year, double t_h) {
    scene::Snapshot snapshot = state(40.0, 200.0, 20000.0, t_h);
    snapshot.latitude_deg = latitude_deg;
    snapshot.day_of_year = day_of_year;
    ig.update(snapshot);
    const osg::Image& image = ig.render();
    std::vector<double> middle;
    for (int y = kHeight / 2 - 10; y <= kHeight / 2 + 10; ++y)
      for (int x = kWidth / 2 - 10; x <= kWidth / 2 + 10; ++x)
        middle.push_back(luminance(pixel(image, x, y)));
    std::nth_element(middle.begin(), middle.begin() + middle.size() / 2, middle.end());
    return middle[middle.size() / 2];
  };
  // the local solar time after noon when the sun stands at `elevation_deg` (the textbook's hour angle)
  const auto when = [](double latitude_deg, double day_of_year, double elevation_deg) {
    const double deg = std::numbers::pi / 180.0;
    const double declination = 23.45 * deg * std::sin(2.0 * std::numbers::pi * (284.0 + day_of_year) / 365.0);
    const double cos_h =
        (std::sin(elevation_deg * deg) - std::sin(latitude_deg * deg) * std::sin(declination)) /
        (std::cos(latitude_deg * deg) * std::cos(declination));
    return 12.0 + std::acos(cos_h) / deg / 15.0;
  };
  // the textbook's elevation of the sun, degrees, at `t_h`
  const auto elevation = [](double latitude_deg, double day_of_year, double t_h) {
    const double deg = std::numbers::pi / 180.0;
    const double declination = 23.45 * deg * std::sin(2.0 * std::numbers::pi * (284.0 + day_of_year) / 365.0);
    return std::asin(std::sin(latitude_deg * deg) * std::sin(declination) +
                     std::cos(latitude_deg * deg) * std::cos(declination) *
                         std::cos((t_h - 12.0) * 15.0 * deg)) /
           deg;
  };
  const double civil_end = zenith_brightness(40.0, 80.0, when(40.0, 80.0, -6.0));
  const double at_sunset = zenith_brightness(40.0, 80.0, when(40.0, 80.0, 0.0));
  EXPECT_GT(at_sunset, 2.0 * civil_end);
  for (const auto& [latitude, day] : {std::pair{40.0, 80.0}, std::pair{60.0, 172.0}}) {
    double lighter = when(latitude, day, 0.0), darker = when(latitude, day, -6.5);
    for (int i = 0; i < 12; ++i) {
      const double mid = (lighter + darker) / 2.0;
      (zenith_brightness(latitude, day, mid) > civil_end ? lighter : darker) = mid;
    }
    const double crossed = (lighter + darker) / 2.0, astronomical = when(latitude, day, -6.0);
    std::printf(
        "%.0f deg N, day %.0f: sunset %.2f h; the zenith as dark as civil twilight's end at %.3f h, the "
        "sun 6 deg down at %.3f h (%.2f deg down then)\n",
        latitude, day, when(latitude, day, 0.0), crossed, astronomical, -elevation(latitude, day, crossed));
    EXPECT_NEAR(elevation(latitude, day, crossed), -6.0, 0.25) << latitude;  // a 8-bit picture's step
  }
  EXPECT_GT(when(60.0, 172.0, -6.0) - when(60.0, 172.0, 0.0),
            3.0 * (when(40.0, 80.0, -6.0) - when(40.0, 80.0, 0.0)));
}

// Rain brings its clouds: looking 29 deg up at noon, the clear sky is smooth, and in 8 mm/h of rain (the sky
// overcast) the picture has the clouds' texture (the mean change between pixels 4 apart, drops filtered out
// by a 3x3 median, three times the clear sky's). In 10 m/s of wind along +x the deck drifts at twice the
// wind: 10 s later the pattern has moved where the projection of a point 200 m along +x at the deck's height
// says, within a fifth of that shift, and matches the earlier picture better there than moved the other way.
TEST(ImageGenerator, RainCloudsTextureTheSkyAndDriftWithTheWind) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  View up = level();
  up.hud = false;
  up.pitch_rad = 0.5;  // the deck from 12 to 46 deg up: 5.6 to 1.7 km away
  ig.set_view(up);
  const auto picture = [&](double rain, double time_s) {
    scene::Snapshot s = state(40.0, 200.0, 20000.0, 12.0);
    s.rain_mm_per_h = rain;
    s.time_s = time_s;
    s.wind_mps = {10.0, 0.0, 0.0};
    ig.update(s);
    return median_luminance(ig.render());
  };
  const auto texture = [](const std::vector<double>& l) {
    double sum = 0.0;
    int n = 0;
    for (int y = 10; y < kHeight - 10; y += 2)
      for (int x = 10; x < kWidth - 14; x += 2, ++n)
        sum += std::abs(l[static_cast<std::size_t>(y * kWidth + x + 4)] -
                        l[static_cast<std::size_t>(y * kWidth + x)]);
    return sum / n;
  };
  const std::vector<double> clear = picture(0.0, 0.0), clouded = picture(8.0, 0.0),
                            later = picture(8.0, 10.0);
  std::printf("change between pixels 4 apart: clear sky %.4f, in 8 mm/h %.4f\n", texture(clear),
              texture(clouded));
  EXPECT_GT(texture(clouded), 3.0 * texture(clear));
  // the deck's drift in the picture: 2 x 10 m/s x 10 s = 200 m along +x, 1,190 m over the eye, where the
  // picture's middle looks
  const double ahead = 1190.0 / std::tan(0.5);
  const auto from = ig.project({ahead, 0.0, 1200.0}), to = ig.project({ahead + 200.0, 0.0, 1200.0});
  ASSERT_TRUE(from && to);
  const double dx = to->first - from->first, dy = to->second - from->second;
  const double expected = std::hypot(dx, dy);
  // how well the later picture matches the earlier one moved by `share` of the expected shift (mean square)
  const auto mismatch = [&](double share) {
    const int ox = static_cast<int>(std::lround(share * dx)), oy = static_cast<int>(std::lround(share * dy));
    double sum = 0.0;
    int n = 0;
    for (int y = kHeight / 2 - 25; y < kHeight / 2 + 25;
         ++y)  // about the middle, where the projection was taken
      for (int x = 60; x < kWidth - 60; ++x, ++n) {
        const double d = later[static_cast<std::size_t>((y + oy) * kWidth + x + ox)] -
                         clouded[static_cast<std::size_t>(y * kWidth + x)];
        sum += d * d;
      }
    return sum / n;
  };
  double best_share = 0.0, best = 1e9;
  for (double share = -1.0; share <= 2.0; share += 0.05)
    if (const double m = mismatch(share); m < best) {
      best = m;
      best_share = share;
    }
  std::printf("the deck moved %.1f px in 10 s (%.2f of the %.1f px its drift projects to)\n",
              best_share * expected, best_share, expected);
  EXPECT_GT(expected, 10.0);
  EXPECT_NEAR(best_share, 1.0, 0.2);
  EXPECT_LT(best, mismatch(-1.0));
}

TEST(ImageGenerator, FogHidesAFarBoxMoreThanANearOne) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(level());
  const auto contrast = [&](double visibility) {
    ig.update(state(30.0, 250.0, visibility, 12.0));
    const osg::Image& image = ig.render();
    const auto near = ig.project({30.0, 0.0, 14.0}), far = ig.project({250.0, 0.0, 14.0 + 220.0 * 0.04});
    // each box against the sky beside it, at its height (the dome darkens upwards)
    const auto c = [&](const std::pair<double, double>& at) {
      const osg::Vec3 p = pixel(image, at.first, at.second), beside = pixel(image, 5, at.second);
      return (p - beside).length() / std::max(beside.length(), 1e-3f);
    };
    return std::pair{c(*near), c(*far)};
  };
  const auto [near_clear, far_clear] = contrast(20000.0);
  const auto [near_fog, far_fog] = contrast(300.0);
  std::printf("contrast against the sky: clear near %.3f far %.3f; fog 300 m near %.3f far %.3f\n",
              near_clear, far_clear, near_fog, far_fog);
  // the fog's colour is grey: the sky beside the far box in 300 m of fog, its channels within 10 % of each
  // other
  ig.update(state(30.0, 250.0, 300.0, 12.0));
  const osg::Vec3 fog = pixel(ig.render(), 5, ig.project({250.0, 0.0, 14.0 + 220.0 * 0.04})->second);
  const double saturation = (std::max({fog.x(), fog.y(), fog.z()}) - std::min({fog.x(), fog.y(), fog.z()})) /
                            std::max({fog.x(), fog.y(), fog.z()});
  std::printf("the fog's colour: %.3f %.3f %.3f (saturation %.3f)\n", fog.x(), fog.y(), fog.z(), saturation);
  EXPECT_LT(saturation, 0.10);
  EXPECT_GT(fog.y(), 0.35) << "a daylit grey, not a night's";
  EXPECT_GT(far_clear, 0.5);              // both stand out in clear air
  EXPECT_GT(near_fog, 0.5 * near_clear);  // at 30 m in 300 m fog a box keeps most of its contrast
  EXPECT_LT(far_fog, 0.25 * far_clear);   // at 250 m it has nearly gone (Koschmieder: e^(-3.9 250/300))
  EXPECT_LT(far_fog / far_clear, near_fog / near_clear);
}

TEST(ImageGenerator, MovingAContainerInThePublishedStateMovesItsPixelsWhereProjectionSays) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(level());
  const auto red_centroid = [&](const osg::Image& image) {
    double sx = 0, sy = 0, n = 0;
    for (int y = 0; y < image.t(); ++y)
      for (int x = 0; x < image.s(); ++x) {
        const osg::Vec3 p = pixel(image, x, y);
        if (p.x() > 0.3 && p.x() > 2.5 * p.y() && p.x() > 2.5 * p.z()) {
          sx += x;
          sy += y;
          ++n;
        }
      }
    return std::tuple{sx / std::max(n, 1.0), sy / std::max(n, 1.0), n};
  };
  scene::Snapshot s = state(40.0, 5000.0, 20000.0, 12.0);  // the far box out of sight
  ig.update(s);
  const auto [x0, y0, n0] = red_centroid(ig.render());
  const auto p0 = ig.project({40.0, 0.0, 14.0});
  s.entities[1].pose.position = {40.0, 6.0, 11.0};  // 6 m to the left, 3 m lower
  ig.update(s);
  const auto [x1, y1, n1] = red_centroid(ig.render());
  const auto p1 = ig.project({40.0, 6.0, 11.0});
  ASSERT_GT(n0, 50.0);
  ASSERT_GT(n1, 50.0);
  EXPECT_NEAR(x0, p0->first, 2.0);
  EXPECT_NEAR(y0, p0->second, 2.0);
  EXPECT_NEAR(x1, p1->first, 2.0);
  EXPECT_NEAR(y1, p1->second, 2.0);
  EXPECT_LT(x1, x0 - 20.0);  // left in the picture
  EXPECT_GT(y1, y0 + 10.0);  // and lower
}

TEST(ImageGenerator, ARopesOscillationMovesItsPixels) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(level());
  scene::Snapshot s = state(40.0, 5000.0, 20000.0, 12.0);
  s.entity_count = 1;  // the rope alone
  s.rope_count = 1;
  s.rope_first[0] = 0;
  s.rope_points[0] = 21;
  const auto hang = [&](double amplitude) -> const osg::Image& {
    for (int k = 0; k <= 20; ++k) {
      const double f = k / 20.0;
      s.points[static_cast<std::size_t>(k)] = {30.0, amplitude * std::sin(std::numbers::pi * f),
                                               18.0 - 8.0 * f};
    }
    ig.update(s);
    return ig.render();
  };
  const osg::Image& straight = hang(0.0);
  const auto mid_straight = ig.project({30.0, 0.0, 14.0});
  const double dark_straight = luminance(pixel(straight, mid_straight->first, mid_straight->second));
  const osg::Image& bent = hang(1.5);  // the wave's midspan displacement
  const auto mid_bent = ig.project({30.0, 1.5, 14.0});
  const double at_old = luminance(pixel(bent, mid_straight->first, mid_straight->second));
  const double at_new = luminance(pixel(bent, mid_bent->first, mid_bent->second));
  EXPECT_LT(dark_straight, 0.2);  // the rope is drawn where it hangs
  EXPECT_LT(at_new, 0.2);         // and where it swung to
  EXPECT_GT(at_old, 0.4);         // the sky shows where it was
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// Every entity of every shipped exercise has a look: the harbour's or its machine file's.
TEST(Visuals, EveryLookTheShippedExercisesPublishIsInTheData) {
  const Looks looks = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  int exercises = 0;
  for (const auto& file : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/exercises")) {
    const sim::ExerciseSettings e = io::load_exercise(file.path().string());
    for (const scene::SceneDescription::Entity& entity : sim::Simulation(e.scenario).scene().entities)
      EXPECT_TRUE(looks.visuals.count(entity.visual))
          << file.path().filename() << ": no look for '" << entity.visual << "'";
    ++exercises;
  }
  EXPECT_GE(exercises, 27);
}

TEST(Visuals, BadLooksNameFileLineAndField) {
  const std::string path = (std::filesystem::temp_directory_path() / "harbour_looks.yaml").string();
  const auto error = [&](const std::string& text) {
    { std::ofstream(path) << text; }
    try {
      load_visuals(path);
    } catch (const io::DataError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(
      error("visuals:\n  - key: a\n    parts:\n      - {size: entity, at: [0, 0, 0], color: [1, 0, 0]}\n"),
      "");
  EXPECT_NE(
      error("visuals:\n  - key: a\n    parts:\n      - {size: entity, at: [0, 0, 0], color: livery}\n")
          .find("harbour_looks.yaml:4: visuals[0].parts[0].color: a livery colour needs the look's liveries"),
      std::string::npos);
  EXPECT_NE(
      error("visuals:\n  - key: a\n    parts:\n      - {size: [1, 2], at: [0, 0, 0], color: [1, 0, 0]}\n")
          .find("visuals[0].parts[0].size"),
      std::string::npos);
  EXPECT_NE(
      error("visuals:\n  - key: a\n    parts:\n      - {size: entity, at: [0, 0, 0], color: [2, 0, 0]}\n")
          .find("color"),
      std::string::npos);
  EXPECT_NE(
      error("visuals:\n  - key: a\n    parts: []\n  - key: a\n    parts: []\n").find("'a' is declared twice"),
      std::string::npos);
  EXPECT_NE(
      error("visuals:\n  - key: a\n    parts:\n      - {size: entity, at: [0, 0, 0], color: [1, 0, 0], "
            "material: chrome}\n")
          .find("harbour_looks.yaml:4: visuals[0].parts[0].material: 'chrome' is not a material: paint, "
                "steel, galvanised, rubber, concrete, glass, timber or bulk"),
      std::string::npos);
  const std::string no_looks = "visuals:\n  - key: a\n    parts: []\n";
  EXPECT_NE(
      error(no_looks + "scenery:\n  - {shape: cone, at: [0, 0, 0], size: [1, 1, 1], color: [1, 1, 1]}\n")
          .find("harbour_looks.yaml:5: scenery[0].shape: 'cone' is not a shape: box or cylinder"),
      std::string::npos);
  EXPECT_NE(
      error(no_looks + "scenery:\n  - {at: [0, 0, 0], size: [1, 1, 1], color: [1, 1, 1], material: 7}\n")
          .find("harbour_looks.yaml:5: scenery[0].material: '7' is not a material"),
      std::string::npos);
  EXPECT_NE(error(no_looks + "scenery:\n  - {at: [0, 0, 0], size: [1, 0, 1], color: [1, 1, 1]}\n")
                .find("scenery[0].size: sizes are positive"),
            std::string::npos);
  EXPECT_NE(error(no_looks + "scenery:\n  - {at: [0, 0, 0], size: [1, 1, 1], color: [1, 1, 1], repeat: 3}\n")
                .find("scenery[0].step"),
            std::string::npos);
  EXPECT_NE(error(no_looks + "floodlights:\n  - {entity: 7, at: [0, 0, 0], color: [1, 1, 1], range_m: 1}\n")
                .find("floodlights[0].range_m"),
            std::string::npos);
  // parts that are lattices or meshes
  const std::string part = "visuals:\n  - key: a\n    parts:\n      - ";
  EXPECT_EQ(error(part + "{shape: lattice, size: [10, 1, 1], at: [0, 0, 0], bay_m: 2, color: [1, 0, 0]}\n"),
            "");
  EXPECT_NE(error(part + "{shape: cone, size: [1, 1, 1], at: [0, 0, 0], color: [1, 0, 0]}\n")
                .find("harbour_looks.yaml:4: visuals[0].parts[0].shape: 'cone' is not a shape: box, lattice, "
                      "container, tyre, shell, hull, mesh, girder, walkway, stairs, cylinder, member, "
                      "spreader or deckhouse"),
            std::string::npos);
  EXPECT_NE(error(part + "{shape: lattice, size: [10, 1, 1], at: [0, 0, 0], member_m: 9, color: [1, 0, 0]}\n")
                .find("visuals[0].parts[0].member_m"),
            std::string::npos);
  EXPECT_NE(error(part + "{shape: mesh, file: nowhere.obj, at: [0, 0, 0], color: [1, 0, 0]}\n")
                .find("visuals[0].parts[0].file: no such file"),
            std::string::npos);
  // a rolling part is a tyre, rolling level across its axle
  EXPECT_EQ(error(part + "{shape: tyre, size: [1, 0.4, 1], at: [0, 0, 0], color: [0, 0, 0], "
                         "rolls: {with: speed_kmh, unit_mps: 0.277778}}\n"),
            "");
  EXPECT_NE(error(part + "{size: [1, 1, 1], at: [0, 0, 0], color: [0, 0, 0], rolls: {with: speed_kmh}}\n")
                .find("harbour_looks.yaml:4: visuals[0].parts[0].rolls: only a tyre rolls"),
            std::string::npos);
  EXPECT_NE(error(part + "{shape: tyre, size: [0.4, 1, 1], at: [0, 0, 0], color: [0, 0, 0], "
                         "rolls: {with: gantry_mps}}\n")
                .find("visuals[0].parts[0].rolls.along: a level direction across the tyre's axle"),
            std::string::npos);
  // steelwork: members between two points, stairs of EN ISO 14122-3's steps, walkways' rails, repeats
  EXPECT_EQ(
      error(part + "{shape: member, from: [0, 0, 0], to: [3, 4, 0], section_m: [0.3, 0.4], color: [1, 0, 0], "
                   "repeat: 3, step: [0, 2, 0]}\n"),
      "");
  {
    {
      std::ofstream(path) << part +
                                 "{shape: member, from: [0, 0, 0], to: [3, 4, 0], section_m: [0.3, 0.4], "
                                 "color: [1, 0, 0], repeat: 3, step: [0, 2, 0]}\n";
    }
    const std::vector<VisualPart> members = load_visuals(path).at("a").parts;
    ASSERT_EQ(members.size(), 3u);
    EXPECT_DOUBLE_EQ(members[2].centre_m.y, 6.0);
    EXPECT_DOUBLE_EQ(members[0].size_m->x, 5.0);
    EXPECT_DOUBLE_EQ(members[0].along.y, 0.8);
  }
  EXPECT_NE(
      error(part +
            "{shape: member, from: [1, 1, 1], to: [1, 1, 1], section_m: [0.3, 0.4], color: [1, 0, 0]}\n")
          .find("visuals[0].parts[0].to: a member's ends are apart"),
      std::string::npos);
  EXPECT_NE(
      error(part + "{shape: member, from: [0, 0, 0], to: [1, 1, 1], section_m: [0.3], color: [1, 0, 0]}\n")
          .find("visuals[0].parts[0].section_m: expected [width, depth]"),
      std::string::npos);
  EXPECT_EQ(error(part + "{shape: stairs, size: [4, 1, 3.25], at: [0, 0, 0], color: [1, 1, 0]}\n"), "");
  EXPECT_NE(
      error(part + "{shape: stairs, size: [2, 1, 3.25], at: [0, 0, 0], color: [1, 1, 0]}\n")
          .find("visuals[0].parts[0].size: a flight 2 m long and 3.25 m high (58.4 deg) has no steps of EN "
                "ISO 14122-3"),
      std::string::npos);
  EXPECT_NE(
      error(part + "{shape: walkway, size: [9, 1, 1.1], at: [0, 0, 0], rails: left, color: [1, 1, 0]}\n")
          .find("visuals[0].parts[0].rails: 'left' is not a side: both, positive, negative or none"),
      std::string::npos);
  EXPECT_NE(error(part + "{shape: cylinder, size: [1, 2, 3], at: [0, 0, 0], color: [1, 1, 0]}\n")
                .find("visuals[0].parts[0].size: a cylinder's size is written out: two equal sides"),
            std::string::npos);
  EXPECT_NE(error(no_looks + "floodlights:\n  - {entity: a, at: [0, 0, 30], color: [1, 1, 1], range_m: 50, "
                             "mast: true}\n")
                .find("floodlights[0].mast: a light mast stands on the quay under a lamp at least 5 m up"),
            std::string::npos);
  const std::string junk = (std::filesystem::temp_directory_path() / "harbour_junk.obj").string();
  { std::ofstream(junk) << "this is not a model\n"; }
  EXPECT_NE(error(part + "{shape: mesh, file: harbour_junk.obj, at: [0, 0, 0], color: [1, 0, 0]}\n")
                .find("visuals[0].parts[0].file: osgDB could not read a model from"),
            std::string::npos);
}

// A lattice girder lets the sky through between its members; a mesh part (the shipped funnel, OBJ through
// osgDB) draws where its geometry is, in the part's colour where the file gives none.
TEST(ImageGenerator, LatticeAndMeshPartsDrawAsTheirGeometry) {
  const auto red_pixels = [](const osg::Image& image) {
    int n = 0;
    for (int y = 0; y < image.t(); ++y)
      for (int x = 0; x < image.s(); ++x) {
        const osg::Vec3 p = pixel(image, x, y);
        n += p.x() > 0.3 && p.x() > 2.5 * p.y() && p.x() > 2.5 * p.z();
      }
    return n;
  };
  const auto drawn = [&](const VisualPart& part) {
    Visual look;
    look.parts.push_back(part);
    ImageGenerator ig(scene(), {{"test.box", look}}, kWidth, kHeight);
    ig.set_view(level());
    ig.update(state(40.0, 5000.0, 20000.0, 12.0));
    return red_pixels(ig.render());
  };
  VisualPart solid;  // a 2 x 2 m section, 6 m tall, side on
  solid.size_m = core::Vec3{2.0, 2.0, 6.0};
  solid.color = {0.9, 0.1, 0.1};
  VisualPart lattice = solid;
  lattice.shape = VisualPart::Shape::kLattice;
  lattice.bay_m = 2.0;
  lattice.member_m = 0.15;
  const int solid_pixels = drawn(solid), lattice_pixels = drawn(lattice);
  EXPECT_GT(solid_pixels, 200);
  EXPECT_GT(lattice_pixels, solid_pixels / 10);     // its members show
  EXPECT_LT(lattice_pixels, solid_pixels * 2 / 3);  // and the sky between them
  VisualPart mesh;
  mesh.shape = VisualPart::Shape::kMesh;
  mesh.mesh = std::string(HARBOUR_DATA_DIR) + "/visuals/meshes/funnel.obj";
  mesh.centre_m = {0.0, 0.0, -4.0};  // the funnel's foot 4 m below the box's place: 9 m tall
  ASSERT_TRUE(read_mesh(mesh.mesh));
  Visual look;
  look.parts.push_back(mesh);
  ImageGenerator ig(scene(), {{"test.box", look}}, kWidth, kHeight);
  ig.set_view(level());
  ig.update(state(40.0, 5000.0, 20000.0, 12.0));
  const osg::Image& image = ig.render();
  // dark (its material) where the funnel stands, sky beside it
  const auto middle = ig.project({40.0, 0.0, 14.0});
  const auto beside = ig.project({40.0, 8.0, 14.0});
  EXPECT_LT(luminance(pixel(image, middle->first, middle->second)), 0.2);
  EXPECT_GT(luminance(pixel(image, beside->first, beside->second)), 0.3);
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

TEST(ImageGenerator, TheHudShowsTheMachinesIndicatorsByNameAndTheAlarms) {
  scene::SceneDescription d = scene();
  d.indicators = {"load_t", "lamp_locked", "gear"};
  ImageGenerator ig(d, looks(), kWidth, kHeight);
  ig.set_hud({{"load_t", "load", "t", 1, false},
              {"lamp_locked", "LOCKED", "", 0, true},
              {"absent", "x", "", 0, false}});
  ig.set_view(level());
  scene::Snapshot s = state(40.0, 5000.0, 20000.0, 12.0);
  s.time_s = 12.345;
  s.wind_mps = {3.0, 4.0, 0.0};
  s.indicator_count = 3;
  s.indicators[0] = 41.26;
  s.indicators[1] = 0.0;
  ig.update(s);
  EXPECT_EQ(ig.hud_text(), "t 12.3 s   wind 5.0 m/s   load 41.3 t");
  const osg::Image& plain = ig.render();
  const auto top_band = [&](const osg::Image& image) {  // the HUD's lines: the top 15 % of the picture
    double sum = 0.0;
    for (int y = 0; y < kHeight * 15 / 100; ++y)
      for (int x = 0; x < kWidth; ++x)
        sum += luminance(pixel(image, x, y));
    return sum;
  };
  const double before = top_band(plain);
  s.indicators[1] = 1.0;
  s.devices_missing = 1;
  ig.update(s);
  EXPECT_EQ(
      ig.hud_text(),
      "t 12.3 s   wind 5.0 m/s   load 41.3 t   LOCKED\nINPUT DEVICE MISSING: ITS CONTROLS ARE NEUTRAL   ");
  const double after = top_band(ig.render());
  EXPECT_NE(after, before);  // the lamp and the alarm are drawn
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// the view from 40 m above the quay's apron, looking straight down at (0, 0, 0)
scene::Snapshot over_the_quay(double time_of_day_h, double rain_mm_per_h) {
  scene::Snapshot s = state(5000.0, 5000.0, 20000.0, time_of_day_h);
  s.cab.pose.position = {-10.0, 0.0, 40.0};
  s.rain_mm_per_h = rain_mm_per_h;
  return s;
}

View down() {
  View v;
  v.pitch_rad = -std::numbers::pi / 2.0 + 1e-3;
  v.fov_vertical_rad = 0.5;
  return v;
}

double centre_luminance(const osg::Image& image) {
  double sum = 0.0;
  for (int y = kHeight / 2 - 10; y < kHeight / 2 + 10; ++y)
    for (int x = kWidth / 2 - 10; x < kWidth / 2 + 10; ++x)
      sum += luminance(pixel(image, x, y));
  return sum / 400.0;
}

TEST(ImageGenerator, FloodlightsLightTheQuayAtNightOnly) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(down());
  ig.update(over_the_quay(23.0, 0.0));
  const double dark = centre_luminance(ig.render());
  ig.set_floodlights({{{-10.0, 0.0, 30.0}, {1.0, 0.9, 0.75}, 60.0}});
  ig.update(over_the_quay(23.0, 0.0));
  const double lit = centre_luminance(ig.render());
  ig.update(over_the_quay(12.0, 0.0));
  const double noon_with = centre_luminance(ig.render());
  ig.set_floodlights({});
  ig.update(over_the_quay(12.0, 0.0));
  const double noon_without = centre_luminance(ig.render());
  std::printf("quay at night %.3f, under a floodlight %.3f; at noon %.3f with, %.3f without\n", dark, lit,
              noon_with, noon_without);
  EXPECT_GT(lit, 2.0 * dark);
  EXPECT_NEAR(noon_with, noon_without, 1e-6);  // off by day
}

// A lit floodlight is seen as a lamp at night from below it: its glow where it projects; none by day, and
// none from above (a floodlight faces down).
TEST(ImageGenerator, ALitLampGlowsAtNightSeenFromBelowOnly) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  const core::Vec3 lamp{-10.0, 30.0, 30.0};  // beside the boxes, clear of them
  const auto seen_from = [&](const core::Vec3& eye, double time_of_day_h) {
    View v;
    v.kind = View::Kind::kFree;
    v.position_m = eye;
    const core::Vec3 to = lamp - eye;
    v.yaw_rad = std::atan2(to.y, to.x);
    v.pitch_rad = std::atan2(to.z, std::hypot(to.x, to.y));
    v.fov_vertical_rad = 0.6;
    ig.set_view(v);
    ig.update(state(5000.0, 5000.0, 20000.0, time_of_day_h));
    const osg::Image& image = ig.render();
    const auto at = ig.project(lamp);
    EXPECT_TRUE(at.has_value());
    return at ? luminance(pixel(image, static_cast<int>(at->first), static_cast<int>(at->second))) : -1.0;
  };
  const core::Vec3 below{-10.0, 0.0, 2.0}, above{-10.0, 10.0, 70.0};
  ig.set_floodlights({});
  const double night_unlit = seen_from(below, 23.0), above_unlit = seen_from(above, 23.0);
  const double noon_unlit = seen_from(below, 12.0);
  ig.set_floodlights({{lamp, {1.0, 0.9, 0.75}, 60.0}});
  const double night = seen_from(below, 23.0), from_above = seen_from(above, 23.0);
  const double noon = seen_from(below, 12.0);
  std::printf(
      "the lamp from below at night %.3f (%.3f without it), from above %.3f (%.3f), at noon %.3f "
      "(%.3f)\n",
      night, night_unlit, from_above, above_unlit, noon, noon_unlit);
  EXPECT_GT(night, 0.6);  // the lamp's colour (luminance 0.91) at its glow's core
  EXPECT_LT(night_unlit, 0.1);
  EXPECT_LT(from_above - above_unlit, 0.2);  // the quay under it is lit, the lamp not seen
  EXPECT_NEAR(noon, noon_unlit, 1e-6);
}

TEST(ImageGenerator, AMachinesLampRidesItAndGoesOutInAPowerFailure) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(down());
  scene::Snapshot night = over_the_quay(23.0, 0.0);
  ig.update(night);
  const double dark = centre_luminance(ig.render());
  // seven lamps on a machine this scene lacks (they take none of the seven lights), then one on the near box,
  // 16 m above the quay under the view; the box itself far away
  std::vector<Floodlight> lamps(7, Floodlight{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 60.0, "other.machine"});
  const core::Vec3 box_at = night.entities[1].pose.position;
  lamps.push_back({core::Vec3{-10.0, 0.0, 16.0} - box_at, {1.0, 0.9, 0.75}, 60.0, "test.box"});
  ig.set_floodlights(lamps);
  ig.update(night);
  const double lit = centre_luminance(ig.render());
  night.entities[1].pose.position = box_at + core::Vec3{0.0, 200.0, 0.0};  // the lamp rides its box away
  ig.update(night);
  const double moved = centre_luminance(ig.render());
  night.entities[1].pose.position = box_at;
  night.power_off = true;
  ig.update(night);
  const double power_off = centre_luminance(ig.render());
  night.power_off = false;
  ig.update(night);
  const double power_back = centre_luminance(ig.render());
  std::printf("quay at night %.3f; the box's lamp over it %.3f, moved away %.3f; power off %.3f, back %.3f\n",
              dark, lit, moved, power_off, power_back);
  EXPECT_GT(lit, 2.0 * dark);
  EXPECT_LT(moved, 1.2 * dark);
  EXPECT_NEAR(power_off, dark, 0.2 * dark);
  EXPECT_NEAR(power_back, lit, 1e-6);
}

TEST(ImageGenerator, RainWetsAndDarkensTheQuay) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(down());
  ig.update(over_the_quay(12.0, 0.0));
  const double dry = centre_luminance(ig.render());
  ig.update(over_the_quay(12.0, 10.0));
  const double wet = centre_luminance(ig.render());
  std::printf("quay luminance dry %.3f, in 10 mm/h rain %.3f\n", dry, wet);
  EXPECT_LT(wet, 0.8 * dry);
  EXPECT_GT(wet, 0.4 * dry);
}

// Rain wets every face turned up, and a wet face is darker the darker it was, as Lekner & Dorf's (1988) film
// model says: A_wet = (1 - re)(1 - ri) A / (1 - ri A), re = 0.066, ri = 0.472. Three painted plates of albedo
// 0.6, 0.35 and 0.15 side by side, seen from above at noon dry and in 2 mm/h (wet through, with few drops in
// the picture: their timing follows the host's clock): the ratio of their steps, (L1 - L2) / (L2 - L3),
// cancels the light (the sun's, the overcast's) and the sky's reflection (the same on each), and goes from
// 1.25 dry to the model's 1.62 wet, within 5 %.
TEST(ImageGenerator, RainDarkensEveryFaceTurnedUpAsAWaterFilmDoes) {
  scene::SceneDescription d;
  d.machine = "test";
  d.entities.push_back({"plates", "test.plates", {9.0, 2.5, 0.1}});
  Visual plates;
  const std::array<double, 3> albedo{0.6, 0.35, 0.15};
  for (int k = 0; k < 3; ++k) {
    VisualPart part;
    part.size_m = core::Vec3{5.0, 5.0, 0.1};
    part.centre_m = {-6.0 + 6.0 * k, 0.0, 0.0};
    part.color = {albedo[static_cast<std::size_t>(k)], albedo[static_cast<std::size_t>(k)],
                  albedo[static_cast<std::size_t>(k)]};
    plates.parts.push_back(part);
  }
  ImageGenerator ig(d, {{"test.plates", plates}}, kWidth, kHeight);
  ig.set_surface_detail(false);
  View v;
  v.kind = View::Kind::kFree;
  v.position_m = {0.0, 0.0, 40.0};
  v.yaw_rad = 0.0;
  v.pitch_rad = -std::numbers::pi / 2.0 + 1e-3;
  v.fov_vertical_rad = 0.5;
  v.hud = false;
  ig.set_view(v);
  const auto steps = [&](double rain) {
    scene::Snapshot s;
    s.time_of_day_h = 12.0;
    s.visibility_m = 20000.0;
    s.rain_mm_per_h = rain;
    s.entity_count = 1;
    s.entities[0] = {0, 0, {core::Mat3::identity(), {0.0, 0.0, 1.0}}};
    ig.update(s);
    const std::vector<double> l = median_luminance(ig.render());
    std::array<double, 3> plate{};
    for (int k = 0; k < 3; ++k) {
      const auto at = ig.project({-6.0 + 6.0 * k, 0.0, 1.05});
      std::vector<double> patch;
      for (int y = -10; y <= 10; ++y)
        for (int x = -10; x <= 10; ++x)
          patch.push_back(l[static_cast<std::size_t>((static_cast<int>(at->second) + y) * kWidth +
                                                     static_cast<int>(at->first) + x)]);
      std::nth_element(patch.begin(), patch.begin() + static_cast<std::ptrdiff_t>(patch.size() / 2),
                       patch.end());
      plate[static_cast<std::size_t>(k)] = patch[patch.size() / 2];
    }
    std::printf("plates %.3f %.3f %.3f in %.0f mm/h: steps' ratio %.3f\n", plate[0], plate[1], plate[2], rain,
                (plate[0] - plate[1]) / (plate[1] - plate[2]));
    return (plate[0] - plate[1]) / (plate[1] - plate[2]);
  };
  const auto wet_albedo = [](double a) { return (1.0 - 0.066) * (1.0 - 0.472) * a / (1.0 - 0.472 * a); };
  const double model = (wet_albedo(0.6) - wet_albedo(0.35)) / (wet_albedo(0.35) - wet_albedo(0.15));
  EXPECT_NEAR(steps(0.0), 0.25 / 0.20, 0.05 * 0.25 / 0.20);
  EXPECT_NEAR(steps(2.0), model, 0.05 * model) << "Lekner & Dorf: " << model;  // wet through, few drops
}

// A wet quay is a rough mirror: at night in rain a floodlight 30 m up and 60 m ahead glares on the quay
// where its mirror image (30 m below the quay) is seen — the brightest part of what the rain adds is centred
// within 3 pixels of that image's projection across the picture and 10 along it — while the dry quay has no
// glare there (its pool of light lies under the lamp, higher in the picture).
TEST(ImageGenerator, AWetQuayMirrorsAFloodlightWhereItsMirrorImageIs) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  View v = level();
  v.hud = false;
  v.pitch_rad = -0.45;
  ig.set_view(v);
  ig.set_floodlights({{{60.0, 0.0, 30.0}, {1.0, 0.9, 0.75}, 80.0}});
  const auto picture = [&](double rain) {
    scene::Snapshot s = state(40.0, 200.0, 20000.0, 23.0);
    s.rain_mm_per_h = rain;
    ig.update(s);
    return median_luminance(ig.render());
  };
  const std::vector<double> dry = picture(0.0), wet = picture(10.0);
  const auto mirror = ig.project({60.0, 0.0, -30.0}), lamp_pool = ig.project({60.0, 0.0, 0.0});
  ASSERT_TRUE(mirror && lamp_pool);
  // what the rain added, summed over 9x9 patches; the glare is where those sums are within 30 % of the most
  // (its plateau's centre of brightness)
  std::vector<double> patch(static_cast<std::size_t>(kWidth * kHeight), 0.0);
  double best = 0.0;
  for (int y = 4; y < kHeight - 4; ++y)
    for (int x = 4; x < kWidth - 4; ++x) {
      double added = 0.0;
      for (int j = -4; j <= 4; ++j)
        for (int i = -4; i <= 4; ++i) {
          const std::size_t k = static_cast<std::size_t>((y + j) * kWidth + x + i);
          added += wet[k] - dry[k];
        }
      patch[static_cast<std::size_t>(y * kWidth + x)] = added;
      best = std::max(best, added);
    }
  double weight = 0.0, cx = 0.0, cy = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double p = patch[static_cast<std::size_t>(y * kWidth + x)];
      if (p < 0.7 * best) continue;
      weight += p;
      cx += p * x;
      cy += p * y;
    }
  cx /= weight;
  cy /= weight;
  std::printf(
      "glare on the wet quay centred at (%.1f, %.1f), up to +%.3f a pixel; the lamp's mirror image projects "
      "to "
      "(%.1f, %.1f), its pool to (%.1f, %.1f)\n",
      cx, cy, best / 81.0, mirror->first, mirror->second, lamp_pool->first, lamp_pool->second);
  EXPECT_NEAR(cx, mirror->first, 3.0);
  EXPECT_NEAR(cy, mirror->second, 10.0);  // a rough mirror draws the glare out along the line of sight
  EXPECT_GT(best / 81.0, 0.10);           // bright against the night
  EXPECT_GT(mirror->second - lamp_pool->second, 20.0) << "the glare is not the pool of light";
}

// The sun's glint on a flat plate by GGX (Walter et al. 2007) with Smith-Schlick visibility and Schlick's
// Fresnel, as the lit shader has it, in units of the sun's diffuse light: pi D V F (n.l).
double ggx_glint(const core::Vec3& n, const core::Vec3& v, const core::Vec3& l, double f0, double roughness) {
  const core::Vec3 sum = l + v;
  const core::Vec3 h = sum * (1.0 / core::length(sum));
  const double nl = std::max(dot(n, l), 0.0), nv = std::max(dot(n, v), 1e-3), nh = std::max(dot(n, h), 0.0);
  const double a = roughness * roughness, a2 = a * a, d = nh * nh * (a2 - 1.0) + 1.0, k = a / 2.0;
  const double visibility = 0.25 / ((nl * (1.0 - k) + k) * (nv * (1.0 - k) + k));
  const double fresnel = f0 + (1.0 - f0) * std::pow(1.0 - dot(v, h), 5.0);
  return fresnel * a2 / (d * d) * visibility * nl;
}

// The sun's glint on a dark plate seen looking along the sun's mirror image: it peaks where the mirror image
// is (the picture's centre), as wide across and along the picture as GGX's lobe for the plate's roughness
// (the half-maximum widths within 15 %), and as bright for bare steel against paint as GGX and Fresnel say
// (within 20 %): steel (roughness 0.35) draws a glint 0.4 as wide across as paint (0.50).
TEST(ImageGenerator, ASunsGlintIsWhereAndAsWideAsGgxSays) {
  constexpr int kW = 320, kH = 240;
  constexpr double kFov = 1.2, kTime = 14.0;
  double elevation = 0.0;
  const core::Vec3 to_sun = sun_direction(kTime, 80.0, 40.0, elevation);
  ASSERT_GT(elevation, 0.3);
  const core::Vec3 eye{0.0, 0.0, 12.0}, mirror{to_sun.x, to_sun.y, -to_sun.z};
  constexpr double kTop = 1.0;  // the plate's top, clear of the quay
  const core::Vec3 glint_at = eye + mirror * ((eye.z - kTop) / to_sun.z);
  View view;
  view.kind = View::Kind::kFree;
  view.position_m = eye;
  view.yaw_rad = std::atan2(to_sun.y, to_sun.x);
  view.pitch_rad = -elevation;  // the picture's centre looks at the sun's mirror image
  view.fov_vertical_rad = kFov;
  view.hud = false;
  // a pixel's ray (the camera's forward, right and up; rows from the top)
  const core::Vec3 forward{std::cos(view.pitch_rad) * std::cos(view.yaw_rad),
                           std::cos(view.pitch_rad) * std::sin(view.yaw_rad), std::sin(view.pitch_rad)};
  const core::Vec3 right{std::sin(view.yaw_rad), -std::cos(view.yaw_rad), 0.0};
  const core::Vec3 up = core::cross(right, forward);
  const double focal = (kH / 2.0) / std::tan(kFov / 2.0);
  const auto ray = [&](int x, int y) {
    const core::Vec3 d =
        forward + right * ((x + 0.5 - kW / 2.0) / focal) + up * ((kH / 2.0 - y - 0.5) / focal);
    return d * (1.0 / core::length(d));
  };
  struct Glint {
    int x = 0, y = 0;           // the brightest pixel
    double peak = 0.0;          // over the plate's darkest
    double cx = 0.0, cy = 0.0;  // the centre of the pixels at or over half the peak
    int across = 0, along = 0;  // those pixels on the brightest's row and column
  };
  const auto measure = [&](const std::function<double(int, int)>& at) {
    Glint g;
    double lowest = 1e9;
    for (int y = kH / 8; y < kH; ++y)  // the plate fills the picture's lower seven eighths
      for (int x = 0; x < kW; ++x) {
        const double value = at(x, y);
        lowest = std::min(lowest, value);
        if (value > g.peak) g = {x, y, value, 0.0, 0.0, 0, 0};
      }
    g.peak -= lowest;
    int count = 0;
    for (int y = kH / 8; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        if (at(x, y) - lowest >= 0.5 * g.peak) {
          g.cx += x;
          g.cy += y;
          ++count;
          g.across += y == g.y ? 1 : 0;
          g.along += x == g.x ? 1 : 0;
        }
    g.cx /= count;
    g.cy /= count;
    return g;
  };
  std::map<std::string, Glint> drawn, ggx;
  for (const auto& [name, surface, f0, roughness] :
       {std::tuple{"steel", Surface::kSteel, 0.01, 0.35}, std::tuple{"paint", Surface::kPaint, 0.04, 0.50}}) {
    scene::SceneDescription d;
    d.machine = "test";
    d.entities.push_back({"plate", "test.plate", {300.0, 300.0, 0.1}});
    Visual plate;
    VisualPart part;
    part.color = {0.01, 0.01, 0.01};  // dark: the glint stands out and stays under the highlights' shoulder
    part.surface = surface;
    plate.parts.push_back(part);
    ImageGenerator ig(d, {{"test.plate", plate}}, kW, kH);
    ig.set_surface_detail(false);  // the finish's own roughness everywhere
    ig.set_view(view);
    scene::Snapshot s;
    s.time_of_day_h = kTime;
    s.visibility_m = 1e6;
    s.entity_count = 1;
    s.entities[0] = {0, 0, {core::Mat3::identity(), {glint_at.x, glint_at.y, kTop - 0.05}}};
    ig.update(s);
    const osg::Image& image = ig.render();
    drawn[name] = measure([&](int x, int y) { return luminance(pixel(image, x, y)); });
    ggx[name] = measure([&](int x, int y) {
      const core::Vec3 r = ray(x, y);
      return r.z < 0.0 ? ggx_glint({0.0, 0.0, 1.0}, r * -1.0, to_sun, f0, roughness) : 0.0;
    });
    std::printf(
        "%s: drawn +%.3f centred at (%.1f, %.1f), %d px across, %d along; GGX centred at (%.1f, %.1f), "
        "%d across, %d along\n",
        name, drawn[name].peak, drawn[name].cx, drawn[name].cy, drawn[name].across, drawn[name].along,
        ggx[name].cx, ggx[name].cy, ggx[name].across, ggx[name].along);
    EXPECT_NEAR(drawn[name].cx, ggx[name].cx, 2.0) << name;
    EXPECT_NEAR(drawn[name].cy, ggx[name].cy, 2.0) << name;
    EXPECT_NEAR(drawn[name].across, ggx[name].across, 0.15 * ggx[name].across) << name;
    EXPECT_NEAR(drawn[name].along, ggx[name].along, 0.15 * ggx[name].along) << name;
  }
  const double drawn_ratio = drawn["steel"].peak / drawn["paint"].peak,
               ggx_ratio = ggx["steel"].peak / ggx["paint"].peak;
  std::printf("steel's glint %.2f times paint's (GGX %.2f)\n", drawn_ratio, ggx_ratio);
  EXPECT_NEAR(drawn_ratio, ggx_ratio, 0.2 * ggx_ratio);
  EXPECT_LT(drawn["steel"].across, 0.7 * drawn["paint"].across);
}

// Surface detail is laid on the object's own faces: a painted wall filling the picture is textured with it
// (its luminance varies by over 2 % of its mean, four times the plain wall's variation from its sky
// reflection and glint) and the texture rides the wall —
// moved 1.3 m along and 0.7 m up (not whole 4 m tiles), with the camera moved alike, the picture is the same.
TEST(ImageGenerator, SurfaceDetailRidesTheMachine) {
  scene::SceneDescription d;
  d.machine = "test";
  d.entities.push_back({"wall", "test.wall", {2.0, 20.0, 20.0}});
  Visual wall;
  VisualPart part;
  part.color = {0.6, 0.3, 0.2};
  wall.parts.push_back(part);
  ImageGenerator ig(d, {{"test.wall", wall}}, kWidth, kHeight);
  const auto picture = [&](const core::Vec3& offset, bool detail) {
    ig.set_surface_detail(detail);
    View v;
    v.kind = View::Kind::kFree;
    v.position_m = core::Vec3{-12.0, 0.0, 30.0} + offset;
    v.yaw_rad = 0.0;
    v.pitch_rad = 0.0;
    v.fov_vertical_rad = 0.8;
    v.hud = false;
    ig.set_view(v);
    scene::Snapshot s;
    s.time_of_day_h = 12.0;
    s.visibility_m = 1e6;
    s.entity_count = 1;
    s.entities[0] = {0, 0, {core::Mat3::identity(), core::Vec3{0.0, 0.0, 30.0} + offset}};
    ig.update(s);
    return luminances(ig.render());
  };
  const auto spread = [](const std::vector<double>& l) {
    double mean = 0.0, square = 0.0;
    for (const double v : l)
      mean += v / static_cast<double>(l.size());
    for (const double v : l)
      square += (v - mean) * (v - mean) / static_cast<double>(l.size());
    return std::sqrt(square) / mean;
  };
  const std::vector<double> plain = picture({}, false), detailed = picture({}, true),
                            moved = picture({0.0, 1.3, 0.7}, true);
  double largest = 0.0;
  for (std::size_t k = 0; k < detailed.size(); ++k)
    largest = std::max(largest, std::abs(moved[k] - detailed[k]));
  std::printf(
      "the wall's luminance varies by %.4f (plain) and %.4f (detailed) of its mean; moved, the detailed "
      "picture differs by at most %.4f\n",
      spread(plain), spread(detailed), largest);
  EXPECT_GT(spread(detailed), 0.02);
  EXPECT_GT(spread(detailed), 4.0 * spread(plain));
  EXPECT_LT(largest, 3.0 / 255.0);
}

// Spray flies off the crests in a gale only: 2.5 m over the water and looking level out to sea, the sky over
// the horizon is as it is in a calm at 14 m/s of wind (below the 15 m/s where spray begins) and whitened by
// puffs rising over the eye's height at 22 m/s and more at 28 m/s (over six moments: +0.028 and +0.038 a
// pixel).
TEST(ImageGenerator, SprayFliesOffTheCrestsAboveFifteenMetresASecond) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  View v;
  v.kind = View::Kind::kFree;
  v.position_m = {40.0, 0.0, -1.0};  // 2.5 m over the still water
  v.yaw_rad = 0.0;
  v.pitch_rad = 0.0;
  v.fov_vertical_rad = 0.5;
  v.hud = false;
  ig.set_view(v);
  const auto sky_above_horizon = [&](double wind, double time_s) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
    s.time_s = time_s;
    s.wind_mps = {wind, 0.0, 0.0};  // blowing out to sea
    ig.update(s);
    const osg::Image& image = ig.render();
    std::vector<double> l;
    for (int y = 0; y < kHeight / 2 - 2; ++y)  // the rows over the horizon (the picture's middle)
      for (int x = 0; x < kWidth; ++x)
        l.push_back(luminance(pixel(image, x, y)));
    return l;
  };
  std::map<int, int> whitened;
  std::map<int, double> added;  // the luminance the spray adds over the horizon, a pixel on average
  for (const int wind : {14, 22, 28})
    for (const double time_s : {100.0, 101.3, 102.6, 103.9, 105.2, 106.5}) {  // six moments, 1.3 s apart
      const std::vector<double> calm = sky_above_horizon(0.0, time_s), sky = sky_above_horizon(wind, time_s);
      for (std::size_t k = 0; k < sky.size(); ++k) {
        whitened[wind] += sky[k] > calm[k] + 0.02 ? 1 : 0;
        added[wind] += std::max(sky[k] - calm[k], 0.0) / static_cast<double>(6 * sky.size());
      }
    }
  for (const int wind : {14, 22, 28})
    std::printf("%d m/s: %d pixels over the horizon whitened in six pictures, +%.4f a pixel\n", wind,
                whitened[wind], added[wind]);
  EXPECT_EQ(whitened[14], 0);
  EXPECT_GT(whitened[22], 100);
  EXPECT_GT(added[28], 1.25 * added[22]);  // overlapping puffs: less than their number's 1.9 times
}

TEST(ImageGenerator, RainStreaksPastTheEyeFallTheWayTheDropsFall) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(down());
  ig.update(over_the_quay(12.0, 0.0));
  ig.render();
  EXPECT_TRUE(ig.rain_streaks().empty());  // dry
  // 40 mm/h, looking straight down: the drops fall away from the eye towards the picture's centre
  ig.update(over_the_quay(12.0, 40.0));
  ig.render();
  const auto down_streaks = ig.rain_streaks();
  const double expected = 400.0 * 0.8 * kWidth * kHeight / (1280.0 * 720.0);
  EXPECT_NEAR(static_cast<double>(down_streaks.size()), expected, 1.0);
  int towards_centre = 0;
  for (const auto& [from, to] : down_streaks) {
    osg::Vec3 way = to - from, centre = osg::Vec3(kWidth / 2.0f, kHeight / 2.0f, 0.0f) - from;
    way.normalize();
    centre.normalize();
    towards_centre += way * centre > 0.99f ? 1 : 0;
  }
  EXPECT_GE(towards_centre, static_cast<int>(0.95 * static_cast<double>(down_streaks.size())));
  // looking ahead in still air they fall straight down the picture; in 10 m/s of wind from the left (blowing
  // to the right of the view) they slant to the right
  ig.set_view(level());
  scene::Snapshot s = over_the_quay(12.0, 40.0);
  ig.update(s);
  ig.render();
  for (const auto& [from, to] : ig.rain_streaks()) {
    osg::Vec3 way = to - from;
    way.normalize();
    EXPECT_LT(way.y(), -0.9f);
  }
  s.wind_mps = {0.0, -10.0, 0.0};  // the cab looks along +x with y to its left: this blows to its right
  ig.update(s);
  ig.render();
  double across = 0.0;
  for (const auto& [from, to] : ig.rain_streaks())
    across += (to - from).x() / (to - from).length();
  EXPECT_GT(across / static_cast<double>(ig.rain_streaks().size()), 0.3);
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

TEST(ImageGenerator, ACameraRidingAnEntityMovesWithIt) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  Looks extra;
  extra.cameras.push_back({"mast", "none", {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 0.6});
  ig.use(extra);
  EXPECT_EQ(ig.view_names(), (std::vector<std::string>{"cab", "chase", "free", "mast"}));
  ig.set_view(view_named("mast"));
  scene::Snapshot s = state(40.0, 5000.0, 20000.0, 12.0);
  s.entities[0].pose.position = {0.0, 0.0, 14.0};
  ig.update(s);
  ig.render();
  const auto centred = ig.project({40.0, 0.0, 14.0});
  EXPECT_NEAR(centred->first, kWidth / 2.0, 0.5);
  EXPECT_NEAR(centred->second, kHeight / 2.0, 0.5);
  s.entities[0].pose.position = {0.0, -6.0, 14.0};  // the mast moves 6 m to the right of the box
  ig.update(s);
  ig.render();
  EXPECT_LT(ig.project({40.0, 0.0, 14.0})->first, kWidth / 2.0 - 20.0);  // the box is now left of centre
  ig.set_view(view_named("hook"));
  EXPECT_THROW(ig.render(), std::invalid_argument);
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// Head tracking on a desktop monitor: the screen is a window; what lies in its plane stays put as the head
// moves, what lies far beyond it moves with the head (motion parallax), as through a real window.
TEST(ImageGenerator, OffAxisProjectionMakesTheScreenAWindow) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  View v = level();
  v.off_axis = true;
  v.screen_distance_m = 0.6;
  ig.set_view(v);
  scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
  const core::Vec3 on_screen{0.6, 0.05, 10.1}, far{100.0, 0.0, 10.0};
  ig.update(s);
  ig.render();
  const auto screen_before = *ig.project(on_screen), far_before = *ig.project(far);
  s.cab.head_offset_m = {0.0, -0.10, 0.05};  // 10 cm to the right, 5 cm up
  ig.update(s);
  ig.render();
  const auto screen_after = *ig.project(on_screen), far_after = *ig.project(far);
  EXPECT_NEAR(screen_after.first, screen_before.first, 0.01);
  EXPECT_NEAR(screen_after.second, screen_before.second, 0.01);
  // the far point keeps its direction from the moved eye: through the window it shows right and up by nearly
  // the head's offset (0.0994 m and 0.0497 m on a window 0.6 tan(0.3) m in half height)
  const double pixels_per_m = (kHeight / 2.0) / (0.6 * std::tan(0.3));
  EXPECT_NEAR(far_after.first - far_before.first, 0.0994 * pixels_per_m, 1.0);
  EXPECT_NEAR(far_after.second - far_before.second, -0.0497 * pixels_per_m, 1.0);  // rows count downwards
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

TEST(ImageGenerator, AnAsymmetricFrustumPutsTheViewAxisOffCentre) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  View v = level();
  const double deg = std::numbers::pi / 180.0;
  v.frustum_rad = std::array{-30.0 * deg, 10.0 * deg, -20.0 * deg, 5.0 * deg};
  ig.set_view(v);
  ig.update(state(5000.0, 5000.0, 20000.0, 12.0));
  ig.render();
  const auto axis = *ig.project({1000.0, 0.0, 10.0});  // straight ahead of the eye
  const double t = std::tan(30.0 * deg) / (std::tan(30.0 * deg) + std::tan(10.0 * deg));
  const double u = std::tan(5.0 * deg) / (std::tan(20.0 * deg) + std::tan(5.0 * deg));
  EXPECT_NEAR(axis.first, t * kWidth, 0.5);
  EXPECT_NEAR(axis.second, u * kHeight, 0.5);
}

// Stereo (parallel axes, asymmetric frusta): each eye sees a point at distance d where the other does plus
// a disparity of s (1/d - 1/c) / tan(half the horizontal field) half-widths: crossed in front of the
// convergence distance c, none at it, uncrossed behind it. Measured on the drawn box, not only on the
// matrices.
TEST(ImageGenerator, StereoEyesSeeParallaxThatVanishesAtTheConvergenceDistance) {
  const auto red_x = [](const osg::Image& image) {
    double sx = 0, n = 0;
    for (int y = 0; y < image.t(); ++y)
      for (int x = 0; x < image.s(); ++x) {
        const osg::Vec3 p = pixel(image, x, y);
        if (p.x() > 0.3 && p.x() > 2.5 * p.y() && p.x() > 2.5 * p.z()) {
          sx += x;
          ++n;
        }
      }
    return sx / std::max(n, 1.0);
  };
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  constexpr double separation = 0.065, convergence = 12.0;
  const double tan_half = std::tan(level().fov_vertical_rad / 2.0) * kWidth / kHeight;
  for (const double distance : {6.0, 12.0, 40.0}) {
    scene::Snapshot s = state(distance, 5000.0, 20000.0, 12.0);
    s.entities[1].pose.position.z = 10.0;  // at the eye's height, straight ahead
    ig.update(s);
    double seen[2];
    for (const int eye : {0, 1}) {
      View v = level();
      v.eye_offset_m = (eye == 0 ? -0.5 : 0.5) * separation;
      v.convergence_m = convergence;
      ig.set_view(v);
      seen[eye] = red_x(ig.render());
    }
    const double expected = separation * (1.0 / distance - 1.0 / convergence) / tan_half * kWidth / 2.0;
    EXPECT_NEAR(seen[0] - seen[1], expected, 0.6) << "at " << distance << " m";
  }
}

// The debrief's timeline bar: filled up to the published time, a tick in its colour at each event.
TEST(ImageGenerator, TheTimelineBarFillsUpToNowAndMarksTheEvents) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(level());
  ig.set_timeline(0.0, 100.0, {{50.0, {1.0, 0.0, 0.0}}});
  scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 0.5);  // a dark night sky behind the bar
  s.time_s = 25.0;
  ig.update(s);
  const osg::Image& image = ig.render();
  const double margin = kWidth * 0.03, length = kWidth - 2.0 * margin;
  const double y = kHeight - kHeight * 0.03 - 3.0;  // within the bar, from the top
  const auto at = [&](double t) { return pixel(image, margin + length * t / 100.0, y); };
  EXPECT_GT(luminance(at(10.0)), 0.5);  // the past: filled
  EXPECT_LT(luminance(at(75.0)), 0.1);  // the future: the dark track
  const osg::Vec3 mark = at(50.0);
  EXPECT_GT(mark.x(), 0.8);
  EXPECT_LT(mark.y(), 0.2);
  // no span: no bar
  ig.set_timeline(0.0, 0.0, {});
  ig.update(s);
  EXPECT_LT(luminance(pixel(ig.render(), margin + length * 0.1, y)), 0.1);
}

// The cab view's roll turns the picture about the view axis: rolled right, a point right of the axis rises.
// Multisampling: a red panel against the sky, its edges slanted by the view's roll. Drawn with one sample a
// pixel, each pixel is the panel's or the sky's; with four, a pixel the edge crosses takes the share of the
// panel it covers. The panel's area (its redness summed over the picture) is the same either way.
TEST(ImageGenerator, MultisamplingBlendsThePixelsAnEdgeCrosses) {
  struct Drawn {
    int samples = 0, blended = 0;
    double area_px = 0.0;
  };
  auto draw = [](int samples) {
    ImageGenerator ig(scene(), looks(), kWidth, kHeight, samples);
    ig.update(state(30.0, 5000.0, 20000.0, 12.0));
    View v = level();
    v.roll_rad = 0.3;
    ig.set_view(v);
    const osg::Image& image = ig.render();
    const auto centre = *ig.project({30.0, 0.0, 14.0});
    auto redness = [&](double x, double y) {
      const osg::Vec3 c = pixel(image, x, y);
      return c.x() - 0.5 * (c.y() + c.z());
    };
    const double panel = redness(centre.first, centre.second),
                 sky = redness(centre.first - 30.0, centre.second);
    EXPECT_GT(panel - sky, 0.3);
    Drawn d{ig.multisamples()};
    // the panel (some 32 px square, turned 0.3 rad) and the sky round it, against the sky of the row (the
    // sky's colour changes with height)
    for (int y = static_cast<int>(centre.second) - 30; y <= static_cast<int>(centre.second) + 30; ++y)
      for (int x = static_cast<int>(centre.first) - 30; x <= static_cast<int>(centre.first) + 30; ++x) {
        const double row_sky = redness(centre.first - 40.0, y);
        const double share = (redness(x, y) - row_sky) / (panel - row_sky);
        d.area_px += std::clamp(share, 0.0, 1.0);
        d.blended += share > 0.15 && share < 0.85 ? 1 : 0;
      }
    return d;
  };
  const Drawn aliased = draw(0), smooth = draw(4);
  std::printf("one sample: %d blended pixels, area %.1f px; %d samples: %d blended, area %.1f px\n",
              aliased.blended, aliased.area_px, smooth.samples, smooth.blended, smooth.area_px);
  EXPECT_EQ(aliased.samples, 0);
  EXPECT_EQ(smooth.samples, 4);
  EXPECT_GT(smooth.blended, 60);  // most of the ~130 pixels round the panel's edge
  EXPECT_LT(aliased.blended, smooth.blended / 10);
  EXPECT_NEAR(smooth.area_px, aliased.area_px, 0.03 * aliased.area_px);
}

TEST(ImageGenerator, TheViewsRollTurnsThePictureAboutItsAxis) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.update(state(5000.0, 5000.0, 20000.0, 12.0));
  View v = level();
  const double roll = 0.3;
  v.roll_rad = roll;
  ig.set_view(v);
  ig.render();
  // 100 m ahead, 20 m to the right (-y) of the eye at (0, 0, 10)
  const auto at = *ig.project({100.0, -20.0, 10.0});
  const double focal = kHeight / 2.0 / std::tan(v.fov_vertical_rad / 2.0);  // pixels
  EXPECT_NEAR(at.first, kWidth / 2.0 + focal * 0.2 * std::cos(roll), 0.5);
  EXPECT_NEAR(at.second, kHeight / 2.0 - focal * 0.2 * std::sin(roll), 0.5);
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

TEST(ImageGenerator, AContainersIsoCodeIsPaintedOnItsSidesItsEndsAndItsRoof) {
  scene::SceneDescription d;
  d.entities.push_back({"mast", "none", {}});
  d.entities.push_back({"TGHU1234567", "test.container", {6.1, 1.22, 1.3}});
  // bright pixels within the rows `top`-`bottom` of the picture of the (dark blue) box posed at `pose`, seen
  // from the cab at 10 m looking along +x, turned down by `pitch`
  const auto white_pixels = [&](bool labelled, const core::Pose& pose, double pitch, const core::Vec3& top,
                                const core::Vec3& bottom, double half_width) {
    Visual look;
    VisualPart part;
    part.color = {0.1, 0.25, 0.6};
    look.parts.push_back(part);
    look.name_marked = labelled;
    ImageGenerator ig(d, {{"test.container", look}}, kWidth, kHeight);
    View v = level();
    v.hud = false;
    v.pitch_rad = pitch;
    ig.set_view(v);
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
    s.entity_count = 2;
    s.entities[1] = {1, 0, pose};
    ig.update(s);
    const osg::Image& image = ig.render();
    int white = 0;
    const auto from = ig.project(top), to = ig.project(bottom);
    // the box's columns (the pale sky beside it is not its paint)
    const auto left = ig.project(top + core::Vec3{0.0, half_width, 0.0}),
               right = ig.project(top - core::Vec3{0.0, half_width, 0.0});
    const int first = std::max(0, static_cast<int>(std::min(left->first, right->first)));
    const int last = std::min(kWidth - 1, static_cast<int>(std::max(left->first, right->first)));
    for (int y = static_cast<int>(std::min(from->second, to->second));
         y <= static_cast<int>(std::max(from->second, to->second)); ++y)
      for (int x = first; x <= last; ++x)
        white += luminance(pixel(image, x, y)) > 0.6;
    return white;
  };
  const core::Mat3 across = core::Mat3::rotation({0.0, 0.0, 1.0}, std::numbers::pi / 2.0);
  struct Seen {
    const char* what;
    core::Pose pose;
    double pitch_rad;
    core::Vec3 top, bottom;
    double half_width_m;  // the box's across the picture
    int at_least;
  };
  const Seen views[] = {
      // 7 m ahead, its long side towards the eye: "TGHU1234567" in 0.32 m letters
      {"side", {across, {7.0, 0.0, 10.0}}, 0.0, {7.0, 0.0, 11.2}, {7.0, 0.0, 8.8}, 6.1, 80},
      // its end towards the eye, 7 m ahead of it: 0.2 m letters across its 2.44 m
      {"end", {core::Mat3::identity(), {13.1, 0.0, 10.0}}, 0.0, {7.0, 0.0, 11.2}, {7.0, 0.0, 8.8}, 1.22, 30},
      // 9 m below the eye, looked straight down on: its roof, 0.45 m letters
      {"roof",
       {core::Mat3::identity(), {0.0, 0.0, -0.3}},
       -std::numbers::pi / 2.0,
       {6.0, 0.0, 1.0},
       {-6.0, 0.0, 1.0},
       1.22,
       150},
  };
  for (const Seen& seen : views) {
    const int plain =
        white_pixels(false, seen.pose, seen.pitch_rad, seen.top, seen.bottom, seen.half_width_m);
    const int labelled =
        white_pixels(true, seen.pose, seen.pitch_rad, seen.top, seen.bottom, seen.half_width_m);
    std::printf("white pixels on the box's %s: %d plain, %d with its code\n", seen.what, plain, labelled);
    EXPECT_EQ(plain, 0) << seen.what;
    EXPECT_GT(labelled, seen.at_least) << seen.what;
  }
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

View free_camera(const core::Vec3& at, double yaw, double pitch) {
  View v = view_named("free");
  v.position_m = at;
  v.yaw_rad = yaw;
  v.pitch_rad = pitch;
  v.hud = false;
  return v;
}

// the open sea drawn in a wind along +x at `time_of_day_h`, `t` seconds into it (the boxes behind the camera)
const osg::Image& sea_in_wind(ImageGenerator& ig, double wind, double time_of_day_h, double t) {
  scene::Snapshot s = state(-500.0, -600.0, 20000.0, time_of_day_h);
  s.wind_mps = {wind, 0.0, 0.0};
  s.time_s = t;
  ig.update(s);
  return ig.render();
}

// The wind sea (Tessendorf's FFT waves) breaks the water's reflection of the sky into a pattern: the
// water's luminance varies across the picture in a fresh breeze far more than in a calm.
TEST(ImageGenerator, WindRoughensTheWater) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(free_camera({200.0, 0.0, 6.0}, 0.0, -0.35));  // over open water, looking down the wind
  const auto spread = [&](double wind) {
    const osg::Image& image = sea_in_wind(ig, wind, 11.0, 30.0);
    double sum = 0.0,
           n = 0.0;  // mean change of luminance from pixel to pixel (the gradient of distance aside)
    for (int y = kHeight * 3 / 10; y < kHeight * 6 / 10; ++y)  // water only, where it mirrors the sky most
      for (int x = 0; x < kWidth; ++x) {
        sum += std::abs(luminance(pixel(image, x, y)) - luminance(pixel(image, x, y - 1)));
        ++n;
      }
    if (wind > 0.0) ig.write_png(::testing::TempDir() + "/wind_sea.png");
    return sum / n;
  };
  const double calm = spread(0.0), breeze = spread(12.0);
  std::printf("water luminance change pixel to pixel: calm %.4f, 12 m/s %.4f\n", calm, breeze);
  EXPECT_GT(breeze, 3.0 * calm);
}

// The swell through the vessel's reference point rises and falls with the vessel's heave: a post standing
// there, seen from beside it along the crests, shows the waterline where projection puts the heaved level.
TEST(ImageGenerator, TheWaterlineFollowsTheVesselsHeave) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  const core::Vec3 post{60.0, 0.0, -3.5};
  ig.set_view(free_camera({post.x, post.y - 14.0, post.z + 1.2}, std::numbers::pi / 2.0, -0.08));
  std::vector<double> rows, projected;
  for (const double phase : {std::numbers::pi / 2.0, -std::numbers::pi / 2.0, 0.0}) {
    scene::Snapshot s = state(-500.0, -600.0, 20000.0, 12.0);
    s.sea.water_level_m = post.z;
    s.sea.reference_m = post;
    s.sea.swell_count = 1;
    s.sea.swells[0] = {0.6, 9.0, phase,
                       std::numbers::pi};  // running along -x: the camera looks along a crest
    s.entities[1] = {1, 0, {core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 2.0), post}};  // the red panel
    ig.update(s);
    const osg::Image& image = ig.render();
    const auto at = ig.project(post);
    ASSERT_TRUE(at);
    int lowest_red = -1;
    for (int y = 0; y < kHeight; ++y) {
      const osg::Vec3 p = pixel(image, at->first, y);
      if (p.x() > 0.3 && p.x() > 2.5 * p.y() && p.x() > 2.5 * p.z()) lowest_red = y;
    }
    const double heave = 0.6 * std::sin(phase);
    const auto waterline = ig.project({post.x, post.y - 0.1, post.z + heave});  // the panel's near face
    std::printf("heave %+.2f m: waterline at row %d, projected %.1f\n", heave, lowest_red, waterline->second);
    EXPECT_NEAR(lowest_red, waterline->second, 3.0);
    rows.push_back(lowest_red);
    projected.push_back(waterline->second);
  }
  // crest to trough: the waterline moves as far as projection says (within a tenth)
  EXPECT_NEAR(rows[1] - rows[0], projected[1] - projected[0], 0.1 * (projected[1] - projected[0]));
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// The sun casts shadows (osgShadow's view-dependent shadow map): a box held 6 m over the quay darkens the
// quay where the sun's ray through it lands (computed from the sun's position for the time of day), not the
// spot as far the other way; the shadow moves with the sun.
// A software renderer draws the sun's shadows hard unless told (the filter's taps cost it ~40 % of a frame).
TEST(ImageGenerator, SoftShadowsAreOnUnlessTheRendererIsSoftware) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  EXPECT_EQ(ig.soft_shadows(), !software_renderer(ig.renderer())) << ig.renderer();
  EXPECT_TRUE(software_renderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
  EXPECT_TRUE(software_renderer("softpipe"));
  EXPECT_FALSE(software_renderer("NVIDIA H100 80GB HBM3/PCIe/SSE2"));
  ig.set_soft_shadows(true);
  EXPECT_TRUE(ig.soft_shadows());
}

TEST(ImageGenerator, TheSunCastsAShadowWhereItsRaysSay) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  View v = free_camera({-20.0, 0.0, 60.0}, 0.0, -std::numbers::pi / 2.0 + 1e-3);
  v.fov_vertical_rad = 0.9;
  ig.set_view(v);
  for (const double hour : {10.0, 14.0}) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, hour);
    const core::Vec3 box{-20.0, 0.0, 6.0};
    s.entities[1] = {1, 0, {core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 2.0), box}};
    ig.update(s);
    const osg::Image& image = ig.render();
    // the sun's direction as the image generator computes it (equinox, 40 deg N): its hour angle and
    // the horizontal and vertical parts
    const double h = (hour - 12.0) / 24.0 * 2.0 * std::numbers::pi, lat = 40.0 * std::numbers::pi / 180.0;
    const double declination =
        23.45 * std::numbers::pi / 180.0 * std::sin(2.0 * std::numbers::pi * 364.0 / 365.0);
    const core::Vec3 to_sun{
        -std::cos(declination) * std::sin(h),
        std::cos(lat) * std::sin(declination) - std::sin(lat) * std::cos(declination) * std::cos(h),
        std::sin(lat) * std::sin(declination) + std::cos(lat) * std::cos(declination) * std::cos(h)};
    const core::Vec3 shadow = box - to_sun * (box.z / to_sun.z), mirror = box + (box - shadow);
    const auto around = [&](const core::Vec3& p) {
      const auto at = ig.project({p.x, p.y, 0.0});
      double sum = 0.0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          sum += luminance(pixel(image, at->first + dx, at->second + dy));
      return sum / 25.0;
    };
    const double in_shadow = around(shadow), across = around({mirror.x, mirror.y, 0.0});
    std::printf("%.0f h: quay %.3f where the shadow should fall, %.3f as far the other way\n", hour,
                in_shadow, across);
    EXPECT_LT(in_shadow, 0.7 * across);
  }
}

// Fair-weather cloud covers the share of the sky its oktas say: looking up at 16 headings and elevations
// through four moments of the deck's drift, the pixels whose blue lead over red is under half the clear
// sky's there (a cloud drawn at least half opaque) are N/8 of them within 0.08 at 2, 4 and 6 oktas; none
// clear. An overcast sky without rain (8 oktas) hides the sun: the box's shadow on the quay fades (its spot
// 0.9 or more of the quay beside it, against under 0.7 clear) and the sky greys.
TEST(ImageGenerator, CloudsCoverTheSkyAsTheirOktasSayAndAnOvercastHidesTheSun) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  const auto sky_seen = [&](double oktas, double yaw, double pitch, double t) -> const osg::Image& {
    View v = free_camera({0.0, 0.0, 10.0}, yaw, pitch);
    v.fov_vertical_rad = 0.6;
    ig.set_view(v);
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 11.0);
    s.cloud_oktas = oktas;
    s.wind_mps = {10.0, 4.0, 0.0};
    s.time_s = t;
    ig.update(s);
    return ig.render();
  };
  std::vector<std::vector<double>> clear_lead;  // blue less red of the clear sky, per view and pixel
  const auto views = [](const auto& each) {
    for (const double yaw : {0.0, 0.8, 1.6, 2.4, 3.2, 4.0, 4.8, 5.6})
      for (const double pitch : {0.75, 1.25})
        each(yaw, pitch);
  };
  views([&](double yaw, double pitch) {
    const osg::Image& image = sky_seen(0.0, yaw, pitch, 0.0);
    std::vector<double> lead;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        lead.push_back(pixel(image, x, y).z() - pixel(image, x, y).x());
    clear_lead.push_back(std::move(lead));
  });
  for (const double oktas : {2.0, 4.0, 6.0}) {
    double cloud = 0.0, pixels = 0.0;
    for (const double t : {0.0, 150.0, 300.0, 450.0}) {  // the deck drifts 3.2 km in 150 s
      std::size_t view = 0;
      views([&](double yaw, double pitch) {
        const osg::Image& image = sky_seen(oktas, yaw, pitch, t);
        const std::vector<double>& lead = clear_lead[view++];
        for (int y = 0; y < kHeight; ++y)
          for (int x = 0; x < kWidth; ++x) {
            const double here = pixel(image, x, y).z() - pixel(image, x, y).x();
            cloud += here < 0.5 * lead[static_cast<std::size_t>(y * kWidth + x)] ? 1.0 : 0.0;
            ++pixels;
          }
      });
    }
    std::printf("%.0f oktas: cloud over %.3f of the sky seen (%.3f)\n", oktas, cloud / pixels, oktas / 8.0);
    EXPECT_NEAR(cloud / pixels, oktas / 8.0, 0.08) << oktas;
  }
  // an overcast without rain: the shadow fades, the sky greys
  View down = free_camera({-20.0, 0.0, 60.0}, 0.0, -std::numbers::pi / 2.0 + 1e-3);
  down.fov_vertical_rad = 0.9;
  const auto shadow_share = [&](double oktas) {
    ig.set_view(down);
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 10.0);
    s.cloud_oktas = oktas;
    const core::Vec3 box{-20.0, 0.0, 6.0};
    s.entities[1] = {1, 0, {core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 2.0), box}};
    ig.update(s);
    const osg::Image& image = ig.render();
    // the shadow's spot: where the quay is darkest under the box's side of the picture, against its mean
    double darkest = 1.0, sum = 0.0;
    for (int y = 10; y < kHeight - 10; ++y)
      for (int x = 10; x < kWidth - 10; ++x) {
        darkest = std::min(darkest, luminance(pixel(image, x, y)));
        sum += luminance(pixel(image, x, y));
      }
    return std::pair{darkest, sum / ((kHeight - 20) * (kWidth - 20))};
  };
  const auto [clear_darkest, clear_mean] = shadow_share(0.0);
  const auto [overcast_darkest, overcast_mean] = shadow_share(8.0);
  std::printf("quay from above: darkest %.3f of mean %.3f clear, %.3f of %.3f overcast\n", clear_darkest,
              clear_mean, overcast_darkest, overcast_mean);
  EXPECT_LT(clear_darkest, 0.7 * clear_mean);
  EXPECT_GT(overcast_darkest, 0.85 * overcast_mean);
  const osg::Image& overcast_sky = sky_seen(8.0, 0.0, 1.25, 0.0);
  const osg::Vec3 up = pixel(overcast_sky, kWidth / 2, kHeight / 2);
  EXPECT_LT(up.z() - up.x(), 0.08) << "an overcast sky is grey";
}

// Clouds shade the harbour where they hide the sun: looking down on the quay through 60 moments of the deck's
// drift (20 m/s, 1.5 km between moments: each a fresh part of the deck), the share of the quay's pixels
// darker than 0.8 of the clear day's is the cloud's cover within 0.12 at 2 and 6 oktas, and none clear.
TEST(ImageGenerator, CloudsShadeTheQuayAsMuchAsTheyCoverTheSky) {
  constexpr int kSide = 48;
  ImageGenerator ig(scene(), looks(), kSide, kSide);
  View down = free_camera({-40.0, 0.0, 60.0}, 0.0, -std::numbers::pi / 2.0 + 1e-3);
  down.fov_vertical_rad = 0.6;
  ig.set_view(down);
  const auto quay = [&](double oktas, double t) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 11.0);
    s.cloud_oktas = oktas;
    s.wind_mps = {10.0, 0.0, 0.0};
    s.time_s = t;
    ig.update(s);
    return luminances(ig.render());
  };
  const std::vector<double> clear = quay(0.0, 0.0);
  for (const double oktas : {0.0, 2.0, 6.0}) {
    double shaded = 0.0, pixels = 0.0;
    for (int k = 0; k < 60; ++k) {
      const std::vector<double> l = quay(oktas, 75.0 * k);
      for (std::size_t p = 0; p < l.size(); ++p) {
        shaded += l[p] < 0.8 * clear[p] ? 1.0 : 0.0;
        ++pixels;
      }
    }
    std::printf("%.0f oktas: the quay in the clouds' shade %.3f of the time\n", oktas, shaded / pixels);
    EXPECT_NEAR(shaded / pixels, oktas / 8.0, 0.12) << oktas;
  }
}

}  // namespace
}  // namespace harbour::ig

#include "harbour/bulk/BulkPublish.h"
#include "harbour/ig/RenderThread.h"

#include <atomic>
#include <chrono>
#include <thread>

namespace harbour::ig {
namespace {

bulk::BulkWorld sand_yard() {
  bulk::Material sand;
  sand.name = "sand";
  sand.bulk_density_kg_m3 = 1600.0;
  sand.angle_of_repose_rad = 34.0 * std::numbers::pi / 180.0;
  sand.flow_friction_rad = 0.85 * sand.angle_of_repose_rad;
  bulk::BulkWorld world(sand, bulk::BulkWorldSettings{});
  world.add_grid({256, 256, 0.1}, {core::Mat3::identity(), {-12.8, -12.8, 0.0}});  // 8 x 8 tiles, on the quay
  return world;
}

// Bulk material is drawn from its published view, tile by tile: the first view meshes every tile, a change in
// one place re-meshes only the tiles whose version moved on, and the heap shows where it lies.
TEST(ImageGenerator, ABulkUpdateReMeshesOnlyTheTilesThatChanged) {
  bulk::BulkWorld world = sand_yard();
  world.add_heap(0, 12.8, 12.8, 20.0);  // a cone in the middle of the grid
  scene::BulkView view;
  EXPECT_EQ(bulk::publish(world, view), 64);
  std::map<std::string, Visual> visuals = looks();
  Visual bulk_look;
  bulk_look.parts.push_back({});
  bulk_look.parts[0].color = {0.9, 0.8, 0.1};
  visuals["bulk"] = bulk_look;
  ImageGenerator ig(scene(), visuals, kWidth, kHeight);
  ig.set_view(free_camera({0.0, -25.0, 20.0}, std::numbers::pi / 2.0, -0.6));
  ig.update(state(5000.0, 5000.0, 20000.0, 12.0));
  ig.update_bulk(view);
  EXPECT_EQ(ig.bulk_tiles_meshed(), 64);
  const osg::Image& image = ig.render();
  const auto top = ig.project({0.0, 0.0, 1.0});
  const osg::Vec3 heap = pixel(image, top->first, top->second);
  std::printf("heap pixel %.2f %.2f %.2f\n", heap.x(), heap.y(), heap.z());
  EXPECT_GT(heap.x(), 1.5 * heap.z());  // the sand's yellow, not the grey quay

  // nothing changed: nothing re-meshed
  EXPECT_EQ(bulk::publish(world, view), 0);
  ig.update_bulk(view);
  EXPECT_EQ(ig.bulk_tiles_meshed(), 64);
  // a little poured into one cell deep inside tile (1, 1): that tile only
  world.grid(0).add_volume(40, 40, 0.0001);  // 1 cm: below the critical drop, it stays
  EXPECT_EQ(bulk::publish(world, view), 1);
  ig.update_bulk(view);
  EXPECT_EQ(ig.bulk_tiles_meshed(), 65);
  // material flowing over a tile border changes both
  world.grid(0).add_volume(63, 10, 0.002);  // 0.2 m on one cell: it slides into the next tile
  world.step(0.001, {});
  const int copied = bulk::publish(world, view);
  ig.update_bulk(view);
  std::printf("a pour at a tile border: %d tiles changed\n", copied);
  EXPECT_EQ(copied, 2);
  EXPECT_EQ(ig.bulk_tiles_meshed(), 65 + copied);
}

// The station's render thread draws the bulk material its source hands it (the real-time loop's view), with
// every frame's snapshot: the trainee sees the pile the grab digs.
TEST(RenderThread, DrawsTheBulkMaterialItIsHanded) {
  bulk::BulkWorld world = sand_yard();
  world.add_heap(0, 12.8, 12.8, 20.0);
  scene::BulkView view;
  bulk::publish(world, view);
  Looks looks;
  looks.visuals = ig::looks();
  looks.visuals["bulk"].parts.push_back({});
  looks.visuals["bulk"].parts[0].color = {0.9, 0.8, 0.1};
  const auto snapshot = std::make_unique<scene::Snapshot>(state(5000.0, 5000.0, 20000.0, 12.0));
  std::atomic<long> meshed{0};
  std::atomic<int> frames{0};
  RenderThread render(
      scene(), looks, 320, 180, {free_camera({0.0, -25.0, 20.0}, std::numbers::pi / 2.0, -0.6)},
      [&]() -> const scene::Snapshot* { return snapshot.get(); },
      [&](ImageGenerator& generator, const scene::Snapshot&, int) {
        meshed = generator.bulk_tiles_meshed();
        ++frames;
      },
      0.0, [&]() -> const scene::BulkView* { return &view; });
  for (int wait = 0; wait < 200 && frames.load() == 0; ++wait)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  render.stop();
  EXPECT_EQ(render.error(), "");
  ASSERT_GT(frames.load(), 0);
  EXPECT_EQ(meshed.load(), 64);  // every tile of the grid, once
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// The night sky: stars come out when the sun is well down, and the moon stands where its model puts it, lit.
TEST(ImageGenerator, StarsShowAtNightAndTheMoonWhereItsOrbitSays) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  double illuminated = 0.0;
  const core::Vec3 to_moon =
      moon_direction(22.0, 80.0, 40.0, illuminated);  // waning gibbous, east-south-east
  ASSERT_GT(to_moon.z, 0.2);
  const double yaw = std::atan2(to_moon.y, to_moon.x), pitch = std::asin(to_moon.z);
  ig.set_view(free_camera({0.0, 0.0, 20.0}, yaw + 0.3, pitch));  // the moon off centre
  const auto sky_speckles = [&](double hour) {
    ig.update(state(5000.0, 5000.0, 20000.0, hour));
    const osg::Image& image = ig.render();
    int bright = 0;  // pixels much brighter than their neighbours two to the side
    for (int y = 2; y < kHeight / 3; ++y)
      for (int x = 2; x < kWidth - 2; ++x) {
        const double l = luminance(pixel(image, x, y));
        bright +=
            l > luminance(pixel(image, x - 2, y)) + 0.15 && l > luminance(pixel(image, x + 2, y)) + 0.15;
      }
    return bright;
  };
  const int noon = sky_speckles(12.0), night = sky_speckles(22.0);
  ig.update(state(5000.0, 5000.0, 20000.0, 22.0));
  const osg::Image& image = ig.render();
  const auto at = ig.project(core::Vec3{0.0, 0.0, 20.0} + to_moon * 3000.0);
  ASSERT_TRUE(at);
  const double moon = luminance(pixel(image, at->first, at->second));
  std::printf("star speckles: noon %d, night %d; moon (%.0f%% lit) at (%.0f, %.0f): luminance %.2f\n", noon,
              night, illuminated * 100.0, at->first, at->second, moon);
  EXPECT_EQ(noon, 0);
  EXPECT_GT(night, 10);
  EXPECT_GT(moon, 0.5);
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// Looking round: the view turns left and up about the picture's own axes, from a level view and from one
// straight down through a floor (where a turn about the cab's vertical would only spin the picture).
TEST(ImageGenerator, LookingRoundTurnsTheViewAboutThePicturesOwnAxes) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(level());
  scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
  s.cab.look_yaw_rad = 0.5;    // left
  s.cab.look_pitch_rad = 0.3;  // then up
  ig.update(s);
  ig.aim();
  // a point 0.5 rad to the left, then 0.3 up along the turned view: in the picture's centre
  const core::Vec3 eye{0.0, 0.0, 10.0};
  const core::Vec3 left{std::cos(0.5), std::sin(0.5), 0.0};
  const core::Vec3 ahead = left * std::cos(0.3) + core::Vec3{0.0, 0.0, std::sin(0.3)};
  const auto centre = ig.project(eye + ahead * 50.0);
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->first, kWidth / 2.0, 0.5);
  EXPECT_NEAR(centre->second, kHeight / 2.0, 0.5);
  // straight down, the top of the picture ahead (+x): looking left brings a point 0.4 rad to the left of the
  // nadir to the centre
  View down = level();
  down.pitch_rad = -std::numbers::pi / 2.0;
  ig.set_view(down);
  s.cab.look_yaw_rad = 0.4;
  s.cab.look_pitch_rad = 0.0;
  ig.update(s);
  ig.aim();
  const auto nadir_left = ig.project(eye + core::Vec3{0.0, std::sin(0.4), -std::cos(0.4)} * 20.0);
  ASSERT_TRUE(nadir_left);
  EXPECT_NEAR(nadir_left->first, kWidth / 2.0, 0.5);
  EXPECT_NEAR(nadir_left->second, kHeight / 2.0, 0.5);
}

// A camera's picture set into the view: a mirror's is reversed left to right, a monitor's is not; cab views
// only.
TEST(ImageGenerator, AMirrorShowsWhatIsBehindReversedAndAMonitorAsItIs) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  Looks extra;
  extra.cameras.push_back({"rear", "none", {0.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 0.6});
  extra.insets.push_back({"rear", 0.0, 0.6, 0.4, 0.4, true});   // a mirror, top left
  extra.insets.push_back({"rear", 0.6, 0.0, 0.4, 0.4, false});  // a monitor, bottom right
  ig.use(extra);
  ASSERT_EQ(ig.insets().size(), 2u);
  ig.set_view(level());
  scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
  s.entities[0].pose.position = {0.0, 0.0, 14.0};
  // behind the mast: the near box 4 m to the left (+y), the far one 4 m to the right
  s.entities[1].pose.position = {-40.0, 4.0, 14.0};
  s.entities[2].pose.position = {-40.0, -4.0, 14.0};
  ig.update(s);
  const osg::Image& image = ig.render();
  const auto mirror_left = ig.project_inset(0, s.entities[1].pose.position),
             mirror_right = ig.project_inset(0, s.entities[2].pose.position),
             monitor_left = ig.project_inset(1, s.entities[1].pose.position),
             monitor_right = ig.project_inset(1, s.entities[2].pose.position);
  ASSERT_TRUE(mirror_left && mirror_right && monitor_left && monitor_right);
  EXPECT_LT(mirror_left->first, mirror_right->first);    // in the mirror what is on the left shows left
  EXPECT_GT(monitor_left->first, monitor_right->first);  // a camera looking back sees it on its right
  EXPECT_LT(mirror_left->second, kHeight * 0.4);         // in the top-left inset
  EXPECT_GT(monitor_left->first, kWidth * 0.6);          // in the bottom-right one
  // and drawn there: the red box's pixels where the projection says
  const osg::Vec3 red = pixel(image, mirror_left->first, mirror_left->second);
  EXPECT_GT(red.x(), 2.0f * std::max(red.y(), red.z())) << red.x() << " " << red.y() << " " << red.z();
  // a chase view shows no cab mirrors
  View chase;
  chase.kind = View::Kind::kChase;
  ig.set_view(chase);
  ig.render();
  const osg::Vec3 there = pixel(ig.render_result(), mirror_left->first, mirror_left->second);
  EXPECT_FALSE(there.x() > 2.0f * std::max(there.y(), there.z()));
}

// The station's key list over the picture (F1): a dark panel with the text, over the middle of the picture.
TEST(ImageGenerator, TheOverlayPutsItsTextOnADarkPanelOverThePicture) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(level());
  ig.update(state(5000.0, 5000.0, 20000.0, 12.0));
  const double plain = luminance(pixel(ig.render(), kWidth / 2.0, kHeight * 0.2));
  ig.set_overlay("hoist (hoist, + raises): W / S\ntrolley (trolley travel): Up / Down\nF1 this list");
  ig.render();
  double bright = 0.0, dark = 1.0;
  for (int x = kWidth / 4; x < 3 * kWidth / 4; ++x)
    for (int y = static_cast<int>(kHeight * 0.16); y < static_cast<int>(kHeight * 0.3); ++y) {
      const double l = luminance(pixel(ig.render_result(), x, y));
      bright = std::max(bright, l);
      dark = std::min(dark, l);
    }
  EXPECT_LT(dark, 0.5 * plain);  // the panel
  EXPECT_GT(bright, 0.8);        // the letters
  ig.set_overlay("");
  EXPECT_NEAR(luminance(pixel(ig.render(), kWidth / 2.0, kHeight * 0.2)), plain, 0.02)
      << dark << " " << bright;
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// The shipped grab's shells turn with the published opening: shut, the jaw tips meet 0.8 m under the lower
// block's centre (where the bulk model cuts); fully open they part across 4.6 m and rise 2.3 m, as the bite's
// arc in data/machines/mhc.yaml says (2.2 m) to a cell; half open, the tips span half of it (arcsine law).
TEST(ImageGenerator, TheGrabsShellsOpenWithThePublishedOpening) {
  scene::SceneDescription d;
  d.machine = "test";
  d.entities.push_back({"mast", "none", {}});
  d.entities.push_back({"grab", "mhc.grab", {1.6, 1.4, 0.8}});
  d.indicators = {"grab_opening"};
  const Looks shipped = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  ImageGenerator ig(d, shipped.visuals, kWidth, kHeight);
  View v = level();
  v.hud = false;
  ig.set_view(v);
  // 14 m ahead, turned so its shells open across the picture (its x along the world's y)
  const core::Vec3 at{14.0, 0.0, 10.0};
  const auto yellow_extent = [&](double opening) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
    s.entity_count = 2;
    s.entities[1] = {1, 0, {core::Mat3::rotation({0.0, 0.0, 1.0}, std::numbers::pi / 2.0), at}};
    s.indicator_count = 1;
    s.indicators[0] = opening;
    ig.update(s);
    const osg::Image& image = ig.render();
    int left = kWidth, right = -1, lowest = -1;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const osg::Vec3 p = pixel(image, x, y);
        if (safety_yellow(p)) {
          left = std::min(left, x);
          right = std::max(right, x);
          lowest = std::max(lowest, y);
        }
      }
    return std::tuple{left, right, lowest};
  };
  const auto [l0, r0, low0] = yellow_extent(0.0);
  const double metre = ig.project(at + core::Vec3{0, -1, 0})->first - ig.project(at)->first;  // pixels
  const auto [lh, rh, lowh] = yellow_extent(0.5);
  const auto [l1, r1, low1] = yellow_extent(1.0);
  std::printf("shells across: shut %.2f m, half open %.2f m, open %.2f m; lowest point %.2f, %.2f, %.2f m\n",
              (r0 - l0) / metre, (rh - lh) / metre, (r1 - l1) / metre,
              at.z - (low0 - ig.project(at)->second) / metre, at.z - (lowh - ig.project(at)->second) / metre,
              at.z - (low1 - ig.project(at)->second) / metre);
  // where the near side plates' corners must be drawn (the grab 2.8 m wide along the view: its near side is
  // the larger in the picture)
  const auto near = [&](double across, double up) { return *ig.project(at + core::Vec3{-1.4, -across, up}); };
  EXPECT_NEAR(low0, near(0.0, -0.8).second,
              3.0);  // shut: the tips meet 0.8 m down, where the bulk model cuts
  EXPECT_NEAR(r0 - l0, near(1.5, 0.0).first - near(-1.5, 0.0).first, 4.0);  // two shells 1.5 m deep
  // open: the tips 4.6 m apart, up on their arc at the pivot's height
  EXPECT_NEAR(r1 - l1, near(2.3, 1.5).first - near(-2.3, 1.5).first, 4.0);
  EXPECT_NEAR(low1, near(2.3, 1.5).second, 4.0);
  EXPECT_GT(rh - lh, r0 - l0);
  EXPECT_LT(rh - lh, r1 - l1);
}

// A steered tyre turns about its upright with its indicator as published, left for a positive one and right
// for a negative, a full 90 deg as an RTG's wheels turn (seen from above, the tread's long axis is the
// wheel's heading), and rolls about its axle by the distance its machine's speed covers over its radius; a
// jump in time (a seek) does not roll it.
TEST(ImageGenerator, ASteeredWheelTurnsWithItsSteeringAndRollsWithTheSpeed) {
  scene::SceneDescription d;
  d.machine = "test";
  d.entities.push_back({"mast", "none", {}});
  d.entities.push_back({"car", "test.car", {1.0, 1.0, 1.0}});
  d.indicators = {"speed_kmh", "steer_deg"};
  VisualPart wheel;
  wheel.shape = VisualPart::Shape::kTyre;
  wheel.size_m = core::Vec3{1.1, 0.4, 1.1};
  wheel.color = {0.05, 0.05, 0.05};
  wheel.rim_color = {0.05, 0.05, 0.05};
  wheel.turn = PartTurn{"steer_deg", {0.0, 0.0, 1.0}, std::numbers::pi / 180.0, false};  // a degree a degree
  wheel.rolls_with = "speed_kmh";
  wheel.rolls_unit_mps = 1.0 / 3.6;
  Visual car;
  car.parts.push_back(wheel);
  ImageGenerator ig(d, {{"test.car", car}}, kWidth, kHeight);
  const core::Vec3 at{0.0, 0.0, 14.0};
  ig.set_view(free_camera(at + core::Vec3{0.0, 0.0, 6.0}, 0.0, -std::numbers::pi / 2.0 + 1e-3));
  const auto snapshot = [&](double time_s, double speed_kmh, double steering) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
    s.time_s = time_s;
    s.entity_count = 2;
    s.entities[1] = {1, 0, {core::Mat3::identity(), at}};
    s.indicator_count = 2;
    s.indicators[0] = speed_kmh;
    s.indicators[1] = steering;
    return s;
  };
  // the heading of the tread's long axis seen from above (second moments of its dark pixels), in the world
  const auto heading_deg = [&](double steering) {
    ig.update(snapshot(0.0, 0.0, steering));
    const osg::Image& image = ig.render();
    const auto centre = *ig.project(at);
    double n = 0, sxx = 0, syy = 0, sxy = 0;
    for (int row = 0; row < kHeight; ++row)
      for (int col = 0; col < kWidth; ++col)
        if (luminance(pixel(image, col, row)) < 0.1) {
          // looking down with +x up the picture: the world's x up, its y to the left
          const double x = centre.second - row, y = centre.first - col;
          n += 1, sxx += x * x, syy += y * y, sxy += x * y;
        }
    EXPECT_GT(n, 100.0);
    return 0.5 * std::atan2(2.0 * sxy, sxx - syy) * 180.0 / std::numbers::pi;
  };
  const double straight = heading_deg(0.0), left = heading_deg(38.0), right = heading_deg(-19.0),
               across = heading_deg(90.0);
  std::printf("wheel heading: %.1f deg straight, %.1f deg turned 38 left, %.1f deg 19 right, %.1f deg 90\n",
              straight, left, right, across);
  EXPECT_NEAR(straight, 0.0, 2.0);
  EXPECT_NEAR(left, 38.0, 2.0);
  EXPECT_NEAR(right, -19.0, 2.0);
  EXPECT_NEAR(std::abs(across), 90.0, 2.0);  // the long axis: 90 and -90 are one

  // rolling: 10 km/h for 0.5 s in 50 snapshots is 1.389 m, over a 0.55 m radius 2.525 rad
  ig.update(snapshot(0.0, 0.0, 0.0));
  ASSERT_EQ(ig.tyre_angles().size(), 1u);
  const double start = ig.tyre_angles()[0];
  for (int k = 1; k <= 50; ++k)
    ig.update(snapshot(0.01 * k, 10.0, 0.0));
  EXPECT_NEAR(ig.tyre_angles()[0] - start, 10.0 / 3.6 * 0.5 / 0.55, 1e-9);
  const double before_jump = ig.tyre_angles()[0];
  ig.update(snapshot(30.0, 10.0, 0.0));  // a seek half a minute on
  EXPECT_EQ(ig.tyre_angles()[0], before_jump);
  ig.update(snapshot(30.1, -10.0, 0.0));  // backing up turns it back
  EXPECT_NEAR(ig.tyre_angles()[0], before_jump - 10.0 / 3.6 * 0.1 / 0.55, 1e-9);
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// the first of "box 0", "box 1", ... whose livery is `livery` of `count`
std::string named_for_livery(std::size_t livery, std::size_t count) {
  for (int n = 0;; ++n)
    if (const std::string name = "box " + std::to_string(n); scene::livery_key(name) % count == livery)
      return name;
}

TEST(ImageGenerator, ABoxIsPaintedByItsNameWhereverItStandsAndTakesTheLiveryOfANewName) {
  EXPECT_EQ(scene::livery_key(""), 2166136261u);  // FNV-1a's published vectors
  EXPECT_EQ(scene::livery_key("a"), 0xe40c292cu);
  EXPECT_EQ(scene::livery_key("foobar"), 0xbf9cf968u);
  Visual painted;
  VisualPart part;
  part.size_m = core::Vec3{0.2, 2.44, 2.6};
  part.livery = true;
  painted.parts.push_back(part);
  painted.liveries = {{0.9, 0.1, 0.1}, {0.1, 0.9, 0.1}, {0.1, 0.1, 0.9}};
  const std::map<std::string, Visual> looks{{"test.box", painted}};
  const std::string red = named_for_livery(0, 3), green = named_for_livery(1, 3);
  // the colour drawn where entity `index` stands 40 m ahead of the cab (the others out of sight)
  const auto colour_ahead = [&](ImageGenerator& ig, std::size_t index) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
    s.entities[index].pose.position = {40.0, 0.0, 14.0};
    ig.set_view(level());
    ig.update(s);
    const osg::Image& image = ig.render();
    const auto at = ig.project({40.0, 0.0, 14.0});
    return pixel(image, at->first, at->second);
  };
  scene::SceneDescription first = scene();
  first.entities[1].name = red;
  first.entities[2].name = green;
  first.machine_entities = 3;  // as a tractor's load is one of its machine's entities
  ImageGenerator ig(first, looks, kWidth, kHeight);
  const osg::Vec3 as_first = colour_ahead(ig, 1);
  EXPECT_GT(as_first.x(), 2.0 * as_first.y()) << as_first.x() << " " << as_first.y() << " " << as_first.z();
  EXPECT_GT(colour_ahead(ig, 2).y(), 2.0 * colour_ahead(ig, 2).x());
  // the same box second in another scene: the same paint
  scene::SceneDescription other = scene();
  other.entities[1].name = green;
  other.entities[2].name = red;
  ImageGenerator elsewhere(other, looks, kWidth, kHeight);
  const osg::Vec3 again = colour_ahead(elsewhere, 2);
  EXPECT_NEAR(again.x(), as_first.x(), 0.02);
  EXPECT_NEAR(again.y(), as_first.y(), 0.02);
  // a box handed over onto this entity: it is the green one now
  ig.rename_entity(1, green);
  const osg::Vec3 renamed = colour_ahead(ig, 1);
  EXPECT_GT(renamed.y(), 2.0 * renamed.x()) << renamed.x() << " " << renamed.y() << " " << renamed.z();
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// The shipped STS spreader telescopes with its published length: seen from above its yellow spans the
// length the physics has (40 ft, then 20 and 45 ft) to a pixel or two; its flippers fold down with their
// indicators: seen from the side, the plates reach 0.4 m under its underside (data/machines/sts.yaml's
// flipper depth), none while they are up.
TEST(ImageGenerator, TheSpreaderTelescopesWithItsLengthAndItsFlippersFoldDown) {
  scene::SceneDescription d;
  d.machine = "test";
  d.entities.push_back({"mast", "none", {}});
  d.entities.push_back({"spreader", "sts.spreader", {1.219, 6.096, 0.5}});  // 40 ft, as the STS describes it
  d.indicators = {"spreader_length_m", "flipper_1", "flipper_2", "flipper_3", "flipper_4"};
  const Looks shipped = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  ImageGenerator ig(d, shipped.visuals, kWidth, kHeight);
  const core::Vec3 at{20.0, 0.0, 14.0};
  const auto show = [&](double length_m, double flippers) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
    s.entity_count = 2;
    s.entities[1] = {1, 0, {core::Mat3::identity(), at}};
    s.indicator_count = 5;
    s.indicators[0] = length_m;
    for (int c = 1; c <= 4; ++c)
      s.indicators[static_cast<std::size_t>(c)] = flippers;
    ig.update(s);
    return &ig.render();
  };
  // from 40 m above, its length across the picture (the world's y to the left)
  ig.set_view(free_camera(at + core::Vec3{0.0, 0.0, 40.0}, 0.0, -std::numbers::pi / 2.0 + 1e-3));
  for (const double length : {12.192, 6.058, 13.716}) {
    const osg::Image& image = *show(length, 0.0);
    int left = kWidth, right = -1;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (safety_yellow(pixel(image, x, y))) {
          left = std::min(left, x);
          right = std::max(right, x);
        }
    const double drawn = right - left + 1;
    const double expected = ig.project(at + core::Vec3{0.0, -length / 2.0, 0.0})->first -
                            ig.project(at + core::Vec3{0.0, length / 2.0, 0.0})->first;
    std::printf("spreader %.3f m long: drawn %.0f px, its length %.1f px\n", length, drawn, expected);
    EXPECT_NEAR(drawn, expected, 2.5) << length;
  }
  // from the side, 15 m off: the lowest yellow
  ig.set_view(free_camera(at + core::Vec3{-15.0, 0.0, 0.0}, 0.0, 0.0));
  const auto lowest_row = [&](double flippers) {
    const osg::Image& image = *show(12.192, flippers);
    int lowest = -1;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (safety_yellow(pixel(image, x, y))) lowest = std::max(lowest, y);
    return lowest;
  };
  // the near corners' underside, 1.3 m nearer than the centre
  const auto row_at = [&](double below_m) {
    return ig.project(at + core::Vec3{-1.3, 0.0, -0.5 - below_m})->second;
  };
  const int up = lowest_row(0.0), down = lowest_row(1.0), half = lowest_row(0.5);
  std::printf("lowest yellow row: flippers up %d, down %d, half %d; underside %.1f, 0.4 m under it %.1f\n",
              up, down, half, row_at(0.0), row_at(0.4));
  EXPECT_NEAR(up, row_at(0.0), 2.0);
  EXPECT_NEAR(down, row_at(0.4), 2.0);
  EXPECT_GT(half, up);  // half way round: hanging outboard
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// A jack between two entities is drawn from eye to eye as they move apart (its barrel from one, its rod from
// the other), and shows the gap a real one would have were they further apart than both its lengths.
TEST(ImageGenerator, AJackReachesFromEyeToEyeAsItsEntitiesMove) {
  scene::SceneDescription d;
  d.machine = "test";
  d.entities.push_back({"mast", "none", {}});
  d.entities.push_back({"base", "test.base", {0.5, 0.5, 0.5}});
  d.entities.push_back({"arm", "test.arm", {0.5, 0.5, 0.5}});
  ImageGenerator ig(d, {{"test.base", Visual{}}, {"test.arm", Visual{}}}, kWidth, kHeight);
  Jack jack;
  jack.from_entity = "test.base";
  jack.to_entity = "test.arm";
  jack.barrel_m = 2.0;
  jack.rod_m = 2.0;
  jack.diameter_m = 0.3;
  jack.color = {0.7, 0.1, 0.1};
  ig.set_view(level());
  // the jack across the view 15 m ahead, its eyes `apart` metres apart: the columns it changes
  const auto columns = [&](double apart) {
    scene::Snapshot s = state(5000.0, 5000.0, 20000.0, 12.0);
    s.entity_count = 3;
    s.entities[1] = {1, 0, {core::Mat3::identity(), {15.0, apart / 2.0, 10.0}}};
    s.entities[2] = {2, 0, {core::Mat3::identity(), {15.0, -apart / 2.0, 10.0}}};
    ig.set_jacks({});
    ig.update(s);
    const osg::ref_ptr<osg::Image> without = new osg::Image(ig.render(), osg::CopyOp::DEEP_COPY_ALL);
    ig.set_jacks({jack});
    ig.update(s);
    const osg::Image& with = ig.render();
    std::vector<bool> changed(kWidth, false);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if ((pixel(with, x, y) - pixel(*without, x, y)).length() > 0.05f)
          changed[static_cast<std::size_t>(x)] = true;
    return changed;
  };
  const auto column_of = [&](double y) { return ig.project({15.0, y, 10.0})->first; };
  for (const double apart : {2.5, 3.9}) {  // from a rod's length to both lengths
    const std::vector<bool> changed = columns(apart);
    const auto first = std::find(changed.begin(), changed.end(), true) - changed.begin();
    const auto last = changed.rend() - std::find(changed.rbegin(), changed.rend(), true) - 1;
    std::printf("jack %.1f m between its eyes: columns %td-%td, its eyes at %.1f and %.1f\n", apart, first,
                last, column_of(apart / 2.0), column_of(-apart / 2.0));
    EXPECT_NEAR(static_cast<double>(first), column_of(apart / 2.0), 2.0);
    EXPECT_NEAR(static_cast<double>(last), column_of(-apart / 2.0), 2.0);
    for (auto x = first; x <= last; ++x)
      EXPECT_TRUE(changed[static_cast<std::size_t>(x)]) << apart << " m: a gap at column " << x;
  }
  // 4.6 m apart: the barrel's and the rod's ends 0.6 m apart in the middle
  const std::vector<bool> over = columns(4.6);
  for (double y = -0.2; y <= 0.2; y += 0.1)
    EXPECT_FALSE(over[static_cast<std::size_t>(std::lround(column_of(y)))]) << y;
  EXPECT_TRUE(over[static_cast<std::size_t>(std::lround(column_of(1.0)))]);
  EXPECT_TRUE(over[static_cast<std::size_t>(std::lround(column_of(-1.0)))]);
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// Far off in a gale the whitecaps whiten the sea evenly (their mean, where a pixel spans several of their
// cells) instead of drawing a lattice of dots: just under the horizon (0.3-2.7 km out) the luminance changes
// from pixel to pixel along a row no more than in a calm (0.0002 against 0.028-0.049 with the dots), while
// the sea there is whiter than in a calm by the foam's cover W (mean luminance 0.558 at 26 m/s, 0.511 calm).
TEST(ImageGenerator, FarWhitecapsWhitenTheSeaEvenly) {
  constexpr int kFrom = 3, kTo = 25;  // rows under the horizon: 2.7 km to 320 m out, 20 m below the eye
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  ig.set_view(free_camera({200.0, 0.0, 20.0}, 0.0, 0.0));  // level, out over open water
  const auto band = [&](double wind) {
    const osg::Image& image = sea_in_wind(ig, wind, 12.0, 30.0);
    const int horizon = static_cast<int>(std::lround(ig.project({200.0 + 1e5, 0.0, 20.0})->second));
    double change = 0.0, mean = 0.0, n = 0.0;
    for (int y = horizon + kFrom; y <= horizon + kTo; ++y)
      for (int x = 1; x < kWidth; ++x) {
        change += std::abs(luminance(pixel(image, x, y)) - luminance(pixel(image, x - 1, y)));
        mean += luminance(pixel(image, x, y));
        ++n;
      }
    return std::pair{change / n, mean / n};
  };
  const auto [calm_change, calm_mean] = band(0.0);
  const auto [gale_change, gale_mean] = band(26.0);
  std::printf("far sea: calm change %.4f mean %.3f; 26 m/s change %.4f mean %.3f\n", calm_change, calm_mean,
              gale_change, gale_mean);
  EXPECT_LT(gale_change, calm_change + 0.005);
  EXPECT_GT(gale_mean, calm_mean + 0.015);
}

// Whitecaps cover the share of the sea Monahan & O'Muircheartaigh (1980) photographed, W = 3.84e-6 U^3.41,
// as the wind rises: the share of the sea's pixels, looking down at it from 40 m with the sun behind or
// beside the eye (no glint), whiter than half way from the calm sea's luminance to the foam's, at 10-22 m/s,
// over three headings and four moments each (streaks live a few seconds).
TEST(ImageGenerator, WhitecapsCoverTheSeaAsMonahansLawSays) {
  ImageGenerator ig(scene(), looks(), kWidth, kHeight);
  const auto render = [&](double wind, double yaw, double t) -> const osg::Image& {
    ig.set_view(free_camera({300.0, 0.0, 40.0}, yaw, -1.1));
    return sea_in_wind(ig, wind, 12.0, t);
  };
  const double calm = mean_luminance(render(0.0, 0.0, 30.0));
  const double foam = luminance({0.86f, 0.89f, 0.91f});  // the shader's foam in full daylight
  const double threshold = 0.5 * (calm + foam);
  double previous = 0.0;
  for (const double wind : {10.0, 14.0, 18.0, 22.0}) {
    double white = 0.0, pixels = 0.0;
    for (const double yaw : {0.0, std::numbers::pi / 2.0, std::numbers::pi})
      for (const double t : {30.0, 37.0, 44.0, 51.0}) {
        const osg::Image& image = render(wind, yaw, t);
        for (int y = 0; y < kHeight; ++y)
          for (int x = 0; x < kWidth; ++x) {
            white += luminance(pixel(image, x, y)) > threshold ? 1.0 : 0.0;
            ++pixels;
          }
      }
    const double cover = white / pixels, monahan = 3.84e-6 * std::pow(wind, 3.41);
    std::printf("%.0f m/s: whitecaps cover %.4f of the sea, Monahan's W %.4f (%.0f %%)\n", wind, cover,
                monahan, 100.0 * cover / monahan);
    EXPECT_NEAR(cover, monahan, 0.25 * monahan) << wind << " m/s";
    EXPECT_GT(cover, previous) << wind << " m/s";
    previous = cover;
  }
}

}  // namespace
}  // namespace harbour::ig
