#include "harbour/io/RecordingFile.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace harbour::io {
namespace {

sim::Recording sample() {
  sim::Recording r;
  r.scenario = "sts_discharge";
  r.parent = "attempt-7";
  r.branch_step = 1234;
  r.total_steps = 5000;
  sim::Inputs a;
  a.sts.trolley = 0.25;
  a.sts.lock = true;
  sim::Inputs b;
  b.sts.hoist = -1.0 / 3.0;
  b.sts.emergency_stop = true;
  sim::Inputs c;  // every cab control of version 3
  c.sts.boom = 0.5;
  c.sts.horn = true;
  c.sts.flipper_down = {true, false, false, true};
  c.sts.spreader_size_ft = 45;
  r.inputs = {{0, a}, {2500, b}, {3000, c}};
  r.checkpoints = {{1000, 0x0123456789ABCDEFull}, {2000, 42}};
  sim::InstructorCommand gust;  // version 4: the instructor's commands
  gust.gust = {0.0, 3.0, 8.0};
  sim::InstructorCommand fog;
  fog.kind = sim::InstructorCommand::Kind::kSetVisibility;
  fog.value = 300.0;
  r.commands = {{1500, gust}, {2600, fog}};
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
  EXPECT_TRUE(back.inputs[0].inputs == sample().inputs[0].inputs);
  EXPECT_TRUE(back.inputs[1].inputs == sample().inputs[1].inputs);  // -1/3 exactly
  EXPECT_TRUE(back.inputs[2].inputs == sample().inputs[2].inputs);
  EXPECT_EQ(back.checkpoints[0].state_hash, 0x0123456789ABCDEFull);
  ASSERT_EQ(back.commands.size(), 2u);
  EXPECT_EQ(back.commands[1].step, 2600);
  EXPECT_TRUE(back.commands[0].command == sample().commands[0].command);
  EXPECT_TRUE(back.commands[1].command == sample().commands[1].command);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  std::filesystem::remove(path);
}

TEST(RecordingFile, BadFilesNameTheFileAndTheByte) {
  const std::string path = temp("harbour_bad.hsrc");
  write_recording(path, sample());
  const auto size = std::filesystem::file_size(path);

  std::filesystem::resize_file(path, size - 5);  // truncated inside the last checkpoint
  try {
    read_recording(path);
    FAIL() << "accepted a truncated file";
  } catch (const RecordingFileError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": byte "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }

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
    f.put(9);  // version 9
  }
  try {
    read_recording(path);
    FAIL() << "accepted a future version";
  } catch (const RecordingFileError& e) {
    EXPECT_NE(std::string(e.what()).find("version 9 is not supported"), std::string::npos) << e.what();
  }
  // the last instructor command's kind byte (records of 61 bytes at the end; the kind after the step)
  write_recording(path, sample());
  {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(static_cast<std::streamoff>(size) - 61 + 8);
    f.put(char(42));
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
  sim::Inputs expected;
  expected.sts.trolley = 0.5;
  expected.sts.lock = true;
  expected.sts.emergency_stop = true;
  EXPECT_EQ(r.inputs[0].step, 7);
  EXPECT_TRUE(r.inputs[0].inputs == expected);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace harbour::io
