#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/mhc/HookAutopilot.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665;

ExerciseSettings hook_lift() {
  return io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_hook_lift.yaml");
}

const MobileHarbourCrane& mhc(const Simulation& sim) {
  return dynamic_cast<const MobileHarbourCrane&>(sim.machine());
}

scene::Controls levers(const Simulation& sim, std::initializer_list<std::pair<const char*, double>> values) {
  scene::Controls c = sim.control_table().neutral();
  for (const auto& [label, value] : values)
    c.value[static_cast<std::size_t>(sim.control_table().find(label))] = value;
  return c;
}

void run(Simulation& sim, double seconds, const scene::Controls& controls) {
  for (int k = 0; k < static_cast<int>(std::lround(seconds / Simulation::kStep_s)); ++k)
    sim.step(controls);
  ASSERT_FALSE(sim.diverged()) << sim.divergence();
}

// Lets the autopilot drive until it starts `activity` (or 300 s pass).
void drive_until(Simulation& sim, HookAutopilot& pilot, const std::string& activity,
                 Evaluator* evaluator = nullptr) {
  for (int k = 0; k < 300000 && std::string(pilot.activity()) != activity; ++k) {
    const scene::Controls c = pilot.next(sim);
    sim.step(c);
    if (evaluator) evaluator->observe(sim, c);
  }
  ASSERT_EQ(std::string(pilot.activity()), activity);
  ASSERT_FALSE(sim.diverged()) << sim.divergence();
}

TEST(MhcHook, TheSlingerSlingsOnlyUnderTheHookAndTakesOffOnlyAPieceAtRest) {
  const ExerciseSettings exercise = hook_lift();
  Simulation sim(exercise.scenario);
  // the hook over the quay 20 m from the piece: the slinger cannot reach
  run(sim, 0.1, levers(sim, {{"sling", 1.0}}));
  EXPECT_FALSE(sim.machine().held_item());
  EXPECT_EQ(mhc(sim).slings_refused(), 1u);
  // plumb over its centre, 1 m above its top
  HookAutopilot pilot(exercise);
  drive_until(sim, pilot, "sling");
  run(sim, 0.1, levers(sim, {{"sling", 0.0}}));
  run(sim, 0.1, levers(sim, {{"sling", 1.0}}));
  ASSERT_EQ(sim.machine().held_item(), sim.container_body(0));
  EXPECT_EQ(mhc(sim).slings_refused(), 1u);
  // lifted: the piece hangs and the slinger will not take it off
  run(sim, 10.0, levers(sim, {{"hoist", 0.2}}));
  EXPECT_GT(sim.world().pose(sim.container_body(0)).position.z, 1.75 + 0.5);
  run(sim, 0.1, levers(sim, {{"sling", 0.0}}));
  run(sim, 0.1, levers(sim, {{"sling", 1.0}}));
  EXPECT_EQ(sim.machine().held_item(), sim.container_body(0));
  EXPECT_EQ(mhc(sim).slings_refused(), 2u);
  // set down again and resting: off
  run(sim, 14.0, levers(sim, {{"hoist", -0.2}}));
  EXPECT_NEAR(sim.world().pose(sim.container_body(0)).position.z, 1.75, 0.01);
  run(sim, 0.1, levers(sim, {{"sling", 0.0}}));
  run(sim, 0.1, levers(sim, {{"sling", 1.0}}));
  EXPECT_FALSE(sim.machine().held_item());
}

// The load on the falls over 5 s braked (the load's bounce on the ropes, ~0.7 s, averages out).
double mean_hoisted_load_n(Simulation& sim) {
  double sum = 0.0;
  constexpr int kSteps = 5000;
  for (int k = 0; k < kSteps; ++k) {
    sim.step(sim.control_table().neutral());
    sum += mhc(sim).hoisted_load_n();
  }
  return sum / kSteps;
}

