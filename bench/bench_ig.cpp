// The image generator: frames per second of the STS deck exercise with everything on (ten boxes, the feeder,
// trucks, the crane and its ropes, the harbour's scenery and lamps, sun shadows, the FFT wind sea in 8 m/s
// of wind) drawn headless (EGL) from the cab (with and without its spreader camera inset) and the chase view,
// dry and in rain, under 4 oktas of cloud, with the renderer's default surfaces and with surface detail; the
// analytic sky's colours; and the cost of re-meshing one changed bulk tile. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <osg/Image>

#include <cmath>
#include <optional>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/core/Rng.h"
#include "harbour/ig/ImageGenerator.h"
#include "harbour/ig/Sky.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/MachineRegistry.h"

namespace harbour {
namespace {

void BM_Frame(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0)), height = static_cast<int>(state.range(1));
  const sim::ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_bay12_deck.yaml");
  sim::Simulation simulation(exercise.scenario);
  sim::GantryAutopilot pilot(exercise);
  sim::InstructorCommand wind;
  wind.kind = sim::InstructorCommand::Kind::kSetWind;
  wind.wind_mean_mps = 8.0;
  simulation.command(wind);
  if (state.range(5) > 0) {  // rain [mm/h]: the wet quay's own shading
    sim::InstructorCommand rain;
    rain.kind = sim::InstructorCommand::Kind::kSetRain;
    rain.value = static_cast<double>(state.range(5));
    simulation.command(rain);
  }
  if (state.range(7) > 0) {  // cloud [oktas]: the lit programs' shade under it
    sim::InstructorCommand cloud;
    cloud.kind = sim::InstructorCommand::Kind::kSetCloud;
    cloud.value = static_cast<double>(state.range(7));
    simulation.command(cloud);
  }
  while (simulation.time_s() < 30.0)
    simulation.step(pilot.next(simulation));  // a box on the spreader
  const ig::Looks looks = ig::load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  // samples per pixel: -1 the renderer's default (none on a software renderer)
  const std::optional<int> samples =
      state.range(4) < 0 ? std::nullopt : std::optional<int>(static_cast<int>(state.range(4)));
  ig::ImageGenerator generator(simulation.scene(), looks.visuals, width, height, samples);
  if (state.range(6) >= 0) generator.set_surface_detail(state.range(6) != 0);  // -1: the renderer's default
  generator.use(looks);
  ig::View view;
  view.kind = state.range(2) == 0 ? ig::View::Kind::kCab : ig::View::Kind::kChase;
  view.from_sight = view.fov_from_sight = true;  // the desktop station's: the machine's design view
  view.yaw_rad = view.pitch_rad = 0.0;
  view.insets = state.range(3) != 0;  // the cab's: the spreader camera
  generator.set_view(view);
  auto snapshot = std::make_unique<scene::Snapshot>();
  for (auto _ : state) {
    state
        .PauseTiming();  // the scene moves between frames; the simulation's time is not the image generator's
    for (int k = 0; k < 16; ++k)
      simulation.step(pilot.next(simulation));
    state.ResumeTiming();
    simulation.write_snapshot(*snapshot);
    generator.update(*snapshot);
    benchmark::DoNotOptimize(generator.render().data());
  }
  state.counters["fps"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["insets"] =
      static_cast<double>(view.kind == ig::View::Kind::kCab && view.insets ? generator.insets().size() : 0);
  state.counters["samples"] = generator.multisamples();
  state.counters["detail"] = generator.surface_detail() ? 1.0 : 0.0;
  state.SetLabel(generator.renderer());
}
BENCHMARK(BM_Frame)
    ->Args({1280, 720, 0, 1, -1, 0, -1, 0})
    ->Args({1280, 720, 0, 0, -1, 0, -1, 0})
    ->Args({1280, 720, 1, 0, -1, 0, -1, 0})
    ->Args({1280, 720, 0, 1, -1, 10, -1, 0})
    ->Args({1280, 720, 1, 0, -1, 10, -1, 0})
    ->Args({1920, 1080, 0, 1, -1, 0, -1, 0})
    ->Args({1920, 1080, 1, 0, -1, 0, -1, 0})
    ->Args({1280, 720, 0, 1, 4, 0, -1, 0})
    ->Args({1280, 720, 1, 0, 4, 0, -1, 0})
    ->Args({1280, 720, 0, 1, -1, 0, 1, 0})
    ->Args({1280, 720, 1, 0, -1, 0, 1, 0})
    ->Args({1280, 720, 0, 1, -1, 0, -1, 4})
    ->Args({1280, 720, 1, 0, -1, 0, -1, 4})
    ->ArgNames({"w", "h", "chase", "insets", "samples", "rain", "detail", "cloud"})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0)
    ->UseRealTime();  // llvmpipe may draw on threads of its own

// The analytic sky's work on the CPU each frame: the image generator builds Preetham's sky for the sun once
// (its lights, the horizon's mean) and colours the dome's 833 vertices and the 900 stars.
void BM_SkyColours(benchmark::State& state) {
  double t_h = 6.0;
  for (auto _ : state) {
    t_h = t_h > 20.0 ? 6.0 : t_h + 0.01;  // the sun moving through a day
    const double hour_angle = (t_h - 12.0) / 24.0 * 6.283185307179586;
    const core::Vec3 to_sun{-std::sin(hour_angle), -0.64 * std::cos(hour_angle), 0.77 * std::cos(hour_angle)};
    const ig::Daylight daylight(to_sun);
    double sum = daylight.horizon().x;
    for (int n = 0; n < 833 + 900; ++n) {
      const double elevation = -0.2 + 1.77 * (n % 17) / 16.0, azimuth = 0.13 * n;
      sum += daylight
                 .sky({std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                       std::sin(elevation)})
                 .y;
    }
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_SkyColours)->Unit(benchmark::kMicrosecond);

// One bulk tile (32 x 32 cells) changed per iteration on a 1024^2 grid holding a heap: publish copies it, the
// image generator re-meshes it (no frame drawn).
void BM_BulkTileRemesh(benchmark::State& state) {
  bulk::Material coal;
  coal.name = "coal";
  coal.bulk_density_kg_m3 = 850.0;
  coal.angle_of_repose_rad = 0.6;
  coal.flow_friction_rad = 0.51;
  bulk::BulkWorld world(coal, bulk::BulkWorldSettings{});
  world.add_grid({1024, 1024, 0.05}, {core::Mat3::identity(), {-25.6, -25.6, 0.0}});
  world.add_heap(0, 25.6, 25.6, 400.0);
  scene::BulkView view;
  bulk::publish(world, view);
  scene::SceneDescription scene;
  ig::ImageGenerator generator(scene, {}, 64, 64);
  generator.update_bulk(view);
  core::Rng rng(3);
  const long before = generator.bulk_tiles_meshed();
  for (auto _ : state) {
    world.grid(0).add_volume(static_cast<int>(rng.below(1024)), static_cast<int>(rng.below(1024)), 1e-6);
    bulk::publish(world, view);
    generator.update_bulk(view);
  }
  state.counters["tiles_per_iteration"] =
      static_cast<double>(generator.bulk_tiles_meshed() - before) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_BulkTileRemesh)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
