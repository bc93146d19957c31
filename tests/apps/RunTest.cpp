// harboursim run as a person or a centre runs it: a separate process, killed or run eight at a time.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/sim/Recording.h"
#include "support/AppProcess.h"

namespace harbour::apps {
namespace {

namespace fs = std::filesystem;

// starts `harboursim run` on the shipped discharge exercise (or `exercise`), its output to a log in `folder`
pid_t start_run(const fs::path& folder, const std::string& db, const std::string& record, int n,
                const std::vector<std::string>& more = {}, const std::string& exercise = "sts_discharge") {
  std::vector<std::string> args = {"run", "--exercise", exercise, "--autopilot", "--db", db};
  if (!record.empty()) args.insert(args.end(), {"--record", record});
  args.insert(args.end(), more.begin(), more.end());
  return start_app(args, folder / ("run" + std::to_string(n) + ".log"));
}

TEST(Run, KilledMidExerciseItsAttemptIsInterruptedAndItsRecordingPrefixReplays) {
  const fs::path folder = fresh_folder("harbour_kill9");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  const std::string record = (folder / "run.hsrc").string();
  const pid_t child = start_run(folder, db, record, 0);
  // wait until the streamed recording holds a keyframe (10 s) and a few seconds more, then kill -9
  sim::Recording seen;
  for (int tries = 0; tries < 600 && seen.checkpoints.size() < 13; ++tries) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    try {
      seen = io::read_recording(record);  // while it is being written
    } catch (const std::exception&) {
    }
  }
  ASSERT_GE(seen.checkpoints.size(), 13u) << "the run did not get going";
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));

  // opening the database marks the attempt whose process is gone; its recording is linked from the start
  records::RecordsStore store(db);
  const auto attempts = store.attempts();
  ASSERT_EQ(attempts.size(), 1u);
  EXPECT_EQ(attempts[0].status, "interrupted");
  EXPECT_EQ(attempts[0].recording, record);

  const sim::Recording prefix = io::read_recording(record);
  EXPECT_FALSE(prefix.complete);
  ASSERT_GE(prefix.keyframes.size(), 1u);
  EXPECT_EQ(prefix.total_steps, prefix.checkpoints.back().step);
  const sim::ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  // bit for bit from the start to its last second, and from its last keyframe (an instructor's take-over)
  const sim::ReplayResult whole = sim::replay(exercise.scenario, prefix);
  EXPECT_FALSE(whole.first_mismatch);
  EXPECT_EQ(whole.checkpoints_checked, static_cast<int>(prefix.checkpoints.size()));
  const sim::ReplayResult seek = sim::replay(exercise.scenario, prefix, prefix.total_steps);
  EXPECT_EQ(seek.keyframes_used, 1);
  EXPECT_FALSE(seek.first_mismatch);
  EXPECT_EQ(seek.simulation->state_hash(), whole.simulation->state_hash());
}

TEST(Run, EightStationsOnOneSqliteDatabaseAllStoreTheirAttempts) {
  const fs::path folder = fresh_folder("harbour_eight");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  std::vector<pid_t> runs;
  for (int n = 0; n < 8; ++n)
    runs.push_back(start_run(folder, db, "", n));
  for (std::size_t n = 0; n < runs.size(); ++n) {
    int status = 0;
    waitpid(runs[n], &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << "run " << n << (WIFSIGNALED(status) ? " killed by signal " + std::to_string(WTERMSIG(status)) : "")
        << ", its log:\n"
        << read_text(folder / ("run" + std::to_string(n) + ".log"));
  }
  records::RecordsStore store(db);
  const auto attempts = store.attempts();
  ASSERT_EQ(attempts.size(), 8u);
  for (const records::AttemptRow& a : attempts) {
    EXPECT_EQ(a.status, "finished");
    EXPECT_EQ(a.moves, 1);
  }
}

TEST(Run, ABadRecordingPathIsRefusedBeforeTheRunAndNothingIsStored) {
  const fs::path folder = fresh_folder("harbour_badrecord");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  for (const std::string& record : {(folder / "missing" / "run.hsrc").string(), folder.string()}) {
    const pid_t child = start_run(folder, db, record, 0);
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1);
  }
  EXPECT_FALSE(fs::exists(folder / "records.db"));  // refused before the database was even opened
  EXPECT_FALSE(fs::exists(folder / "missing"));
}