TEST(MhcHook, ASlungPieceHangsItsWeightOnTheRopesAndTheHookCurveLimitsIt) {
  const ExerciseSettings exercise = hook_lift();
  Simulation sim(exercise.scenario);
  HookAutopilot pilot(exercise);
  drive_until(sim, pilot, "sling");
  run(sim, 5.0, sim.control_table().neutral());
  const double empty_n = mean_hoisted_load_n(sim);
  run(sim, 0.1, levers(sim, {{"sling", 1.0}}));
  ASSERT_TRUE(sim.machine().held_item());
  run(sim, 8.0, levers(sim, {{"hoist", 0.2}}));
  run(sim, 10.0, sim.control_table().neutral());  // braked
  const double piece_kg = exercise.scenario.containers[0].gross_mass_kg;
  // the piece's weight came onto the falls (the hook rose 1.6 m: 12.8 m less rope hangs, 57 kg of it)
  const double added_n = mean_hoisted_load_n(sim) - empty_n;
  EXPECT_NEAR(added_n, piece_kg * kG, 0.01 * piece_kg * kG);
  std::printf("the falls took %.2f kN of the piece's %.2f kN\n", added_n / 1000, piece_kg * kG / 1000);
  // the hook curve: 63 t to 12 m, 50 t at 25 m
  const double r = mhc(sim).radius_m();
  ASSERT_GT(r, 12.0);
  ASSERT_LT(r, 25.0);
  EXPECT_NEAR(mhc(sim).capacity_t(), 63.0 + (r - 12.0) / 13.0 * (50.0 - 63.0), 1e-9);
}

struct Attempt {
  Metrics metrics;
  Score score;
  bool finished = false;
  core::Vec3 placed_m;
};

Attempt attempt(const ExerciseSettings& exercise, bool drop_it = false) {
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  HookAutopilot pilot(exercise);
  const auto steps = static_cast<std::int64_t>(exercise.rules.time_limit_s / Simulation::kStep_s);
  for (std::int64_t k = 0; k < steps && !evaluator.finished(); ++k) {
    scene::Controls c = pilot.next(sim);
    // the bad operator lets the piece down at full speed onto its place
    if (drop_it && std::string(pilot.activity()) == "set down")
      c.value[static_cast<std::size_t>(sim.control_table().find("hoist"))] = -1.0;
    sim.step(c);
    evaluator.observe(sim, c);
    EXPECT_FALSE(sim.diverged());
  }
  return {evaluator.metrics(), evaluator.score(), evaluator.finished(),
          sim.world().pose(sim.container_body(0)).position};
}

TEST(MhcHook, TheAutopilotSetsThePieceDownGentlyOnItsPlace) {
  const ExerciseSettings exercise = hook_lift();
  const Attempt a = attempt(exercise);
  ASSERT_TRUE(a.finished);
  EXPECT_EQ(a.metrics.moves_completed, 1);
  EXPECT_TRUE(a.score.passed);
  const core::Vec3 target = exercise.moves[0].target_m;
  EXPECT_LT(std::hypot(a.placed_m.x - target.x, a.placed_m.y - target.y), exercise.moves[0].tolerance_m);
  EXPECT_NEAR(a.placed_m.z, target.z, 0.01);
  EXPECT_EQ(a.metrics.collisions, 0);
  EXPECT_EQ(a.metrics.hard_landings, 0);
  EXPECT_EQ(a.metrics.overloads, 0);
  EXPECT_EQ(a.metrics.limiter_trips, 0);
  EXPECT_EQ(a.metrics.pad_lift_offs, 0);
  ASSERT_EQ(a.metrics.landing_sway_m.size(), 2u) << "slung, then set down";
  EXPECT_LT(a.metrics.landing_sway_m[0], exercise.rules.sway_limit_m);
  EXPECT_LT(a.metrics.landing_sway_m[1], exercise.rules.sway_limit_m);
  EXPECT_LT(a.metrics.worst_landing_mps, 0.15);
  std::printf("hook lift: %.1f s, landing %.3f m/s, sway %.3f m, placed %.3f m off, score %.0f\n",
              a.metrics.time_s, a.metrics.worst_landing_mps, a.metrics.landing_sway_m[1],
              std::hypot(a.placed_m.x - target.x, a.placed_m.y - target.y), a.score.total);
}

