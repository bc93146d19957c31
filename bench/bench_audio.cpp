// The station's sound: the cost of one 10 ms block with every source of the busiest machine playing (the MHC
// working its grab in wind and rain: its drives, engine, pouring, alarms, impacts and the ambience), from
// the snapshot to the mixed output. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "harbour/audio/AudioOut.h"
#include "harbour/audio/SoundFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/sim/Simulation.h"

namespace harbour {
namespace {

struct BusyScene {
  scene::SceneDescription scene;
  std::unique_ptr<scene::Snapshot> snapshot = std::make_unique<scene::Snapshot>();
  int material_t = -1;
  BusyScene() {
    const sim::ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_coal_discharge.yaml");
    sim::Simulation simulation(e.scenario);
    scene = simulation.scene();
    simulation.write_snapshot(*snapshot);
    for (std::size_t k = 0; k < scene.indicators.size(); ++k) {
      if (scene.indicators[k] == "limiter_stop" || scene.indicators[k] == "horn")
        snapshot->indicators[k] = 1.0;
      if (scene.indicators[k] == "grab_material_t") material_t = static_cast<int>(k);
    }
    snapshot->wind_mps = {15.0, 3.0, 0.0};
    snapshot->rain_mm_per_h = 20.0;
  }
  // block k: every drive moving under load, the grab pouring, a knock every 100 ms
  void advance(int k) {
    scene::Snapshot& s = *snapshot;
    s.step += 10;
    s.time_s += 0.01;
    for (int d = 0; d < s.drive_count; ++d)
      s.drives[static_cast<std::size_t>(d)] = {0.7 + 0.2 * std::sin(0.05 * k + d), 0.6};
    s.indicators[static_cast<std::size_t>(material_t)] = 20.0 - 0.02 * (k % 1000);
    if (k % 10 == 0) {
      s.knocks[static_cast<std::size_t>(s.knocks_total % scene::kMaxKnocks)] = {s.step - 3, 3000.0, 0.3,
                                                                                s.cab.pose.position};
      ++s.knocks_total;
    }
  }
};

void sound_block(benchmark::State& state, audio::Speakers speakers) {
  BusyScene busy;
  audio::AudioSettings settings;
  settings.speakers = speakers;
  const audio::SoundSettings sounds = audio::load_shipped_sounds(HARBOUR_DATA_DIR, sim::machine_kinds());
  audio::SoundScape scape(busy.scene, sounds);
  const std::unique_ptr<audio::AudioOut> out = audio::AudioOut::loopback(settings);
  std::vector<float> mixed(audio::SoundScape::kBlockFrames * static_cast<std::size_t>(out->channels()));
  int k = 0;
  for (auto _ : state) {
    busy.advance(k++);
    scape.update(*busy.snapshot);
    out->play(scape);
    out->render(mixed);
    benchmark::DoNotOptimize(mixed.data());
  }
  state.counters["sources"] = static_cast<double>(scape.source_count());
  state.counters["share_of_a_core"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 0.01,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_SoundBlockSpeakers(benchmark::State& state) {
  sound_block(state, audio::Speakers::kStereo);
}
void BM_SoundBlockHeadphones(benchmark::State& state) {
  sound_block(state, audio::Speakers::kHeadphones);
}
void BM_SoundBlockSurround(benchmark::State& state) {
  sound_block(state, audio::Speakers::kSurround51);
}
BENCHMARK(BM_SoundBlockSpeakers)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SoundBlockHeadphones)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SoundBlockSurround)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
