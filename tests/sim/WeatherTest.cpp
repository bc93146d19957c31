#include "harbour/sim/Weather.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "harbour/core/Units.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/sim/Simulation.h"
#include "scenes/StsScenes.h"

namespace harbour::sim {
namespace {

TEST(Weather, GustFollowsTheOneMinusCosineShape) {
  WeatherSettings s;
  s.wind_mean_mps = 5.0;
  Weather w(s, 1);
  w.add_gust({1.0, 3.0, 8.0});
  auto speed_at = [&](double t) {
    Weather copy = w;
    for (int k = 0; k < static_cast<int>(std::lround(t / 0.001)); ++k)
      copy.step(0.001);
    return copy.speed_mps();
  };
  EXPECT_NEAR(speed_at(0.5), 5.0, 1e-9);
  EXPECT_NEAR(speed_at(1.75), 5.0 + 4.0, 1e-6);  // a quarter in: half the amplitude
  EXPECT_NEAR(speed_at(2.5), 13.0, 1e-6);        // the peak at mid-gust
  EXPECT_NEAR(speed_at(4.5), 5.0, 1e-9);
}

TEST(Weather, TurbulenceHasTheSetIntensity) {
  WeatherSettings s;
  s.wind_mean_mps = 10.0;
  s.turbulence_intensity = 0.15;
  Weather w(s, 42);
  double sum = 0, sum2 = 0;
  const int n = 720000;  // 2 hours at 100 Hz
  for (int k = 0; k < n; ++k) {
    w.step(0.01);
    sum += w.speed_mps();
    sum2 += w.speed_mps() * w.speed_mps();
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 10.0, 0.2);
  EXPECT_NEAR(sd, 1.5, 0.15);
}

TEST(Weather, DragOnABroadsideBoxFollowsTheFormula) {
  const core::Vec3 half{12.192 / 2, 2.438 / 2, 2.591 / 2};
  const core::Vec3 f = box_drag({0, 20, 0}, {}, {}, half, 1.0, 1.225);
  EXPECT_NEAR(f.y, 0.5 * 1.225 * 1.0 * (12.192 * 2.591) * 400.0, 1e-6);
  EXPECT_NEAR(f.x, 0.0, 1e-12);
  const core::Vec3 end_on = box_drag({20, 0, 0}, {}, {}, half, 1.0, 1.225);
  EXPECT_NEAR(end_on.x, 0.5 * 1.225 * (2.438 * 2.591) * 400.0, 1e-6);
}

TEST(Weather, SteadyWindDeflectsTheHangingSpreaderBySwingTheory) {
  ScenarioSettings s = scenes::sts_discharge(HARBOUR_DATA_DIR);
  s.weather.wind_mean_mps = 20.0;
  s.weather.wind_from_rad = core::deg_to_rad(180.0);  // from the south: the air moves towards +y
  Simulation sim(s);
  for (int k = 0; k < 20000; ++k)
    sim.step({});
  double y = 0, fall = 0;
  const int n = 40000;  // four swing periods
  for (int k = 0; k < n; ++k) {
    sim.step({});
    y += sim.machine_as<StsCrane>().spreader_pose().position.y / n;
    fall += (s.machine.as<StsSetup>().crane.trolley_rail_height_m - 1.0 -
             (sim.machine_as<StsCrane>().spreader_pose().position.z + 0.5)) /
            n;
  }
  const double force = 0.5 * 1.225 * 1.0 * s.machine.as<StsSetup>().crane.spreader.width_m *
                       s.machine.as<StsSetup>().crane.spreader.height_m * 400.0;
  const double expected = fall * force / (s.machine.as<StsSetup>().crane.spreader.mass_kg * 9.80665);
  EXPECT_NEAR(y, expected, 0.05 * expected);
  // the rest position the evaluation measures sway from is that equilibrium
  EXPECT_NEAR(sim.machine_as<StsCrane>().pendulum_length_m(), fall, 0.01);
  const core::Vec3 rest = sim.wind_rest_offset_m(sim.weather().mean_wind(), std::nullopt);
  EXPECT_NEAR(rest.y, expected, 0.01 * expected);
  EXPECT_NEAR(rest.x, 0.0, 1e-9);
  EXPECT_NEAR(sim.snapshot()->wind_mps.y, 20.0, 1e-12);
}

TEST(Weather, AnEmergencyStopHoldsTheLoadUnlessTheBrakeIsFaulty) {
  for (const bool faulty : {false, true}) {
    ScenarioSettings s = scenes::sts_discharge(HARBOUR_DATA_DIR);
    if (faulty) s.events.push_back({ScriptedEvent::Kind::kHoistBrakeFault, 1.0});
    Simulation sim(s);
    for (int k = 0; k < 3000; ++k)
      sim.step({});
    const double z0 = sim.machine_as<StsCrane>().spreader_pose().position.z;
    StsControls stop;
    stop.emergency_stop = true;
    for (int k = 0; k < 2000; ++k)
      sim.step(scenes::cab(stop));
    const double dz = sim.machine_as<StsCrane>().spreader_pose().position.z - z0;
    if (faulty) {
      EXPECT_LT(dz, -1.0) << "a faulty brake lets the load run down";
    } else {
      EXPECT_NEAR(dz, 0.0, 0.01);
    }
  }
}

TEST(Weather, AFailedLandedSensorPreventsLocking) {
  ScenarioSettings s = scenes::sts_discharge(HARBOUR_DATA_DIR);
  s.events.push_back({ScriptedEvent::Kind::kLandedSensorFault, 0.0, {}, 2});
  Simulation sim(s);
  StsControls lower;
  lower.hoist = -0.1;
  for (int k = 0; k < 60000 && sim.machine_as<StsCrane>().spreader_pose().position.z > 3.3 + 2.591 + 0.5; ++k)
    sim.step(scenes::cab(lower));
  for (int k = 0; k < 1000; ++k)
    sim.step(scenes::cab(lower));  // sitting on the box
  EXPECT_FALSE(sim.machine_as<StsCrane>().lamps().landed);
  StsControls lock;
  lock.lock = true;
  for (int k = 0; k < 10; ++k)
    sim.step(scenes::cab(lock));
  EXPECT_FALSE(sim.machine_as<StsCrane>().locked_container().has_value());
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

TEST(Weather, OverlappingGustsSaturateAndFinishedOnesAreForgotten) {
  WeatherSettings settings;
  settings.wind_mean_mps = 20.0;
  Weather w(settings, 1);
  for (int n = 0; n < 1000; ++n)  // a thousand 30 m/s gusts peaking together: 30 020 m/s unbounded
    w.add_gust({0.0, 2.0, kMaxGust_mps});
  for (int k = 0; k < 1000; ++k)
    w.step(0.001);
  EXPECT_EQ(w.speed_mps(), kMaxWindSpeed_mps);  // at the peak, t = 1 s
  for (int k = 0; k < 1001; ++k)
    w.step(0.001);
  EXPECT_EQ(w.speed_mps(), 20.0);  // all over: the mean again
  core::StateWriter out;
  w.save_state(out);
  EXPECT_LT(out.take().size(), 200u);  // and the thousand gusts are not carried in the state
}

// The instructor's cloud cover is part of the saved state; a clear sky is saved as before the weather had a
// cover (section "WTX2", the same fields less the cloud: the same bytes and hashes as the runs recorded
// then), and such a state restores with a clear sky.
TEST(Weather, TheCloudCoverIsKeptAndAnOlderStateRestoresClear) {
  WeatherSettings settings;
  settings.rain_mm_per_h = 3.0;
  Weather w(settings, 1);
  w.set_cloud(6.0);
  core::StateWriter out;
  w.save_state(out);
  std::vector<std::uint8_t> bytes = out.take();
  Weather restored(WeatherSettings{}, 2);
  core::StateReader in(bytes);
  restored.restore_state(in);
  EXPECT_TRUE(in.at_end());
  EXPECT_EQ(restored.settings().cloud_oktas, 6.0);
  EXPECT_EQ(restored.settings().rain_mm_per_h, 3.0);
  // the older layout: its tag, then the fields up to the air's density, then the rest as now
  const std::uint32_t version2 = 0x57545832;
  constexpr std::size_t kTag = 4, kFields = 8 * sizeof(double);
  std::vector<std::uint8_t> older;
  for (std::size_t n = 0; n < bytes.size(); ++n)
    if (n < kTag + kFields || n >= kTag + kFields + sizeof(double)) older.push_back(bytes[n]);
  std::memcpy(older.data(), &version2, kTag);
  Weather from_older(WeatherSettings{}, 3);
  from_older.set_cloud(8.0);
  core::StateReader older_in(older);
  from_older.restore_state(older_in);
  EXPECT_TRUE(older_in.at_end());
  EXPECT_EQ(from_older.settings().cloud_oktas, 0.0);
  EXPECT_EQ(from_older.settings().rain_mm_per_h, 3.0);
  // a clear sky saves those bytes
  w.set_cloud(0.0);
  core::StateWriter clear;
  w.save_state(clear);
  EXPECT_EQ(clear.take(), older);
  // anything else is refused by its section
  older[0] ^= 0xFF;
  core::StateReader bad(older);
  EXPECT_THROW(from_older.restore_state(bad), core::StateError);
}

}  // namespace
}  // namespace harbour::sim