TEST(MhcHook, LettingThePieceDownAtFullSpeedIsAHardLanding) {
  const ExerciseSettings exercise = hook_lift();
  const Attempt a = attempt(exercise, true);
  EXPECT_GE(a.metrics.hard_landings, 1);
  EXPECT_GT(a.metrics.worst_landing_mps, exercise.rules.hard_landing_mps);
  double points = 0.0;
  for (const Score::Deduction& d : a.score.deductions)
    if (d.reason == "hard landing") points += d.points;
  EXPECT_EQ(points, a.metrics.hard_landings * exercise.rules.points_hard_landing);
}

TEST(MhcHook, AKeyframeWithAPieceOnTheHookContinuesBitForBit) {
  const ExerciseSettings exercise = hook_lift();
  Simulation sim(exercise.scenario);
  HookAutopilot pilot(exercise);
  drive_until(sim, pilot, "to target");
  ASSERT_TRUE(sim.machine().held_item());
  const std::vector<std::uint8_t> keyframe = sim.save_state();
  const scene::Controls slewing = levers(sim, {{"slew", 0.6}, {"hoist", 0.3}});
  run(sim, 5.0, slewing);
  Simulation restored(exercise.scenario);
  restored.restore_state(keyframe);
  ASSERT_EQ(restored.machine().held_item(), restored.container_body(0));
  run(restored, 5.0, slewing);
  EXPECT_EQ(restored.state_hash(), sim.state_hash());
}

TEST(MhcHook, ATakeOverWithThePieceSlungCarriesItToItsPlace) {
  const ExerciseSettings exercise = hook_lift();
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  HookAutopilot trainee(exercise);
  drive_until(sim, trainee, "to target", &evaluator);
  const scene::Controls slewing = levers(sim, {{"slew", 0.5}});
  run(sim, 3.0, slewing);  // the trainee slews on, then the instructor takes over
  HookAutopilot instructor(exercise);
  instructor.resume(sim, evaluator.metrics().moves_completed, slewing);
  EXPECT_EQ(std::string(instructor.activity()), "lift");
  for (int k = 0; k < 200000 && !evaluator.finished(); ++k) {
    const scene::Controls c = instructor.next(sim);
    sim.step(c);
    evaluator.observe(sim, c);
  }
  EXPECT_TRUE(evaluator.finished());
  EXPECT_EQ(evaluator.metrics().moves_completed, 1);
}

