#include "harbour/io/RecordingFile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>

#include "harbour/core/Rng.h"
#include "harbour/core/StateArchive.h"
#include "harbour/machines/sts/StsCrane.h"
#include "scenes/StsScenes.h"

namespace harbour::io {
namespace {

sim::Recording sample() {
  sim::Recording r;
  r.scenario = "sts_discharge";
  r.parent = "attempt-7";
  r.branch_step = 1234;
  r.total_steps = 5000;
  sim::StsControls a;
  a.trolley = 0.25;
  a.lock = true;
  sim::StsControls b;
  b.hoist = -1.0 / 3.0;
  b.emergency_stop = true;
  sim::StsControls c;  // every cab control of version 3
  c.boom = 0.5;
  c.horn = true;
  c.flipper_down = {true, false, false, true};
  c.spreader_size_ft = 45;
  r.control_labels = sim::legacy_sts_control_labels();  // the shipped table's order
  r.inputs = {{0, scenes::cab(a)}, {2500, scenes::cab(b)}, {3000, scenes::cab(c)}};
  r.checkpoints = {{1000, 0x0123456789ABCDEFull}, {2000, 42}, {3000, 43}, {4000, 44}, {5000, 45}};
  sim::InstructorCommand gust;  // version 4: the instructor's commands
  gust.gust = {0.0, 3.0, 8.0};
  sim::InstructorCommand fog;
  fog.kind = sim::InstructorCommand::Kind::kSetVisibility;
  fog.value = 300.0;
  r.commands = {{1500, gust}, {2600, fog}};
  sim::TeamInput truck;  // version 9: what a team's other stations made happen
  truck.slot = 1;
  truck.pose = {core::Mat3::rotation({0, 0, 1}, 1.5), {8.0, -3.25, 2.45}};
  truck.velocity_mps = {0.0, 1.25, 0.0};
  truck.angular_velocity_radps = {0.0, 0.0, 0.03125};
  sim::TeamInput load;
  load.kind = sim::TeamInput::Kind::kLoadOn;
  load.pose.position = {0.125, 0.0, 1.595};
  load.mass_kg = 22000.0;
  load.name_item("TGHU1000012");  // version 11: the box's name
  sim::TeamInput obstacle;        // version 10: another member's machine body, with its size
  obstacle.kind = sim::TeamInput::Kind::kObstacleAt;
  obstacle.slot = 2;
  obstacle.pose.position = {8.0, 40.0, 1.6};
  obstacle.velocity_mps = {0.0, -2.5, 0.0};
  obstacle.half_extents_m = {1.25, 3.0625, 1.5};
  r.team = {{1500, truck}, {2700, load}, {2800, obstacle}};
  return r;
}

std::string temp(const char* name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

TEST(RecordingFile, RoundTripsBitForBit) {
  const std::string path = temp("harbour_roundtrip.hsrc");
  write_recording(path, sample());
  const sim::Recording back = read_recording(path);
  EXPECT_EQ(back.scenario, "sts_discharge");
  EXPECT_EQ(back.parent, "attempt-7");
  EXPECT_EQ(back.branch_step, 1234);
  EXPECT_EQ(back.total_steps, 5000);
  ASSERT_EQ(back.inputs.size(), 3u);
  EXPECT_TRUE(back.inputs[0].controls == sample().inputs[0].controls);
  EXPECT_TRUE(back.inputs[1].controls == sample().inputs[1].controls);  // -1/3 exactly
  EXPECT_TRUE(back.inputs[2].controls == sample().inputs[2].controls);
  EXPECT_EQ(back.checkpoints[0].state_hash, 0x0123456789ABCDEFull);
  ASSERT_EQ(back.commands.size(), 2u);
  EXPECT_EQ(back.commands[1].step, 2600);
  EXPECT_TRUE(back.commands[0].command == sample().commands[0].command);
  EXPECT_TRUE(back.commands[1].command == sample().commands[1].command);
  ASSERT_EQ(back.team.size(), 3u);
  const sim::Recording expected = sample();
  for (std::size_t n = 0; n < 3; ++n) {
    const sim::TeamInput &got = back.team[n].input, &sent = expected.team[n].input;
    EXPECT_EQ(back.team[n].step, expected.team[n].step);
    EXPECT_EQ(got.kind, sent.kind);
    EXPECT_EQ(got.slot, sent.slot);
    EXPECT_TRUE(got.pose.position == sent.pose.position);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(got.pose.rotation.m[r][c], sent.pose.rotation.m[r][c]);
    EXPECT_TRUE(got.velocity_mps == sent.velocity_mps);
    EXPECT_TRUE(got.angular_velocity_radps == sent.angular_velocity_radps);
    EXPECT_EQ(got.mass_kg, sent.mass_kg);
    EXPECT_TRUE(got.half_extents_m == sent.half_extents_m);
    EXPECT_EQ(got.item_name(), sent.item_name());
  }
  EXPECT_EQ(back.team[1].input.item_name(), "TGHU1000012");
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  EXPECT_TRUE(back.ropes_settled);
  EXPECT_TRUE(back.ropes_curved);
  EXPECT_TRUE(back.end_stops_clear);
  EXPECT_TRUE(back.start_settled);
  EXPECT_TRUE(back.rope_damping_internal);
  EXPECT_TRUE(back.sheave_bending_loss);
  EXPECT_TRUE(back.machine_state_hashed);
  EXPECT_TRUE(back.running_sheaves);
  EXPECT_TRUE(back.slack_ropes_keep_sag);
  // a branch of a run that started on unstretched ropes, stretched along their chords, says so, and an
  // unknown flag is refused
  sim::Recording old_start = sample();
  old_start.ropes_settled = false;
  old_start.ropes_curved = false;
  old_start.end_stops_clear = false;
  old_start.start_settled = false;
  old_start.rope_damping_internal = false;
  old_start.sheave_bending_loss = false;
  old_start.machine_state_hashed = false;
  old_start.running_sheaves = false;
  old_start.slack_ropes_keep_sag = false;
  write_recording(path, old_start);
  EXPECT_FALSE(read_recording(path).ropes_settled);
  EXPECT_FALSE(read_recording(path).ropes_curved);
  EXPECT_FALSE(read_recording(path).end_stops_clear);
  EXPECT_FALSE(read_recording(path).start_settled);
  EXPECT_FALSE(read_recording(path).rope_damping_internal);
  EXPECT_FALSE(read_recording(path).sheave_bending_loss);
  EXPECT_FALSE(read_recording(path).machine_state_hashed);
  EXPECT_FALSE(read_recording(path).running_sheaves);
  EXPECT_FALSE(read_recording(path).slack_ropes_keep_sag);
  std::vector<char> bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // an unknown flag (bit 9) in the header's flags (u16, little-endian, after the magic and the version)
  bytes[7] = static_cast<char>(2);
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  EXPECT_THROW(read_recording(path), RecordingFileError);
  std::filesystem::remove(path);
}

std::vector<char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(RecordingFile, BadFilesNameTheFileAndTheByte) {
  const std::string path = temp("harbour_bad.hsrc");
  write_recording(path, sample());
  const auto size = std::filesystem::file_size(path);

  // what a killed run leaves: the stream cut anywhere reads as an incomplete recording up to its last
  // whole checkpoint, without the records after it
  std::filesystem::resize_file(path, size - 5);  // inside the end record
  sim::Recording cut = read_recording(path);
  EXPECT_FALSE(cut.complete);
  EXPECT_EQ(cut.total_steps, 5000);
  EXPECT_EQ(cut.inputs.size(), 3u);
  std::filesystem::resize_file(path,
                               size - 9 - 17 - 3);  // inside the checkpoint at 4 s (end record: 9 bytes)
  cut = read_recording(path);
  EXPECT_FALSE(cut.complete);
  EXPECT_EQ(cut.total_steps, 3000);
  EXPECT_EQ(cut.checkpoints.size(), 3u);
  EXPECT_EQ(cut.commands.size(), 2u);
  EXPECT_TRUE(read_recording((write_recording(path, sample()), path)).complete);

  { std::ofstream(path, std::ios::binary) << "PNG\x89 not a recording"; }
  try {
    read_recording(path);
    FAIL() << "accepted garbage";
  } catch (const RecordingFileError& e) {
    EXPECT_NE(std::string(e.what()).find("no HSRC magic"), std::string::npos) << e.what();
  }

  write_recording(path, sample());
  {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(4);
    f.put(static_cast<char>(kRecordingVersion + 1));  // a version after this build's
  }
  try {
    read_recording(path);
    FAIL() << "accepted a future version";
  } catch (const RecordingFileError& e) {
    EXPECT_NE(
        std::string(e.what()).find("version " + std::to_string(kRecordingVersion + 1) + " is not supported"),
        std::string::npos)
        << e.what();
  }
  // the last instructor command's kind byte: its record is tag 'M', the step (2600, little-endian), the kind
  write_recording(path, sample());
  {
    std::vector<char> bytes = file_bytes(path);
    const char record[] = {'M', char(0x28), char(0x0A), 0, 0, 0, 0, 0, 0};
    const auto at = std::search(bytes.begin(), bytes.end(), std::begin(record), std::end(record));
    ASSERT_NE(at, bytes.end());
    *(at + 9) = char(42);
    write_bytes(path, bytes);
  }
  try {
    read_recording(path);
    FAIL() << "accepted an unknown command";
  } catch (const RecordingFileError& e) {
    EXPECT_NE(std::string(e.what()).find("instructor command kind 42 unknown"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

TEST(RecordingFile, ReadsVersion2InputsWithTheNewControlsAtRest) {
  // a version-2 file written byte by byte: one input change (trolley 0.5, lock and e-stop), no checkpoints
  std::string bytes = "HSRC";
  auto put = [&](auto v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  };  // little-endian host
  put(std::uint16_t{2});
  put(std::uint16_t{0});
  put(std::uint32_t{3});
  bytes += "sts";
  put(std::uint32_t{0});
  put(std::int64_t{0});
  put(std::int64_t{100});
  put(std::uint32_t{1});
  put(std::int64_t{7});
  for (double d : {0.0, 0.5, 0.0})
    put(d);
  put(std::uint8_t{1 | 4});
  put(std::uint32_t{0});
  put(std::uint32_t{0});
  const std::string path = temp("harbour_v2.hsrc");
  { std::ofstream(path, std::ios::binary) << bytes; }
  const sim::Recording r = read_recording(path);
  ASSERT_EQ(r.inputs.size(), 1u);
  sim::StsControls expected;
  expected.trolley = 0.5;
  expected.lock = true;
  expected.emergency_stop = true;
  EXPECT_EQ(r.inputs[0].step, 7);
  EXPECT_EQ(r.control_labels, sim::legacy_sts_control_labels());
  EXPECT_TRUE(r.inputs[0].controls == scenes::cab(expected));
  std::filesystem::remove(path);
}

// a file's error for `recording`, "" when it reads
std::string read_error(const std::string& path, const sim::Recording& recording) {
  write_recording(path, recording);
  try {
    read_recording(path);
  } catch (const RecordingFileError& e) {
    return e.what();
  }
  return "";
}

TEST(RecordingFile, LeversOutOfRangeAndRecordsOutOfOrderAreRefused) {
  const std::string path = temp("harbour_ranges.hsrc");
  sim::Recording r = sample();
  r.inputs[1].controls.value[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(read_error(path, r).find("control 'hoist' is not a finite value"), std::string::npos);
  r = sample();
  r.control_labels.push_back("hoist");
  EXPECT_NE(read_error(path, r).find("control 'hoist' is listed twice"), std::string::npos);
  // a value out of a control's range reads (the file does not know the machine) but does not replay
  r = sample();
  r.inputs[1].controls.value[2] = -1.5;
  EXPECT_EQ(read_error(path, r), "");

  r = sample();
  std::swap(r.checkpoints[0], r.checkpoints[1]);
  EXPECT_NE(read_error(path, r).find("checkpoint 0 is not at second 1"), std::string::npos);
  r = sample();
  r.checkpoints[1].step = r.total_steps + 1000;
  EXPECT_NE(read_error(path, r).find("checkpoint 1 is not at second 2"), std::string::npos);
  // a length the data does not hold: a checkpoint is missing for every second it claims
  r = sample();
  r.total_steps = 9000;
  EXPECT_NE(read_error(path, r).find("5 checkpoints for 9 recorded seconds"), std::string::npos);
  r.total_steps = std::int64_t{1} << 40;
  EXPECT_NE(read_error(path, r).find("steps is outside 0-86400000 (24 h)"), std::string::npos);
  r = sample();
  r.parent.clear();  // a branch step without a parent
  EXPECT_NE(read_error(path, r).find("a branch step without a parent recording"), std::string::npos);
  r = sample();
  r.branch_step = r.total_steps + 1;
  EXPECT_NE(read_error(path, r).find("branch step outside the recording"), std::string::npos);
  r = sample();
  r.scenario = "sts\x1b[31m";
  EXPECT_NE(read_error(path, r).find("the scenario name holds a control character"), std::string::npos);
  r = sample();
  r.keyframes = {{2000, {1, 2, 3}}, {1000, {4, 5, 6}}};
  EXPECT_NE(read_error(path, r).find("keyframes out of order"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(RecordingFile, ADamagedKeyframeIsRefusedByItsChecksum) {
  const std::string path = temp("harbour_keyframe.hsrc");
  sim::Recording r = sample();
  const std::vector<std::uint8_t> state = {0xA5, 0x5A, 0xC3, 0x3C, 0x0F, 0xF0, 0x99, 0x66};
  r.keyframes = {{1000, state}};
  write_recording(path, r);
  EXPECT_EQ(read_recording(path).keyframes.at(0).state, state);

  std::vector<char> bytes = file_bytes(path);
  const auto at = std::search(bytes.begin(), bytes.end(), state.begin(), state.end(),
                              [](char a, std::uint8_t b) { return static_cast<std::uint8_t>(a) == b; });
  ASSERT_NE(at, bytes.end());
  at[3] ^= 0x10;  // one bit
  write_bytes(path, bytes);
  try {
    read_recording(path);
    FAIL() << "accepted a damaged keyframe";
  } catch (const RecordingFileError& e) {
    EXPECT_NE(std::string(e.what()).find("keyframe 0 is damaged"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

// Damage anywhere in a real recording (one byte changed, over and over): reading refuses it with a
// RecordingFileError, or a seek from its keyframe refuses it with a StateError, or it replays and the
// damage shows as a checkpoint mismatch or changes nothing the seek reads. Never another exception, never
// a crash; damage inside the keyframe's state is always refused at reading.
TEST(RecordingFile, DamageAnywhereIsRefusedOrReportedNeverACrash) {
  const sim::ScenarioSettings scenario = scenes::sts_discharge(HARBOUR_DATA_DIR);
  constexpr std::int64_t kSteps = 11000;  // a keyframe at 10 s, a checkpoint at 11 s
  sim::Recorder recorder("sts_discharge", scenes::sts_controls());
  {
    sim::Simulation s(scenario);
    for (std::int64_t k = 0; k < kSteps; ++k) {
      const sim::StsControls in = scenes::scripted_operator(k);
      s.step(scenes::cab(in));
      recorder.after_step(s, scenes::cab(in));
    }
  }
  const std::string path = temp("harbour_damage.hsrc");
  write_recording(path, recorder.recording());
  const std::vector<char> original = file_bytes(path);
  const std::vector<std::uint8_t>& state = recorder.recording().keyframes.at(0).state;
  const auto keyframe_at = static_cast<std::size_t>(
      std::search(original.begin(), original.end(), state.begin(), state.end(),
                  [](char a, std::uint8_t b) { return static_cast<std::uint8_t>(a) == b; }) -
      original.begin());
  ASSERT_LT(keyframe_at, original.size());
  const std::size_t outside = original.size() - state.size();

  core::Rng rng(20261122);
  int refused_reading = 0, refused_seek = 0, mismatched = 0, unchanged = 0;
  for (int n = 0; n < 160; ++n) {
    // half anywhere in the file, half in the bytes around the keyframe's state
    std::size_t at = rng.next_u64() % (n % 2 ? original.size() : outside);
    if (n % 2 == 0 && at >= keyframe_at) at += state.size();
    std::vector<char> damaged = original;
    damaged[at] = static_cast<char>(damaged[at] ^ static_cast<char>(1 + rng.next_u64() % 255));
    write_bytes(path, damaged);
    SCOPED_TRACE("byte " + std::to_string(at));
    sim::Recording read;
    try {
      read = read_recording(path);
    } catch (const RecordingFileError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": byte "), std::string::npos) << e.what();
      ++refused_reading;
      continue;
    }
    EXPECT_FALSE(at >= keyframe_at && at < keyframe_at + state.size()) << "damaged keyframe state was read";
    try {
      const sim::ReplayResult r = sim::replay(scenario, read, kSteps);
      if (r.first_mismatch)
        ++mismatched;
      else
        ++unchanged;
    } catch (const core::StateError&) {
      ++refused_seek;
    }
  }
  EXPECT_GT(refused_reading, 0);
  EXPECT_EQ(refused_reading + refused_seek + mismatched + unchanged, 160);
  std::printf(
      "damaged bytes: %d refused reading, %d refused at the seek, %d replayed with a mismatch, %d "
      "replayed unchanged\n",
      refused_reading, refused_seek, mismatched, unchanged);
  std::filesystem::remove(path);
}

// A station's recording cut anywhere (a full disk, a killed process): every prefix of its last 64 KiB
// reads, as the incomplete recording of what it holds up to its last whole second; a cut inside a keyframe
// (most of the file's bytes) drops that keyframe. Replayed from the start and from its last keyframe, a
// prefix cut in the last keyframe reproduces every recorded second.
TEST(RecordingFile, ACutAtEveryByteOfItsLast64KiBReadsAsItsPrefix) {
  const sim::ScenarioSettings scenario = scenes::sts_discharge(HARBOUR_DATA_DIR);
  constexpr std::int64_t kSteps = 41000;  // keyframes at 10, 20, 30 and 40 s
  sim::Recorder recorder("sts_discharge", scenes::sts_controls());
  {
    sim::Simulation s(scenario);
    for (std::int64_t k = 0; k < kSteps; ++k) {
      const sim::StsControls in = scenes::scripted_operator(k);
      s.step(scenes::cab(in));
      recorder.after_step(s, scenes::cab(in));
    }
  }
  const sim::Recording& whole = recorder.recording();
  ASSERT_EQ(whole.keyframes.size(), 4u);
  const std::string path = temp("harbour_cut.hsrc");
  write_recording(path, whole);
  const std::vector<char> bytes = file_bytes(path);
  std::filesystem::remove(path);
  const std::vector<std::uint8_t>& last_state = whole.keyframes.back().state;
  const auto last_keyframe_at = static_cast<std::size_t>(
      std::search(bytes.begin(), bytes.end(), last_state.begin(), last_state.end(),
                  [](char a, std::uint8_t b) { return static_cast<std::uint8_t>(a) == b; }) -
      bytes.begin());
  ASSERT_LT(last_keyframe_at, bytes.size());
  ASSERT_GT(bytes.size(), std::size_t{65536}) << "the recording is shorter than the span cut";

  std::size_t refused = 0, wrong = 0, first_wrong = 0;
  std::string first_why;
  std::optional<sim::Recording> inside_last_keyframe;
  for (std::size_t cut = bytes.size() - 65536; cut < bytes.size(); ++cut) {
    sim::Recording prefix;
    try {
      prefix = parse_recording(path, std::string(bytes.data(), cut));
    } catch (const RecordingFileError& e) {
      if (refused++ == 0) first_why = "cut at " + std::to_string(cut) + ": " + e.what();
      continue;
    }
    // what it holds is what the whole recording holds up to its last whole second
    const auto n_keyframes = prefix.keyframes.size();
    const bool ok =
        !prefix.complete && !prefix.checkpoints.empty() &&
        prefix.total_steps == prefix.checkpoints.back().step &&
        prefix.checkpoints.size() <= whole.checkpoints.size() &&
        prefix.checkpoints.back().state_hash == whole.checkpoints[prefix.checkpoints.size() - 1].state_hash &&
        n_keyframes <= whole.keyframes.size() &&
        (n_keyframes == 0 || prefix.keyframes.back().state == whole.keyframes[n_keyframes - 1].state) &&
        prefix.inputs.size() <= whole.inputs.size() &&
        (prefix.inputs.empty() || prefix.inputs.back().step < prefix.total_steps);
    if (!ok && wrong++ == 0) first_wrong = cut;
    if (!inside_last_keyframe && cut > last_keyframe_at + 16 && cut < last_keyframe_at + last_state.size())
      inside_last_keyframe = prefix;
  }
  EXPECT_EQ(refused, 0u) << first_why;
  EXPECT_EQ(wrong, 0u) << "first at byte " << first_wrong;
  ASSERT_TRUE(inside_last_keyframe);
  EXPECT_EQ(inside_last_keyframe->keyframes.size(), 3u);  // the torn one is dropped
  const sim::ReplayResult from_start = sim::replay(scenario, *inside_last_keyframe);
  EXPECT_FALSE(from_start.first_mismatch);
  EXPECT_EQ(from_start.checkpoints_checked, static_cast<int>(inside_last_keyframe->checkpoints.size()));
  const sim::ReplayResult from_keyframe =
      sim::replay(scenario, *inside_last_keyframe, inside_last_keyframe->total_steps);
  EXPECT_EQ(from_keyframe.keyframes_used, 1);
  EXPECT_FALSE(from_keyframe.first_mismatch);
  EXPECT_EQ(from_keyframe.simulation->state_hash(), from_start.simulation->state_hash());
}

// A recording written by the v6 build (2026-11-23, `harboursim run --exercise sts_discharge --autopilot
// --command 20:gust:6:3`): its STS fields are read by label and it replays bit for bit on today's build.
TEST(RecordingFile, ACommittedVersion6RecordingStillReplaysBitForBit) {
  const sim::Recording r =
      read_recording(std::string(HARBOUR_DATA_DIR) + "/../tests/data/recordings/sts_discharge_v6.hsrc");
  EXPECT_EQ(r.control_labels, sim::legacy_sts_control_labels());
  ASSERT_EQ(r.checkpoints.size(), 94u);
  const sim::ScenarioSettings scenario = scenes::sts_discharge(HARBOUR_DATA_DIR);
  const sim::ReplayResult whole = sim::replay(scenario, r);
  EXPECT_EQ(whole.checkpoints_checked, 94);
  EXPECT_FALSE(whole.first_mismatch.has_value()) << "first mismatch at step " << *whole.first_mismatch;
  // and a seek from one of its keyframes (saved by the old build) lands on the recorded state too
  const sim::ReplayResult seek = sim::replay(scenario, r, 61000);
  EXPECT_EQ(seek.keyframes_used, 1);
  EXPECT_FALSE(seek.first_mismatch.has_value());
}

}  // namespace
}  // namespace harbour::io
