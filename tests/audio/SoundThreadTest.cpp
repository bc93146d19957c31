// The station's sound thread on a real OpenAL output device: OpenAL Soft's wave-writer backend (chosen by
// its configuration file before the library starts) plays into a file, so no sound card is needed.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>
#include <vector>

#include "harbour/audio/SoundFile.h"
#include "harbour/audio/SoundThread.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/sim/Simulation.h"

namespace harbour::audio {
namespace {

namespace fs = std::filesystem;

TEST(SoundThread, PlaysTheNewestSnapshotOnTheOutputDeviceAndMutes) {
  const fs::path folder = fs::temp_directory_path() / "harbour_sound_thread";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const fs::path played = folder / "played.wav";
  std::ofstream(folder / "alsoft.conf")
      << "[general]\ndrivers=wave\n[wave]\nfile=" << played.string() << "\n";
  setenv("ALSOFT_CONF", (folder / "alsoft.conf").c_str(), 1);

  const sim::ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/rtg_gantry_move.yaml");
  sim::Simulation simulation(e.scenario);
  auto snapshot = std::make_unique<scene::Snapshot>();
  simulation.write_snapshot(*snapshot);
  snapshot->rain_mm_per_h = 30.0;  // and its generator set idling
  AudioSettings settings;
  settings.speakers = Speakers::kHeadphones;
  {
    SoundThread sound(simulation.scene(), load_shipped_sounds(HARBOUR_DATA_DIR, sim::machine_kinds()),
                      settings, {}, [&] { return snapshot.get(); });
    EXPECT_NE(sound.describe().find("HRTF"), std::string::npos) << sound.describe();
    // it keeps rendering as the device plays (the wave writer plays in real time)
    for (int k = 0; k < 500 && sound.blocks() < 30; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_GE(sound.blocks(), 30);
    sound.set_muted(true);
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
  }
  // the file holds what was played (the wave writer's 32-bit floats, stereo): sound, then silence once muted
  std::ifstream in(played, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t data = bytes.find("data");
  ASSERT_NE(data, std::string::npos);
  std::vector<float> samples((bytes.size() - data - 8) / sizeof(float));
  std::memcpy(samples.data(), bytes.data() + data + 8, samples.size() * sizeof(float));
  ASSERT_GT(samples.size(), 2u * 44100u / 2u);  // half a second at least
  const auto rms = [&](std::size_t from, std::size_t to) {
    double sum = 0.0;
    for (std::size_t n = from; n < to; ++n)
      sum += static_cast<double>(samples[n]) * samples[n];
    return std::sqrt(sum / static_cast<double>(to - from));
  };
  const std::size_t tenth = 2 * 4410;                            // 0.1 s of stereo at the device's 44.1 kHz
  EXPECT_GT(rms(tenth, 3 * tenth), 1e-3);                        // rain and the idling generator set
  EXPECT_LT(rms(samples.size() - tenth, samples.size()), 1e-6);  // muted
}

}  // namespace
}  // namespace harbour::audio