// Left alone, the boom comes to rest on its luffing ropes: the rope's stretch counts its sag (the curved
// length), so the energy the ends put into the ropes' transverse waves is the energy the waves take out of
// the ends; with the chord's stretch, the boom bounced at 1.6 Hz for ever (5.0e-3 rad/s after 120 s). As
// built (the bounce the constructor's settling leaves: 5.3e-5 rad/s in the first 20 s) it comes to
// 6.2e-7 rad/s after 100 s; brought to rest before the first step, as an exercise starts now, it starts
// still and stays so.
TEST(MhcHook, TheBoomLeftAloneComesToRestOnItsRopes) {
  for (const bool as_built : {true, false}) {
    SCOPED_TRACE(as_built ? "as built" : "brought to rest");
    ScenarioSettings scenario = hook_lift().scenario;
    scenario.start_unsettled = as_built;
    Simulation sim(scenario);
    const scene::Controls neutral = sim.control_table().neutral();
    const MobileHarbourCrane& m = mhc(sim);
    struct Window {
      double boom_radps = 0.0, luff_min_n = 1e12, luff_max_n = 0.0, load_min_n = 1e12, load_max_n = 0.0;
    };
    std::vector<Window> windows(6);  // 20 s each
    for (Window& w : windows)
      for (int k = 0; k < 20000; ++k) {
        sim.step(neutral);
        w.boom_radps = std::max(w.boom_radps, std::abs(sim.world().hinge_rate(m.boom_hinge())));
        w.luff_min_n = std::min(w.luff_min_n, m.luffing_tension_n());
        w.luff_max_n = std::max(w.luff_max_n, m.luffing_tension_n());
        w.load_min_n = std::min(w.load_min_n, m.hoisted_load_n());
        w.load_max_n = std::max(w.load_max_n, m.hoisted_load_n());
      }
    ASSERT_FALSE(sim.diverged()) << sim.divergence();
    for (std::size_t n = 0; n < windows.size(); ++n)
      std::printf("%s %3zu-%3zu s: boom rate %.2e rad/s, luffing rope %.1f-%.1f kN, hook load %.2f-%.2f kN\n",
                  as_built ? "as built" : "at rest", n * 20, n * 20 + 20, windows[n].boom_radps,
                  windows[n].luff_min_n / 1e3, windows[n].luff_max_n / 1e3, windows[n].load_min_n / 1e3,
                  windows[n].load_max_n / 1e3);
    const Window& first = windows.front();
    const Window& last = windows.back();
    if (as_built) {
      EXPECT_LT(first.boom_radps, 1e-3);  // it starts near its static equilibrium
      EXPECT_LT(last.boom_radps, 1e-6);   // the 40 m boom's head moving under 0.04 mm/s
    } else {
      for (const Window& w : windows)
        EXPECT_LT(w.boom_radps, 3e-5);
    }
    EXPECT_LT(last.boom_radps, 1e-4);
    EXPECT_LT(last.luff_max_n - last.luff_min_n, 0.01 * last.luff_max_n);  // never slack, hardly moving
    EXPECT_LT(last.load_max_n - last.load_min_n, 0.01 * last.load_max_n);
  }
}

// The hook lift with the boom at `boom_deg`, in still air, nothing scripted.
ScenarioSettings hook_lift_in_still_air(double boom_deg) {
  ScenarioSettings scenario = hook_lift().scenario;
  scenario.weather.wind_mean_mps = 0.0;
  scenario.weather.turbulence_intensity = 0.0;
  scenario.events.clear();
  scenario.lift_events.clear();
  scenario.machine.as<MhcSetup>().start.boom_rad = boom_deg * std::numbers::pi / 180.0;
  return scenario;
}

// The boom's bounce on its luffing ropes decays at every boom angle it works at, 30-80 degrees: as built (the
// bounce its constructor's settling leaves), left alone in still air, the peak boom rate falls by a
// logarithmic decrement between 0.02 and 0.3 per cycle over the first 20 s (the ropes' strain-rate and
// transverse damping, ~1-3 % of critical), and the luffing rope never goes slack. Before the rope's stretch
// counted its sag, the bounce at 66 degrees never decayed and at 75 degrees the rope went slack every cycle.
TEST(MhcHook, TheBoomBounceDecaysAtEveryBoomAngle) {
  for (const double boom_deg : {30.0, 46.0, 60.0, 66.0, 75.0, 80.0}) {
    SCOPED_TRACE(boom_deg);
    ScenarioSettings scenario = hook_lift_in_still_air(boom_deg);
    scenario.start_unsettled = true;
    Simulation sim(scenario);
    const scene::Controls neutral = sim.control_table().neutral();
    const MobileHarbourCrane& m = mhc(sim);
    double luff_min_n = 1e12, luff_max_n = 0.0, previous_rate = 0.0;
    std::vector<double> peaks(4, 0.0);  // 5 s each
    int sign_changes = 0;
    for (int k = 0; k < 20000; ++k) {
      sim.step(neutral);
      const double rate = sim.world().hinge_rate(m.boom_hinge());
      sign_changes += k > 0 && (rate > 0.0) != (previous_rate > 0.0);
      previous_rate = rate;
      peaks[static_cast<std::size_t>(k / 5000)] =
          std::max(peaks[static_cast<std::size_t>(k / 5000)], std::abs(rate));
      luff_min_n = std::min(luff_min_n, m.luffing_tension_n());
      luff_max_n = std::max(luff_max_n, m.luffing_tension_n());
    }
    ASSERT_FALSE(sim.diverged()) << sim.divergence();
    const double cycles_per_s = sign_changes / 2.0 / 20.0;
    const double decrement = std::log(peaks[0] / peaks[3]) / (15.0 * cycles_per_s);
    std::printf("boom at %.0f deg: bounce %.2f Hz, log decrement %.3f per cycle, luffing rope %.1f-%.1f kN\n",
                boom_deg, cycles_per_s, decrement, luff_min_n / 1e3, luff_max_n / 1e3);
    EXPECT_GT(decrement, 0.02);
    EXPECT_LT(decrement, 0.3);
    EXPECT_GT(luff_min_n, 0.9 * luff_max_n);  // taut throughout, hardly moving
  }
}

