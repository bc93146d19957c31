// `harboursim devices --bind` and `harboursim station` used as a person uses them: the binding walk in a
// terminal (tmux), answering its prompts, the person's hand on the stick a virtual SDL joystick inside the
// tool moved over loopback UDP (this machine has no /dev/uinput for a real device); the station ended by
// Ctrl-C.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/station/DeviceMappingFile.h"
#include "scenes/StsScenes.h"
#include "support/PngPixels.h"

namespace harbour::apps {
namespace {

std::string run(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    std::array<char, 4096> buffer;
    while (std::fgets(buffer.data(), buffer.size(), p))
      out += buffer.data();
    pclose(p);
  }
  return out;
}

class Terminal {
 public:
  explicit Terminal(const std::string& command) {
    run("tmux kill-session -t " + kSession + " 2>/dev/null");
    run("tmux new-session -d -s " + kSession + " -x 150 -y 60 \"" + command + "; sleep 60\"");
  }
  ~Terminal() { run("tmux kill-session -t " + kSession + " 2>/dev/null"); }
  std::string screen() const { return run("tmux capture-pane -p -S -200 -t " + kSession); }
  // waits until the screen shows `text` (true) or 20 s pass
  bool wait_for(const std::string& text) const {
    for (int k = 0; k < 400; ++k) {
      if (screen().find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }
  void keys(const std::string& keys) const { run("tmux send-keys -t " + kSession + " " + keys); }

 private:
  const std::string kSession = "harbour_devices_test";
};

// the hand: datagrams to the tool's virtual stick
void hand(std::uint16_t port, const std::string& move) {
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::sendto(s, move.data(), move.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  ::close(s);
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
}

TEST(DevicesTool, APersonBindsAndCalibratesAStickInATerminal) {
  if (run("command -v tmux").empty()) GTEST_SKIP() << "tmux is not installed (./harbour setup installs it)";
  const std::string file = (std::filesystem::temp_directory_path() / "harbour_bound.yaml").string();
  std::filesystem::remove(file);
  const std::uint16_t port = 47000 + static_cast<std::uint16_t>(getpid() % 1000);
  const Terminal t(std::string(HARBOUR_APP) + " devices --bind " + file +
                   " --name 'Test desk' --virtual 'Test Stick:4:12:1' --virtual-port " +
                   std::to_string(port));
  ASSERT_TRUE(t.wait_for("Move the control you use for GANTRY")) << t.screen();
  EXPECT_NE(t.screen().find("Test Stick"), std::string::npos);  // the device list first
  hand(port, "axis 0 30000");                                   // pushed right: gantry +
  ASSERT_TRUE(t.wait_for("Now move GANTRY through its whole range")) << t.screen();
  for (const char* m : {"axis 0 32767", "axis 0 -32768", "axis 0 120"})
    hand(port, m);
  t.keys("Enter");
  ASSERT_TRUE(t.wait_for("calibrated: min -32768, centre 120, max 32767")) << t.screen();

  ASSERT_TRUE(t.wait_for("Move the control you use for TROLLEY")) << t.screen();
  hand(port, "axis 1 -31000");  // pushed forward, which this stick reports as negative: inverted
  ASSERT_TRUE(t.wait_for("Now move TROLLEY")) << t.screen();
  for (const char* m : {"axis 1 -32768", "axis 1 32767", "axis 1 0"})
    hand(port, m);
  t.keys("Enter");
  ASSERT_TRUE(t.wait_for("Move the control you use for HOIST")) << t.screen();
  t.keys("Enter");  // skipped
  ASSERT_TRUE(t.wait_for("Move the control you use for BOOM")) << t.screen();
  t.keys("Enter");
  ASSERT_TRUE(t.wait_for("Move the control you use for LOCK")) << t.screen();
  hand(port, "button 3 1");
  hand(port, "button 3 0");
  ASSERT_TRUE(t.wait_for("button 3 of Test Stick")) << t.screen();
  ASSERT_TRUE(t.wait_for("Move the control you use for UNLOCK")) << t.screen();
  t.keys("q");
  ASSERT_TRUE(t.wait_for("wrote " + file + ": 3 binding(s) on 1 device(s)")) << t.screen();
  std::printf("%s\n", t.screen().c_str());

  const scene::ControlTable table = scenes::sts_controls();
  const station::DeviceMapping m = station::load_device_mapping(file, table);
  ASSERT_EQ(m.devices.size(), 1u);
  EXPECT_EQ(m.devices[0].name, "Test Stick");
  ASSERT_EQ(m.bindings.size(), 3u);
  EXPECT_EQ(m.bindings[0].control, "gantry");
  EXPECT_EQ(m.bindings[0].index, 0);
  EXPECT_FALSE(m.bindings[0].invert);
  EXPECT_EQ(m.bindings[0].calibration.center, 120.0);
  EXPECT_EQ(m.bindings[1].control, "trolley");
  EXPECT_TRUE(m.bindings[1].invert);
  EXPECT_EQ(m.bindings[2].control, "lock");
  EXPECT_EQ(m.bindings[2].source, station::Binding::Source::kButton);
  EXPECT_EQ(m.bindings[2].index, 3);
  // the stick now drives the gantry through the written mapping: full right is +1
  station::ControlMapper mapper(table, m);
  std::vector<station::DeviceState> s{{true, {32767, 0, 0, 0}, std::vector<bool>(12), {0}}};
  EXPECT_DOUBLE_EQ(mapper.map(s).value[static_cast<std::size_t>(table.find("gantry"))], 1.0);
}

// `harboursim station` as a separate process: Ctrl-C ends the attempt, stored as interrupted, with a complete
// recording that replays.
TEST(StationCommand, CtrlCStoresTheAttemptAndClosesTheRecording) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "harbour_station_cli";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  const std::string record = (folder / "live.hsrc").string(), log = (folder / "station.log").string();
  const pid_t child = fork();
  if (child == 0) {
    freopen(log.c_str(), "w", stdout);
    freopen(log.c_str(), "a", stderr);
    execl(HARBOUR_APP, HARBOUR_APP, "station", "--exercise", "sts_discharge", "--profile", "medium",
          "--autopilot", "--time-scale", "5", "--db", db.c_str(), "--record", record.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::seconds(3));
  kill(child, SIGINT);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const std::string output = run("cat " + log);
  EXPECT_NE(output.find("station (medium)"), std::string::npos) << output;
  EXPECT_NE(output.find("(interrupted)"), std::string::npos) << output;

  records::RecordsStore store(db);
  const auto attempts = store.attempts();
  ASSERT_EQ(attempts.size(), 1u);
  EXPECT_EQ(attempts[0].status, "interrupted");
  EXPECT_EQ(attempts[0].trainee, "autopilot");
  const sim::Recording r = io::read_recording(record);
  EXPECT_TRUE(r.complete);         // closed cleanly, not a torn prefix
  EXPECT_GE(r.total_steps, 5000);  // ~3 s at 5x
  const sim::ReplayResult replay = sim::replay(
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/sts_discharge.yaml").scenario, r);
  EXPECT_FALSE(replay.first_mismatch.has_value());

  // the records keep it: with its file gone (another PC), the command line replays the attempt from them
  std::filesystem::remove(record);
  const std::string app = HARBOUR_APP;
  const std::string replayed = run(app + " replay --attempt " + std::to_string(attempts[0].id) + " --db '" +
                                   db + "' 2>&1; echo exit $?");
  EXPECT_NE(replayed.find("the records' copy"), std::string::npos) << replayed;
  EXPECT_NE(replayed.find("reproduced bit for bit"), std::string::npos) << replayed;
  EXPECT_NE(replayed.find("exit 0"), std::string::npos) << replayed;
  const std::string unknown = run(app + " replay --attempt 99 --db '" + db + "' 2>&1; echo exit $?");
  EXPECT_NE(unknown.find("no attempt 99 in the records"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("exit 2"), std::string::npos) << unknown;
  const std::string both =
      run(app + " replay --attempt 1 --exercise sts_discharge --db '" + db + "' 2>&1; echo exit $?");
  EXPECT_NE(both.find("or --attempt alone"), std::string::npos) << both;
}

// With a motion platform the attempt ends when it is asked to: the platform parks (some 5 s) after the
// simulation has stopped, not while it steps on and the evaluation counts the time.
TEST(StationCommand, AnAttemptOnAPlatformEndsWhenAskedNotWhenThePlatformHasParked) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "harbour_station_platform";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string db = "sqlite3://db=" + (folder / "records.db").string();
  const std::string output = run(std::string(HARBOUR_APP) +
                                 " station --exercise tractor_mafi_park --profile immersive --autopilot " +
                                 "--window off --sound off --seconds 2 --db '" + db + "' 2>&1; echo exit $?");
  ASSERT_NE(output.find("motion platform: "), std::string::npos) << output;
  const std::size_t at = output.find("\nloop: ");
  ASSERT_NE(at, std::string::npos) << output;
  const long ticks = std::stol(output.substr(at + 7));
  // 2 s at 1 kHz (fewer on a busy machine); the platform's park time on top was some 5,000 more
  EXPECT_GT(ticks, 500) << output;
  EXPECT_LT(ticks, 3000) << output;
  EXPECT_NE(output.find("exit 130"), std::string::npos) << output;  // stopped by --seconds: interrupted
}

// The trainee's window on an X server (Xvfb): the image generator's frames reach it while the loop keeps
// time.
TEST(StationCommand, TheWindowShowsTheCabViewWhileTheExerciseRuns) {
  if (run("command -v Xvfb").empty()) GTEST_SKIP() << "Xvfb is not installed (./harbour setup installs it)";
  const std::string display = ":" + std::to_string(90 + getpid() % 100);
  const pid_t server = fork();
  if (server == 0) {
    execlp("Xvfb", "Xvfb", display.c_str(), "-screen", "0", "1920x1200x24", "-nolisten", "tcp",
           static_cast<char*>(nullptr));
    _exit(127);
  }
  // stopped however the test ends (an X server left running holds ctest's output pipe open: ctest waits)
  struct StopServer {
    pid_t pid;
    ~StopServer() {
      kill(pid, SIGTERM);
      waitpid(pid, nullptr, 0);
    }
  } stop_server{server};
  std::this_thread::sleep_for(std::chrono::seconds(1));
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "harbour_station_window";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  // the desktop's one window channel, the immersive cabin's four projectors a window each, and a desktop
  // in red-cyan stereo
  const std::string anaglyph = (folder / "anaglyph.yaml").string();
  {
    std::ifstream desktop(std::string(HARBOUR_DATA_DIR) + "/profiles/desktop.yaml");
    std::string text((std::istreambuf_iterator<char>(desktop)), std::istreambuf_iterator<char>());
    text.replace(text.find("stereo: off"), 11,
                 "stereo: {mode: anaglyph, eye_separation_mm: 64, convergence_m: 3}");
    while (text.find(" ../devices") != std::string::npos)
      text.replace(text.find(" ../devices"), 11, " " + std::string(HARBOUR_DATA_DIR) + "/devices");
    std::ofstream(anaglyph) << text;
  }
  for (const auto& [profile, window] :
       {std::pair{std::string("desktop"), "window: 1920x1080, the cab view (desktop, 1 channel)"},
        std::pair{std::string("immersive"),
                  "windows: 4 of 480x300, one per display, the cab view (immersive)"},
        std::pair{anaglyph, "window: 1920x1080, the cab view (desktop, 1 channel, stereo: anaglyph)"}}) {
    const std::string output = run(
        "DISPLAY=" + display + " " + HARBOUR_APP + " station --exercise sts_discharge --profile " + profile +
        " --autopilot --window on --seconds 4 --db sqlite3://db=" + (folder / "records.db").string() +
        " 2>&1");
    EXPECT_NE(output.find(window), std::string::npos) << output;
    long drawn = 0, shown = 0;
    double fps = 0.0;
    const auto at = output.find("window: ", output.find("the cab view") + 1);
    ASSERT_NE(at, std::string::npos) << output;
    ASSERT_EQ(std::sscanf(output.c_str() + at, "window: %ld frames drawn (%lf fps), %ld shown", &drawn, &fps,
                          &shown),
              3)
        << output;
    std::printf("%s: %ld frames drawn (%.1f fps), %ld shown\n", profile.c_str(), drawn, fps, shown);
    // frames keep reaching the window all through the run, one a second at least (how fast is
    // bench_image_generator's business: red-cyan stereo draws every frame twice; this 2-core host drew it at
    // 1.7-2.8 fps beside the rest of the suite)
    EXPECT_GE(drawn, 4);
    EXPECT_GE(shown * 10, drawn * 9);  // a frame replaced before its window took it is not shown
    // the loop ran beside the drawing all through (how well it kept time beside it is the host's business:
    // BM_LiveRun measures it; the pacing itself is tested on a manual clock, LoopPacing.*)
    long ticks = 0, late = 0, given_up = -1;
    const auto loop = output.find("loop: ");
    ASSERT_NE(loop, std::string::npos) << output;
    ASSERT_EQ(std::sscanf(output.c_str() + loop, "loop: %ld ticks, %ld late, %ld given up", &ticks, &late,
                          &given_up),
              3)
        << output;
    EXPECT_GT(ticks, 3000);
    EXPECT_GE(given_up, 0);
  }
}

// A debrief video of a recording: re-simulated, drawn with the HUD, encoded by ffmpeg.
// mean luminance (0-1) of a PNG's rows below its top fifth (the HUD's lines), -1 where it cannot be read
double lower_luminance(const std::string& file) {
  const std::optional<test::RgbPixels> image = test::read_png_rgb(file);
  if (!image) return -1.0;
  const std::vector<png_byte>& pixels = image->rgb;
  double sum = 0.0;
  const std::size_t first =
      3 * static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height / 5);
  for (std::size_t i = first; i + 2 < pixels.size(); i += 3)
    sum += 0.2126 * pixels[i] + 0.7152 * pixels[i + 1] + 0.0722 * pixels[i + 2];
  return sum / 255.0 / static_cast<double>((pixels.size() - first) / 3);
}

TEST(ScreenshotCommand, APowerFailurePutsOutTheCranesLampsAtNight) {
  // the drives stop alike under the emergency stop and in the power failure; only the supply differs
  const std::string folder = std::filesystem::temp_directory_path().string();
  const auto shot = [&](const std::string& command, const std::string& out) {
    return run(std::string(HARBOUR_APP) + " screenshot --exercise sts_discharge --at 20 --view chase " +
               "--time-of-day 22 --size 320x180 --command " + command + " --out " + out + " 2>&1");
  };
  const std::string stopped = folder + "/harbour_stopped_at_night.png";
  const std::string unpowered = folder + "/harbour_power_failure_at_night.png";
  EXPECT_NE(shot("5:emergency-stop", stopped).find("at t=20.0 s"), std::string::npos);
  EXPECT_NE(shot("5:power-failure", unpowered).find("at t=20.0 s"), std::string::npos);
  const double lamps_on = lower_luminance(stopped), lamps_off = lower_luminance(unpowered);
  std::printf("chase view at night below the HUD: stopped %.4f, power failure %.4f\n", lamps_on, lamps_off);
  EXPECT_GT(lamps_off, 0.0);
  EXPECT_LT(lamps_off, 0.95 * lamps_on);
  // a command that is none stops it before anything is drawn, quoting it
  EXPECT_NE(shot("5:power-cut", unpowered).find("'5:power-cut': unknown kind"), std::string::npos);
}

TEST(RenderCommand, ARecordingBecomesADebriefVideo) {
  if (run("command -v ffmpeg").empty())
    GTEST_SKIP() << "ffmpeg is not installed (./harbour setup installs it)";
  const std::string out = (std::filesystem::temp_directory_path() / "harbour_debrief.mp4").string();
  std::filesystem::remove(out);
  const std::string output =
      run(std::string(HARBOUR_APP) + " render " + HARBOUR_DATA_DIR +
          "/../tests/data/recordings/sts_discharge_v6.hsrc --exercise sts_discharge --from 40 "
          "--to 42 --size 320x180 --fps 25 --out " +
          out + " 2>&1");
  EXPECT_NE(output.find("51 frames (40.0-42.0 s at 25 fps, chase view, 320x180, with sound)"),
            std::string::npos)
      << output;
  const std::string probe =
      run("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
          "stream=width,height,nb_read_frames -of "
          "csv=p=0 " +
          out);
  EXPECT_EQ(probe, "320,180,51\n") << probe;
  // a bad size is refused before anything is drawn
  EXPECT_NE(
      run(std::string(HARBOUR_APP) + " render " + HARBOUR_DATA_DIR +
          "/../tests/data/recordings/sts_discharge_v6.hsrc --exercise sts_discharge --size 321x180 --out " +
          out + " 2>&1")
          .find("even"),
      std::string::npos);
}

}  // namespace
}  // namespace harbour::apps
