// Golden images: the discharge exercise 40 s in, seen from the chase view, in five conditions, against small
// committed PNGs (tests/data/golden/) with a tolerance. HARBOUR_UPDATE_GOLDENS=1 rewrites them (look at them
// before committing).
#include <gtest/gtest.h>

#include <osg/Image>
#include <osgDB/ReadFile>

#include <cmath>
#include <cstdlib>
#include <string>

#include "harbour/ig/ImageGenerator.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Autopilot.h"

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

TEST(Golden, TheDischargeInFiveConditionsLooksAsRecorded) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/sts_discharge.yaml");
  sim::Simulation simulation(exercise.scenario);
  sim::Autopilot pilot(exercise);
  while (simulation.time_s() < 40.0)
    simulation.step(pilot.next(simulation));
  Looks looks = load_looks(std::string(HARBOUR_DATA_DIR) + "/visuals/harbour.yaml");
  ImageGenerator ig(simulation.scene(), std::move(looks.visuals), kWidth, kHeight);
  ig.use(looks);
  View chase;
  chase.kind = View::Kind::kChase;
  chase.hud = false;  // text rasterises differently across font builds
  ig.set_view(chase);
  const bool update = std::getenv("HARBOUR_UPDATE_GOLDENS") != nullptr;
  const std::string folder = std::string(HARBOUR_DATA_DIR) + "/../tests/data/golden/";
  for (const Condition& c :
       {Condition{"noon", 12.0, 20000.0, 0.0, 35.0}, Condition{"dusk", 18.2, 20000.0, 0.0, 35.0},
        Condition{"night", 22.0, 20000.0, 0.0, 35.0}, Condition{"fog_200m", 12.0, 200.0, 0.0, 35.0},
        Condition{"rain", 12.0, 3000.0, 20.0, 22.0}}) {
    auto snapshot = simulation.snapshot();
    snapshot->time_of_day_h = c.time_of_day_h;
    snapshot->visibility_m = c.visibility_m;
    snapshot->rain_mm_per_h = c.rain_mm_per_h;
    ig.update(*snapshot);
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
