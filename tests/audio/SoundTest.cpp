// The station's sound as a trainee hears it, rendered through OpenAL Soft's loopback device (no sound card)
// from the machines' real scenes and the shipped sound data, and measured: each sound follows the physical
// quantity it is made from, alarms sound exactly while their condition holds, a power failure silences the
// machine, and the same snapshots give the same samples.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>

#include "audio/AudioAnalysis.h"
#include "harbour/audio/AudioOut.h"
#include "harbour/audio/SoundFile.h"
#include "harbour/io/DataError.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/sim/Simulation.h"

namespace harbour::audio {
namespace {

using test::channel;
using test::rms;

const SoundSettings& shipped_sounds() {
  static const SoundSettings sounds = load_shipped_sounds(HARBOUR_DATA_DIR, sim::machine_kinds());
  return sounds;
}

/// A machine's scene and its first snapshot, from a shipped exercise.
struct Scene {
  scene::SceneDescription description;
  std::unique_ptr<scene::Snapshot> first = std::make_unique<scene::Snapshot>();
  int drive(const std::string& name) const {
    return static_cast<int>(std::find(description.drives.begin(), description.drives.end(), name) -
                            description.drives.begin());
  }
  int indicator(const std::string& name) const {
    return static_cast<int>(std::find(description.indicators.begin(), description.indicators.end(), name) -
                            description.indicators.begin());
  }
};

Scene scene_of(const std::string& exercise) {
  const sim::ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/" + exercise + ".yaml");
  sim::Simulation simulation(e.scenario);
  Scene s;
  s.description = simulation.scene();
  simulation.write_snapshot(*s.first);
  return s;
}

/// The machine's sounds alone (no ambience) over `seconds`, each 10 ms block's snapshot set by `at(t)`.
std::vector<float> render(const Scene& scene, double seconds,
                          const std::function<void(scene::Snapshot&, double)>& at,
                          const AudioSettings& audio = {}, bool ambience = false,
                          const SoundSettings& sounds = shipped_sounds(),
                          const scene::RadioScript& radio = {}) {
  OfflineMix mix(scene.description, sounds, audio, ambience);
  mix.scape().set_radio_script(radio);
  auto s = std::make_unique<scene::Snapshot>(*scene.first);
  const auto blocks = static_cast<int>(std::lround(seconds * 100.0));
  for (int k = 1; k <= blocks; ++k) {
    s->step = scene.first->step + 10 * k;
    s->time_s = scene.first->time_s + 0.01 * k;
    at(*s, 0.01 * k);
    mix.add_block(*s);
  }
  return mix.samples();
}

void set_drive(scene::Snapshot& s, int index, double speed, double load) {
  s.drives[static_cast<std::size_t>(index)] = {speed, load};
}

TEST(Sound, TheHoistsFundamentalFollowsItsDrumSpeed) {
  // the STS's hoist motors: their magnetic tone at rated_hz times the drum's speed (100 Hz at rated)
  const Scene sts = scene_of("sts_discharge");
  const int hoist = sts.drive("hoist");
  for (const double speed : {0.3, 0.6, 1.0}) {
    const std::vector<float> out =
        render(sts, 1.0, [&](scene::Snapshot& s, double) { set_drive(s, hoist, speed, 0.5); });
    const std::vector<double> left = channel(out, 2, 0);
    EXPECT_NEAR(test::strongest_tone_hz(left, 0.2, 1.0, 15.0, 400.0), 100.0 * speed, 1.5)
        << "speed " << speed;
  }
}

TEST(Sound, TheHoistsFundamentalRisesAsTheSimulatedDrumSpeedsUp) {
  // the whole chain: the STS simulated with its hoist lever at half and then full, its published drum speed,
  // the tone heard in the cab
  const sim::ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  sim::Simulation simulation(e.scenario);
  scene::Controls controls = simulation.control_table().neutral();
  const auto lever = static_cast<std::size_t>(simulation.control_table().find("hoist"));
  const scene::SceneDescription scene = simulation.scene();
  OfflineMix mix(scene, shipped_sounds(), {}, false);
  const auto hoist = static_cast<std::size_t>(std::find(scene.drives.begin(), scene.drives.end(), "hoist") -
                                              scene.drives.begin());
  auto snapshot = std::make_unique<scene::Snapshot>();
  std::vector<double> published;
  for (int step = 1; step <= 8000; ++step) {
    controls.value[lever] = step < 4000 ? -0.5 : -1.0;  // lowering into the hold
    simulation.step(controls);
    if (step % 10 != 0) continue;
    simulation.write_snapshot(*snapshot);
    mix.add_block(*snapshot);
    published.push_back(-snapshot->drives[hoist].speed);
  }
  const std::vector<double> left = channel(mix.samples(), 2, 0);
  const double half = published[390], full = published[790];  // the speeds at 3.9 s and 7.9 s
  EXPECT_GT(full, 1.6 * half);
  const double half_hz = test::strongest_tone_hz(left, 3.0, 3.9, 15.0, 400.0);
  const double full_hz = test::strongest_tone_hz(left, 7.0, 7.9, 15.0, 400.0);
  EXPECT_NEAR(half_hz, 100.0 * half, 2.0);
  EXPECT_NEAR(full_hz, 100.0 * full, 2.0);
}

TEST(Sound, ADieselIsLouderUnderLoad) {
  const Scene tractor = scene_of("tractor_free_practice");
  const int engine = tractor.drive("engine");
  std::vector<double> level;
  for (const double load : {0.1, 0.5, 1.0}) {
    const std::vector<float> out =
        render(tractor, 1.0, [&](scene::Snapshot& s, double) { set_drive(s, engine, 0.5, load); });
    level.push_back(rms(channel(out, 2, 0), 0.2, 1.0));
  }
  // each step of load raises it by more than 2 dB
  EXPECT_GT(level[1], 1.26 * level[0]);
  EXPECT_GT(level[2], 1.26 * level[1]);
  // and the firing frequency follows the engine speed: 6 cylinders at 1475 rpm fire at 73.75 Hz
  const std::vector<float> out =
      render(tractor, 1.0, [&](scene::Snapshot& s, double) { set_drive(s, engine, 0.5, 0.5); });
  EXPECT_NEAR(test::strongest_tone_hz(channel(out, 2, 0), 0.2, 1.0, 40.0, 100.0), 73.75, 1.0);
}

TEST(Sound, ALandingsKnockFollowsItsImpulse) {
  // three landings 0.5 s apart at one place, of 2.5, 5 and 10 kN s: each knock's peak twice the last
  const Scene sts = scene_of("sts_discharge");
  const core::Vec3 spot = sts.first->cab.pose.to_parent(sts.first->cab.eye_m) + core::Vec3{0.0, 0.0, -15.0};
  const double impulses[] = {2500.0, 5000.0, 10000.0};
  const std::vector<float> out = render(sts, 1.6, [&](scene::Snapshot& s, double t) {
    const int due = static_cast<int>(std::floor((t - 0.095) / 0.5)) + 1;  // at 0.1, 0.6 and 1.1 s
    while (s.knocks_total < std::min(due, 3)) {
      s.knocks[static_cast<std::size_t>(s.knocks_total)] = {s.step - 5, impulses[s.knocks_total], 0.3, spot};
      ++s.knocks_total;
    }
  });
  const std::vector<double> left = channel(out, 2, 0);
  const double quiet = test::peak(left, 0.0, 0.1);
  const double first = test::peak(left, 0.1, 0.6), second = test::peak(left, 0.6, 1.1),
               third = test::peak(left, 1.1, 1.6);
  EXPECT_LT(quiet, 1e-6);
  EXPECT_NEAR(second / first, 2.0, 0.2);
  EXPECT_NEAR(third / second, 2.0, 0.2);
}

TEST(Sound, AnAlarmSoundsExactlyWhileItsConditionHolds) {
  // the MHC's limiter alarm (950/1250 Hz beeps, 0.25 s on, 0.05 s off) while the limiter stops a motion,
  // from 1.0 s to 2.5 s
  const Scene mhc = scene_of("mhc_hook_lift");
  const int limiter = mhc.indicator("limiter_stop");
  const std::vector<float> out = render(mhc, 3.5, [&](scene::Snapshot& s, double t) {
    s.indicators[static_cast<std::size_t>(limiter)] = t > 1.0 + 1e-9 && t <= 2.5 + 1e-9 ? 1.0 : 0.0;
  });
  const std::vector<double> left = channel(out, 2, 0);
  const auto alarm = [&](double from, double to) {
    return std::max(test::tone_amplitude(left, from, to, 950.0),
                    test::tone_amplitude(left, from, to, 1250.0));
  };
  const double sounding = alarm(1.1, 1.3);
  EXPECT_GT(sounding, 1e-3);
  EXPECT_LT(alarm(0.0, 0.99), 1e-2 * sounding);  // before: nothing at its pitches (-40 dB; the engine idles)
  EXPECT_LT(alarm(2.55, 3.5), 1e-2 * sounding);  // after: gone within 50 ms
  EXPECT_GT(alarm(1.02, 1.07), 0.5 * sounding);  // on from its first block (a block's latency, 5 ms attack)
}

TEST(Sound, TheAnemometersAlarmSoundsWhileTheWindIsPastTheCranesLimit) {
  // the STS's wind warning (2.4 kHz beeps) past its in-service limit of 20 m/s: 15 m/s, then 22 from 1 s
  const Scene sts = scene_of("sts_discharge");
  const std::vector<float> out = render(sts, 2.5, [](scene::Snapshot& s, double t) {
    s.wind_mps = {t > 1.0 + 1e-9 ? 22.0 : 15.0, 0.0, 0.0};
  });
  const std::vector<double> left = channel(out, 2, 0);
  const double calm = test::tone_amplitude(left, 0.2, 1.0, 2400.0),
               warning = test::tone_amplitude(left, 1.2, 2.5, 2400.0);
  EXPECT_GT(warning, 1e-3);
  EXPECT_LT(calm, 1e-2 * warning);
}

TEST(Sound, AFlipperClunksOnceWhenItReachesItsStop) {
  // the STS's flipper 1 folds down from 0.5 s to 1.5 s: no clunk on its way, one as it lands on its stop
  const Scene sts = scene_of("sts_discharge");
  const int flipper = sts.indicator("flipper_1");
  const std::vector<float> out = render(sts, 2.5, [&](scene::Snapshot& s, double t) {
    s.indicators[static_cast<std::size_t>(flipper)] = std::clamp(t - 0.5, 0.0, 1.0);
  });
  const std::vector<double> left = channel(out, 2, 0);
  // its ring (1150 Hz) is not among the other sounds of the idle STS
  EXPECT_LT(test::tone_amplitude(left, 0.2, 1.49, 1150.0), 1e-5);
  EXPECT_GT(test::tone_amplitude(left, 1.5, 1.7, 1150.0), 1e-4);
}

TEST(Sound, APowerFailureSilencesTheMachine) {
  // every drive of the RTG at full speed and load, its horn sounding; the supply fails at 1 s
  const Scene rtg = scene_of("rtg_gantry_move");
  const int horn = rtg.indicator("horn");
  const std::vector<float> out = render(rtg, 2.0, [&](scene::Snapshot& s, double t) {
    for (int d = 0; d < s.drive_count; ++d)
      set_drive(s, d, 1.0, 1.0);
    s.indicators[static_cast<std::size_t>(horn)] = 1.0;
    s.power_off = t > 1.0 + 1e-9;
  });
  const std::vector<double> left = channel(out, 2, 0);
  EXPECT_GT(rms(left, 0.5, 1.0), 0.01);
  // the brakes set with a clunk as the drives stop, then nothing (below -80 dB of full scale)
  EXPECT_GT(test::peak(left, 1.0, 1.1), 0.01);
  EXPECT_LT(rms(left, 1.6, 2.0), 1e-4);
}

TEST(Sound, TheSameSnapshotsGiveTheSameSamplesBitForBit) {
  // the reach stacker working in wind and rain, heard through the HRTF, twice
  const Scene stacker = scene_of("reach_stacker_stack");
  const auto work = [&](scene::Snapshot& s, double t) {
    set_drive(s, 0, 0.5 + 0.5 * std::sin(t), 0.7);
    set_drive(s, 1, std::sin(3.0 * t), 0.6);
    s.wind_mps = {14.0 + 3.0 * std::sin(0.7 * t), 2.0, 0.0};
    s.rain_mm_per_h = 20.0;
  };
  AudioSettings headphones;
  headphones.speakers = Speakers::kHeadphones;
  const std::vector<float> a = render(stacker, 2.0, work, headphones, true);
  const std::vector<float> b = render(stacker, 2.0, work, headphones, true);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  EXPECT_GT(rms(channel(a, 2, 0), 0.5, 2.0), 1e-3);
}

TEST(Sound, ASoundOnTheLeftIsLouderInTheLeftEar) {
  // a knock 10 m to the operator's left, then one 10 m to the right, on speakers and through the HRTF
  const Scene sts = scene_of("sts_discharge");
  const scene::Snapshot& first = *sts.first;
  for (const Speakers speakers : {Speakers::kStereo, Speakers::kHeadphones}) {
    AudioSettings audio;
    audio.speakers = speakers;
    std::array<double, 2> left_over_right{};
    for (const double side : {1.0, -1.0}) {
      const core::Vec3 beside = first.cab.pose.to_parent(first.cab.eye_m + core::Vec3{0.0, 10.0 * side, 0.0});
      const std::vector<float> out = render(
          sts, 0.5,
          [&](scene::Snapshot& s, double t) {
            if (t > 0.095 && s.knocks_total == 0)
              s.knocks[0] = {s.step, 5000.0, 0.3, beside}, s.knocks_total = 1;
          },
          audio);
      left_over_right[side > 0 ? 0 : 1] =
          rms(channel(out, 2, 0), 0.0, 0.5) / rms(channel(out, 2, 1), 0.0, 0.5);
    }
    const char* how = speakers == Speakers::kStereo ? "stereo" : "HRTF";
    // louder on its side by more than 2.3 dB (speakers pan it wholly; the HRTF's 70 Hz thump is heard by
    // both ears, its ringing by the nearer: 3.4 dB)
    EXPECT_GT(left_over_right[0], 1.3) << how;
    EXPECT_LT(left_over_right[1], 1.0 / 1.3) << how;
  }
}

TEST(Sound, TheSignallersCallIsHeardAtItsMomentInTheSpeechBand) {
  // the exercise's script: "hoist up slowly" at 1 s, on the cab's radio alone
  SoundSettings radio_only;
  for (const SoundSource& s : shipped_sounds().ambience)
    if (s.kind == SourceKind::kRadio) radio_only.ambience.push_back(s);
  ASSERT_EQ(radio_only.ambience.size(), 1u);
  const Scene sts = scene_of("sts_discharge");
  scene::RadioScript script;
  script.calls = {{1.0, "hoist up slowly"}};
  const std::vector<float> out = render(
      sts, 3.5, [](scene::Snapshot&, double) {}, {}, true, radio_only, script);
  const std::vector<double> left = channel(out, 2, 0);
  EXPECT_LT(rms(left, 0.0, 1.0), 1e-7);  // nothing before its moment
  EXPECT_GT(rms(left, 1.2, 2.0), 0.02);  // the words
  // a radio's voice: its energy in the speech band, little below 200 Hz or above 4 kHz
  double band = 0.0, outside = 0.0;
  for (double f = 50.0; f <= 8000.0; f += 25.0) {
    const double a = test::tone_amplitude(left, 1.1, 2.5, f);
    (f >= 300.0 && f <= 3000.0 ? band : outside) += a * a;
  }
  EXPECT_GT(band, 5.0 * outside);
  // the instructor's call in another language, heard from the next block
  OfflineMix mix(sts.description, radio_only, {}, true);
  scene::RadioScript german;
  german.language = "de";
  mix.scape().set_radio_script(german);
  auto s = std::make_unique<scene::Snapshot>(*sts.first);
  mix.add_block(*s);
  EXPECT_TRUE(mix.scape().say("langsam heben"));
  for (int k = 0; k < 100; ++k)
    mix.add_block(*s);
  EXPECT_GT(rms(channel(mix.samples(), 2, 0), 0.2, 1.0), 0.02);
  // a language espeak-ng has no voice for is refused by name
  scene::RadioScript unknown;
  unknown.language = "xx";
  unknown.calls = {{1.0, "stop"}};
  try {
    mix.scape().set_radio_script(unknown);
    FAIL() << "accepted";
  } catch (const AudioError& e) {
    EXPECT_NE(std::string(e.what()).find("'xx'"), std::string::npos) << e.what();
  }
}

// Every shipped exercise's machine has sounds of its own that bind to its scene: no machine is silent.
TEST(Sound, EveryMachinesSoundsBindToItsScene) {
  std::set<std::string> kinds;
  for (const auto& file : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/exercises")) {
    const Scene scene = scene_of(file.path().stem().string());
    kinds.insert(scene.description.machine);
    const SoundScape scape(scene.description, shipped_sounds(), false);
    EXPECT_GE(scape.source_count(), 5u) << file.path().filename();
  }
  EXPECT_EQ(kinds.size(), sim::machine_kinds().size());
}

TEST(Sound, ASoundNamingWhatTheMachineLacksIsRefusedByName) {
  SoundSettings sounds;
  SoundSource wrong;
  wrong.name = "jib motor";
  wrong.kind = SourceKind::kElectricDrive;
  wrong.drive = "jib";
  sounds.machines["sts"] = {wrong};
  const Scene sts = scene_of("sts_discharge");
  try {
    SoundScape scape(sts.description, sounds);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "'jib motor' of sts: no drive 'jib' (it has: gantry, trolley, hoist, boom)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Sound, BadSoundDataNamesItsLineAndField) {
  const auto error_of = [](const std::string& text) {
    try {
      parse_sounds(text, "sounds.yaml");
    } catch (const io::DataError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(
      error_of("sounds:\n  ambience:\n    - {name: w, kind: wind, reference: 1, level: 3}\n").find("level"),
      std::string::npos);
  EXPECT_NE(
      error_of("sounds:\n  ambience:\n    - {name: w, kind: wind, reference: 1, level: 0.1, pitch: 2}\n")
          .find("pitch"),
      std::string::npos);
  // a machine's own sounds, in its machine file: named by that file, line and field
  const std::string machine =
      (std::filesystem::temp_directory_path() / "harbour_sound_machine.yaml").string();
  const auto machine_error = [&](const std::string& sounds) {
    std::ofstream(machine) << "machine:\n  kind: sts\nsounds:\n" << sounds;
    try {
      load_sounds(HARBOUR_DATA_DIR "/sounds/harbour.yaml", {machine});
    } catch (const io::DataError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(machine_error("  - {name: a, kind: wind, reference: 1, level: 0.1}\n"), "accepted");
  EXPECT_NE(machine_error("  - {name: a, kind: electric_motor, level: 0.1}\n")
                .find("harbour_sound_machine.yaml:4: sounds[0]"),
            std::string::npos);
  EXPECT_NE(machine_error("  - {name: a, kind: wind, reference: 1, level: 0.1, pitch: 2}\n")
                .find("sounds[0].pitch: unknown key"),
            std::string::npos);
  EXPECT_NE(machine_error("  - {name: a, kind: wind, reference: 1, level: 0.1}\n  - {name: a, kind: rain, "
                          "reference: 1, level: 0.1}\n")
                .find("sounds[1].name: a second sound named 'a'"),
            std::string::npos);
  std::filesystem::remove(machine);
}

}  // namespace
}  // namespace harbour::audio