// The hook's swing after a slew decays at every boom angle, 30-80 degrees, in still air: the ropes roll on
// and off the boom head's sheaves as the hook swings, and their bending hysteresis (1 % of the tension per
// bend, half the 2 % a steel wire rope loses per sheave passage) takes energy every cycle. Without it the
// swing's logarithmic decrement was 0.0006 per cycle at 2 cm and 0.008 at 4.6 m (the air's drag only).
TEST(MhcHook, TheHookSwingDecaysAtEveryBoomAngle) {
  for (const double boom_deg : {30.0, 46.0, 66.0, 80.0}) {
    SCOPED_TRACE(boom_deg);
    Simulation sim(hook_lift_in_still_air(boom_deg));
    const MobileHarbourCrane& m = mhc(sim);
    run(sim, 2.0, levers(sim, {{"slew", 0.4}}));  // a short slew sets the hook swinging
    run(sim, 15.0, sim.control_table().neutral());
    // the swing along its larger horizontal axis: the hook block's distance from its mean, peak per half
    // cycle
    std::vector<core::Vec3> track;
    for (int k = 0; k < 90000; ++k) {
      sim.step(sim.control_table().neutral());
      track.push_back(sim.world().pose(m.block_body()).position);
    }
    ASSERT_FALSE(sim.diverged()) << sim.divergence();
    core::Vec3 mean, spread;
    for (const core::Vec3& p : track)
      mean += p * (1.0 / static_cast<double>(track.size()));
    for (const core::Vec3& p : track)
      spread += core::Vec3{(p.x - mean.x) * (p.x - mean.x), (p.y - mean.y) * (p.y - mean.y), 0.0};
    const bool along_x = spread.x > spread.y;
    std::vector<double> peaks;  // the largest distance between successive crossings of the mean
    double peak = 0.0, previous = 0.0;
    for (const core::Vec3& p : track) {
      const double off = along_x ? p.x - mean.x : p.y - mean.y;
      if ((off > 0.0) != (previous > 0.0) && peak > 0.0) peaks.push_back(std::exchange(peak, 0.0));
      peak = std::max(peak, std::abs(off));
      previous = off;
    }
    peaks.erase(peaks.begin());  // the first from the window's start, not a whole half cycle
    ASSERT_GE(peaks.size(), 6u);
    const double cycles = static_cast<double>(peaks.size() - 1) / 2.0;
    const double decrement = std::log(peaks.front() / peaks.back()) / cycles;
    std::printf(
        "boom at %.0f deg: hook swing %.3f m -> %.3f m over %.1f cycles, log decrement %.3f per cycle\n",
        boom_deg, peaks.front(), peaks.back(), cycles, decrement);
    EXPECT_GT(decrement, 0.02);
    EXPECT_LT(decrement, 0.3);
  }
}

}  // namespace
}  // namespace harbour::sim