// a centre's folder: an exercises folder of its own beside the shipped machines, vessels, ... (linked)
void link_data_beside(const fs::path& folder) {
  fs::create_directories(folder / "exercises");
  for (const auto& entry : fs::directory_iterator(HARBOUR_DATA_DIR))
    if (entry.path().filename() != "exercises")
      fs::create_symlink(entry.path(), folder / entry.path().filename());
}

// The instructor's hoist brake fault in an exercise that does not script it: the autopilot follows the
// procedure and the crane stops with the move left. It used to say "score 100 / 100: PASSED" and count as a
// pass; it is ended by the instructor, neither passed nor failed, and says so in words.
TEST(Run, AFaultTheInstructorInjectedEndsTheAttemptByTheInstructorNotAsAPass) {
  const fs::path folder = fresh_folder("harbour_false_pass");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  EXPECT_EQ(exit_code(start_run(folder, db, "", 0, {"--command", "22:hoist-brake-fault"})), 0);
  const std::string log = read_text(folder / "run0.log");
  EXPECT_NE(log.find("ENDED BY THE INSTRUCTOR (neither passed nor failed)"), std::string::npos) << log;
  EXPECT_EQ(log.find("PASSED"), std::string::npos) << log;
  EXPECT_EQ(log.find("after -"), std::string::npos) << "a negative duration: " << log;
  records::RecordsStore store(db);
  const auto attempts = store.attempts();
  ASSERT_EQ(attempts.size(), 1u);
  EXPECT_EQ(attempts[0].status, "ended_by_instructor");
  EXPECT_FALSE(attempts[0].passed);
  EXPECT_EQ(records::attempt_outcome(attempts[0]), "ended by the instructor");
  EXPECT_EQ(attempts[0].moves, 0);
}

