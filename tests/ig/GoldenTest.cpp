// Golden images: the discharge exercise 40 s in, seen from the chase view, in five conditions, against small
// committed PNGs (tests/data/golden/) with a tolerance. HARBOUR_UPDATE_GOLDENS=1 rewrites them (look at them
// before committing).
#include <gtest/gtest.h>

#include <osg/Image>
#include <osgDB/ReadFile>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include "harbour/ig/ImageGenerator.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/MachineRegistry.h"

namespace harbour::ig {
namespace {

constexpr int kWidth = 240, kHeight = 135;

struct Condition {
  const char* name;
  double time_of_day_h, visibility_m, rain_mm_per_h;
  double min_psnr_db;  // rain's particles are random: a looser match
};

// the peak signal-to-noise ratio of two RGB images of the same size [dB]
double psnr(const osg::Image& a, const osg::Image& b) {
  double sum = 0.0;
  long n = 0;
  for (int y = 0; y < a.t(); ++y)
    for (int x = 0; x < a.s(); ++x) {
      const osg::Vec4 p = a.getColor(x, y), q = b.getColor(x, y);
      for (int c = 0; c < 3; ++c) {
        const double d = 255.0 * (p[c] - q[c]);
        sum += d * d;
        ++n;
      }
    }
  const double mse = sum / static_cast<double>(n);
  return mse == 0.0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}

// The discharge exercise 40 s in under the autopilot (the box on its way), drawn from the chase view without
// the HUD (text rasterises differently across font builds): the image generator and the state it shows.
struct DischargeInChase {
  std::unique_ptr<ImageGenerator> ig;
  std::unique_ptr<scene::Snapshot> at_40_s;
};
DischargeInChase discharge_in_chase(int width, int height) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/sts_discharge.yaml");
  sim::Simulation simulation(exercise.scenario);
  sim::GantryAutopilot pilot(exercise);
  while (simulation.time_s() < 40.0)
    simulation.step(pilot.next(simulation));
  Looks looks = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  DischargeInChase d{
      std::make_unique<ImageGenerator>(simulation.scene(), std::move(looks.visuals), width, height),
      simulation.snapshot()};
  d.ig->use(looks);
  View chase;
  chase.kind = View::Kind::kChase;
  chase.hud = false;
  d.ig->set_view(chase);
  return d;
}

TEST(Golden, TheDischargeInFiveConditionsLooksAsRecorded) {
  const DischargeInChase discharge = discharge_in_chase(kWidth, kHeight);
  ImageGenerator& ig = *discharge.ig;
  const bool update = std::getenv("HARBOUR_UPDATE_GOLDENS") != nullptr;
  const std::string folder = std::string(HARBOUR_DATA_DIR) + "/../tests/data/golden/";
  for (const Condition& c :
       {Condition{"noon", 12.0, 20000.0, 0.0, 35.0}, Condition{"dusk", 18.2, 20000.0, 0.0, 35.0},
        Condition{"night", 22.0, 20000.0, 0.0, 35.0}, Condition{"fog_200m", 12.0, 200.0, 0.0, 35.0},
        Condition{"rain", 12.0, 3000.0, 20.0, 22.0}}) {
    scene::Snapshot snapshot = *discharge.at_40_s;
    snapshot.time_of_day_h = c.time_of_day_h;
    snapshot.visibility_m = c.visibility_m;
    snapshot.rain_mm_per_h = c.rain_mm_per_h;
    ig.update(snapshot);
    ig.render();
    const std::string path = folder + c.name + ".png";
    if (update) {
      ASSERT_TRUE(ig.write_png(path));
      continue;
    }
    const osg::ref_ptr<osg::Image> golden = osgDB::readImageFile(path);
    ASSERT_TRUE(golden.valid()) << path;
    ASSERT_EQ(golden->s(), kWidth);
    ASSERT_EQ(golden->t(), kHeight);
    const double db = psnr(ig.render_result(), *golden);
    std::printf("%-9s PSNR %.1f dB against %s\n", c.name, db, path.c_str());
    EXPECT_GE(db, c.min_psnr_db) << c.name
                                 << ": the picture changed (HARBOUR_UPDATE_GOLDENS=1 rewrites, after a look)";
  }
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// Filtered shadow edges (ImageGenerator::set_soft_shadows): the discharge 40 s in from the chase view at 16
// h, drawn with one shadow-map lookup and with the 3x3 filter, differs only along the shadows' edges, where
// the filtered one ramps between shade and sun: every changed pixel has, within 6 pixels (a few of the shadow
// map's texels), a pixel of another brightness in the hard picture (0.004: the boom's faint shadow on the
// water counts) — all but a few (under 0.01 %: the far crane rail's top, within a shadow-map texel of its
// own shadow, its glint dimmed by the filter's taps).
TEST(Golden, SoftShadowsChangeOnlyTheShadowsEdges) {
  constexpr int kW = 640, kH = 360;
  const DischargeInChase discharge = discharge_in_chase(kW, kH);
  ImageGenerator& ig = *discharge.ig;
  scene::Snapshot snapshot = *discharge.at_40_s;
  snapshot.time_of_day_h = 16.0;
  ig.update(snapshot);
  const auto draw = [&](bool soft) {
    ig.set_soft_shadows(soft);
    const osg::Image& image = ig.render();
    std::vector<double> l(static_cast<std::size_t>(kW * kH));
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const osg::Vec4 c = image.getColor(x, y);
        l[static_cast<std::size_t>(y * kW + x)] = 0.2126 * c.r() + 0.7152 * c.g() + 0.0722 * c.b();
      }
    return l;
  };
  const std::vector<double> hard = draw(false), soft = draw(true);
  int changed = 0, away_from_edges = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t k = static_cast<std::size_t>(y * kW + x);
      if (std::abs(hard[k] - soft[k]) < 0.01) continue;
      ++changed;
      bool edge = false;
      for (int dy = -6; dy <= 6 && !edge; ++dy)
        for (int dx = -6; dx <= 6 && !edge; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && yy >= 0 && xx < kW && yy < kH)
            edge = std::abs(hard[static_cast<std::size_t>(yy * kW + xx)] - hard[k]) > 0.004;
        }
      if (!edge) ++away_from_edges;
    }
  std::printf("soft shadows change %d of %d pixels, %d away from an edge\n", changed, kW * kH,
              away_from_edges);
  EXPECT_GT(changed, 200) << "the filtered edges are ramps";
  EXPECT_LT(changed, kW * kH / 10) << "only edges change";
  EXPECT_LE(away_from_edges, kW * kH / 10000);  // a thin part's top a texel from its own shadow: the far rail
}

}  // namespace
}  // namespace harbour::ig