// An exercise that cannot be finished in its time (here: 5 s for a discharge, no overtime) stops there and
// the run exits non-zero, saying which goals are left.
TEST(Run, ARunOutOfTimeWithGoalsLeftExitsNonZeroAndSaysSo) {
  const fs::path folder = fresh_folder("harbour_out_of_time");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  std::string text = read_text(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  const std::size_t rules = text.find("  rules:\n");
  ASSERT_NE(rules, std::string::npos);
  text.insert(rules + std::string("  rules:\n").size(), "    overtime_s: 0\n");
  const std::size_t limit = text.find("time_limit_s: ");
  ASSERT_NE(limit, std::string::npos);
  text.replace(limit, text.find('\n', limit) - limit, "time_limit_s: 5");
  link_data_beside(folder);
  std::ofstream(folder / "exercises" / "sts_discharge.yaml") << text;
  EXPECT_EQ(
      exit_code(start_run(folder, db, "", 0, {}, (folder / "exercises" / "sts_discharge.yaml").string())), 4);
  const std::string log = read_text(folder / "run0.log");
  EXPECT_NE(log.find("with goals left: moves 0/1"), std::string::npos) << log;
  records::RecordsStore store(db);
  ASSERT_EQ(store.attempts().size(), 1u);
  EXPECT_EQ(store.attempts()[0].status, "finished");
  EXPECT_FALSE(store.attempts()[0].passed);
}

// A stored attempt replays bit for bit after its exercise file was edited: the records keep the version it
// ran, and replay re-simulates that, not the file as it is now.
TEST(Run, AnOldAttemptReplaysBitForBitAfterItsExerciseFileWasEdited) {
  const fs::path folder = fresh_folder("harbour_edited");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  link_data_beside(folder);
  const fs::path file = folder / "exercises" / "sts_discharge.yaml";
  std::string text = read_text(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  std::ofstream(file) << text;
  const std::string record = (folder / "run.hsrc").string();
  ASSERT_EQ(exit_code(start_run(folder, db, record, 0, {}, file.string())), 0)
      << read_text(folder / "run0.log");
  // the crane starting elsewhere: the same recording would diverge at once
  const std::size_t start = text.find("trolley_x_m: 32.27");
  ASSERT_NE(start, std::string::npos);
  text.replace(start, 18, "trolley_x_m: 30.00");
  std::ofstream(file, std::ios::trunc) << text;
  fs::remove(record);  // and the recording's file gone: the records keep both
  const pid_t replay = fork();
  if (replay == 0) {
    const std::string log = (folder / "replay.log").string();
    freopen(log.c_str(), "w", stdout);
    freopen(log.c_str(), "a", stderr);
    execl(HARBOUR_APP, HARBOUR_APP, "replay", "--attempt", "1", "--db", db.c_str(), nullptr);
    _exit(127);
  }
  EXPECT_EQ(exit_code(replay), 0) << read_text(folder / "replay.log");
  const std::string log = read_text(folder / "replay.log");
  EXPECT_NE(log.find("kept in the records"), std::string::npos) << log;
  EXPECT_NE(log.find("reproduced bit for bit"), std::string::npos) << log;
}

// runs harboursim with `arguments`, its output to `log`; returns its exit code
int run_app(const std::vector<std::string>& arguments, const fs::path& log) {
  return exit_code(start_app(arguments, log));
}

// A recording's sound track: the same bit for bit each time it is rendered, not silent, and in the debrief
// video as its audio stream.
TEST(Run, ARecordingsSoundTrackIsTheSameEveryTimeAndTheVideoCarriesIt) {
  const fs::path folder = fresh_folder("harbour_sound");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  const std::string record = (folder / "run.hsrc").string();
  ASSERT_EQ(exit_code(start_run(folder, db, record, 0)), 0) << read_text(folder / "run0.log");
  std::string tracks[2];
  for (int n = 0; n < 2; ++n) {
    const fs::path wav = folder / ("sound" + std::to_string(n) + ".wav");
    ASSERT_EQ(
        run_app({"render", record, "--exercise", "sts_discharge", "--audio", wav.string(), "--to", "12"},
                folder / "render.log"),
        0)
        << read_text(folder / "render.log");
    tracks[n] = read_text(wav);
  }
  EXPECT_EQ(tracks[0].size(), 44u + 12u * 48000u * 2u * 2u);  // 12 s of 16-bit stereo at 48 kHz
  EXPECT_TRUE(tracks[0] == tracks[1]);
  long loud = 0;  // samples above -40 dB of full scale: the hoist at work
  for (std::size_t n = 44; n + 1 < tracks[0].size(); n += 2) {
    const auto sample = static_cast<std::int16_t>(static_cast<unsigned char>(tracks[0][n]) |
                                                  static_cast<unsigned char>(tracks[0][n + 1]) << 8);
    loud += std::abs(sample) > 328;
  }
  EXPECT_GT(loud, 48000);

  const fs::path video = folder / "clip.mp4";
  ASSERT_EQ(run_app({"render", record, "--exercise", "sts_discharge", "--out", video.string(), "--from", "3",
                     "--to", "5", "--size", "160x90"},
                    folder / "video.log"),
            0)
      << read_text(folder / "video.log");
  const fs::path streams = folder / "streams.txt";
  ASSERT_EQ(std::system(("ffprobe -v error -show_entries stream=codec_type -of csv=p=0 " + video.string() +
                         " > " + streams.string())
                            .c_str()),
            0);
  EXPECT_EQ(read_text(streams), "video\naudio\n");
  EXPECT_FALSE(fs::exists(folder / "clip.mp4.silent.mp4"));
  EXPECT_FALSE(fs::exists(folder / "clip.mp4.sound.wav"));
}

// SIGTERM ends every long-running command within a second, whatever it is doing: a run, a console, a served
// station waiting and one running an exercise. (A loader walking nested aliases used to hold it for minutes.)
TEST(Run, ASignalEndsEveryLongRunningCommandWithinASecond) {
  const fs::path folder = fresh_folder("harbour_sigterm");
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  const std::vector<std::vector<std::string>> commands = {
      {"run", "--exercise", "sts_discharge", "--autopilot", "--db", db},
      {"console", "--port", "0", "--domain", "211", "--db", db},
      {"station", "--serve", "--name", "sigterm-1", "--domain", "211", "--window", "off", "--db", db},
      {"station", "--exercise", "sts_discharge", "--autopilot", "--window", "off", "--db", db}};
  for (std::size_t n = 0; n < commands.size(); ++n) {
    const pid_t child = start_app(commands[n], folder / ("cmd" + std::to_string(n) + ".log"));
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));  // well under way
    const auto asked = std::chrono::steady_clock::now();
    kill(child, SIGTERM);
    int status = 0;
    pid_t ended = 0;
    while ((ended = waitpid(child, &status, WNOHANG)) == 0 &&
           std::chrono::steady_clock::now() - asked < std::chrono::seconds(10))
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
    if (ended == 0) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
    }
    EXPECT_LT(took_s, 1.0) << commands[n][0] << " " << commands[n][1] << ", its log:\n"
                           << read_text(folder / ("cmd" + std::to_string(n) + ".log"));
  }
}

}  // namespace
}  // namespace harbour::apps
