#include "harbour/station/Station.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <thread>

#include "harbour/io/DataError.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/station/DeviceMappingFile.h"
#include "harbour/station/HeadTracker.h"
#include "harbour/station/MotionLink.h"
#include "harbour/station/Profile.h"
#include "scenes/MachineControls.h"
#include "scenes/StationScenes.h"
#include "scenes/StsScenes.h"

namespace harbour::station {
namespace {

std::vector<std::uint8_t> opentrack_datagram(const double (&v)[6]) {
  std::vector<std::uint8_t> bytes(48);
  for (int k = 0; k < 6; ++k) {
    std::uint64_t bits;
    std::memcpy(&bits, &v[k], 8);
    for (int b = 0; b < 8; ++b)
      bytes[static_cast<std::size_t>(8 * k + b)] = static_cast<std::uint8_t>(bits >> (8 * b));
  }
  return bytes;
}

void send_to(std::uint16_t port, const std::vector<std::uint8_t>& bytes) {
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::sendto(s, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  ::close(s);
}

struct LiveSession {
  sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  std::unique_ptr<Session> session;
  std::unique_ptr<sim::GantryAutopilot> pilot;
  explicit LiveSession(const std::string& name) {
    SessionOptions options;
    options.trainee = "t1";
    options.database = scenes::fresh_database(name + ".db");
    session = std::make_unique<Session>(exercise, options);
    pilot = std::make_unique<sim::GantryAutopilot>(exercise);
    session->loop().set_pilot([this](const sim::Simulation& s) { return pilot->next(s); });
  }
};

// A take-over (a console's command names the recording) continues only an attempt the records hold: any
// other file is refused before it is read, and no attempt is begun.
TEST(TakeOver, AStationContinuesOnlyAStoredAttempt) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  SessionOptions options;
  options.trainee = "t1";
  options.database = scenes::fresh_database("harbour_take_over.db");
  options.take_over = TakeOverFrom{"/etc/passwd", 0};
  try {
    Session refused(exercise, options);
    ADD_FAILURE() << "a take-over of a file no attempt recorded was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no stored attempt was recorded at '/etc/passwd'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(records::RecordsStore(options.database).attempts().empty());
}

TEST(HeadTracking, OpenTrackDatagramsConvertToTheCabFrameWithinLimits) {
  core::Vec3 offset, angles;
  const HeadLimits limits;
  ASSERT_TRUE(head_pose_from_opentrack(opentrack_datagram({10.0, 5.0, -20.0, 30.0, -15.0, 2.0}), limits,
                                       offset, angles));
  EXPECT_DOUBLE_EQ(offset.x, -0.20);  // OpenTrack z (towards the screen) is the cab's forward x
  EXPECT_DOUBLE_EQ(offset.y, -0.10);  // OpenTrack x right is the cab's -y
  EXPECT_DOUBLE_EQ(offset.z, 0.05);
  EXPECT_DOUBLE_EQ(angles.x, 30.0 * std::numbers::pi / 180.0);
  EXPECT_DOUBLE_EQ(angles.y, -15.0 * std::numbers::pi / 180.0);
  ASSERT_TRUE(
      head_pose_from_opentrack(opentrack_datagram({500.0, 0, 0, 400.0, 0, 0}), limits, offset, angles));
  EXPECT_DOUBLE_EQ(offset.y, -limits.max_offset_m);  // a head 5 m to the right: held at the limit
  EXPECT_DOUBLE_EQ(angles.x, limits.max_yaw_rad);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(head_pose_from_opentrack(opentrack_datagram({nan, 0, 0, 0, 0, 0}), limits, offset, angles));
  EXPECT_FALSE(head_pose_from_opentrack(std::vector<std::uint8_t>(47), limits, offset, angles));
}

TEST(HeadTracking, PacketsOverLoopbackMoveThePublishedEyePoint) {
  LiveSession live("harbour_head");
  Station station(*live.session);
  station.use_head_tracking(std::make_unique<HeadTracker>(0));  // any free port
  const std::uint16_t port = station.head_tracker()->port();
  station.start();
  live.session->start();
  send_to(port, {1, 2, 3});  // not OpenTrack: refused, nothing moves
  send_to(port, opentrack_datagram({-8.0, 4.0, 12.0, -20.0, 10.0, 0.0}));
  bool moved = false;
  for (int k = 0; k < 200 && !moved; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const scene::Snapshot* s = live.session->loop().latest_snapshot(kImageGeneratorReader);
    moved = s && std::abs(s->cab.head_offset_m.x - 0.12) < 1e-12 &&
            std::abs(s->cab.head_offset_m.y - 0.08) < 1e-12 &&
            std::abs(s->cab.head_offset_m.z - 0.04) < 1e-12 &&
            std::abs(s->cab.head_yaw_pitch_roll_rad.x + 20.0 * std::numbers::pi / 180.0) < 1e-12;
  }
  station.stop();
  live.session->finish(SessionEnd::kInterrupted);
  EXPECT_TRUE(moved);
  EXPECT_EQ(station.head_tracker()->refused(), 1);
  EXPECT_EQ(station.head_tracker()->received(), 1);
}

TEST(MotionPlatform, TheCabsCuesDriveThePlatformOverUdp) {
  // a platform stand-in: counts the driver's packets on a loopback port
  const int listener = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  socklen_t size = sizeof address;
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &size);
  timeval timeout{0, 200000};
  ::setsockopt(listener, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);

  const Profile profile = load_profile(resolve_profile("immersive", HARBOUR_DATA_DIR));
  ASSERT_TRUE(profile.motion.has_value());
  io::DriverSettings driver = profile.motion->driver;
  driver.port = ntohs(address.sin_port);
  LiveSession live("harbour_motion");
  Station station(*live.session);
  station.use_motion(std::make_unique<MotionLink>(
      io::load_platform(profile.motion->platform),
      io::load_washout(profile.motion->washout, HARBOUR_DATA_DIR "/machines/sts.yaml"), driver,
      live.session->simulation().scene()));
  station.start();
  live.session->start();
  int packets = 0;
  std::uint8_t buffer[256];
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (std::chrono::steady_clock::now() < until)
    if (::recv(listener, buffer, sizeof buffer, 0) == static_cast<ssize_t>(io::kGenericPacketSize)) ++packets;
  const motion::PlatformState state = station.motion()->state();
  const long frames = station.motion()->frames();
  const motion::PlatformPose pose = station.motion()->last_frame().pose;  // a copy, taken under its lock
  bool finite = true;
  for (const double d : pose.dof)
    finite = finite && std::isfinite(d);
  station.stop();  // parks the platform
  live.session->finish(SessionEnd::kInterrupted);
  ::close(listener);
  std::printf("motion: %d packets in 2 s, %ld frames, state %d\n", packets, frames, static_cast<int>(state));
  EXPECT_GT(packets, 100);  // the washout's 100 Hz (a loaded machine drops some: no burst to catch up)
  EXPECT_LT(packets, 260);
  EXPECT_NE(state, motion::PlatformState::kParked);  // engaging or engaged while the exercise runs
  EXPECT_TRUE(finite);
  EXPECT_EQ(station.motion()->state(), motion::PlatformState::kParked);
}

TEST(ShortCues, ThePlatformFeelsTheEngineAndTheImpactsTheSoundIsMadeOf) {
  scene::SceneDescription scene;
  scene.drives = {"boom", "engine"};
  ShortCueSource source(scene);
  auto s = std::make_unique<scene::Snapshot>();
  s->drive_count = 2;
  s->drives[1] = {0.6, 0.8};
  s->knocks_total = 3;  // before the platform's first frame: not felt
  motion::ShortCueInputs in = source.next(*s);
  EXPECT_EQ(in.engine_speed, 0.6);
  EXPECT_EQ(in.engine_load, 0.8);
  EXPECT_EQ(in.impact_speed_mps, 0.0);
  s->knocks[3 % scene::kMaxKnocks].speed_mps = 0.4;
  s->knocks[4 % scene::kMaxKnocks].speed_mps = 0.25;
  s->knocks_total = 5;
  EXPECT_EQ(source.next(*s).impact_speed_mps, 0.4);  // the hardest since the last frame
  EXPECT_EQ(source.next(*s).impact_speed_mps, 0.0);  // felt once
  s->power_off = true;                               // the engine stops with the supply
  in = source.next(*s);
  EXPECT_EQ(in.engine_speed, 0.0);
  EXPECT_EQ(in.engine_load, 0.0);
  // a machine without an engine (the STS on shore power) gives no engine cue
  scene::SceneDescription sts;
  sts.drives = {"gantry", "trolley", "hoist", "boom"};
  s->power_off = false;
  EXPECT_EQ(ShortCueSource(sts).next(*s).engine_load, 0.0);
}

TEST(Profiles, TheThreeShippedConfigurationsLoad) {
  const Profile desktop = load_profile(resolve_profile("desktop", HARBOUR_DATA_DIR));
  EXPECT_EQ(desktop.displays.size(), 1u);
  EXPECT_EQ(desktop.opentrack_port, 4242);
  EXPECT_FALSE(desktop.motion.has_value());
  // a game pad and a keyboard for every machine
  for (const auto& [kind, table] : test::shipped_machine_controls())
    for (const char* device : {"gamepad", "keyboard"})
      EXPECT_TRUE(std::any_of(desktop.mappings.begin(), desktop.mappings.end(),
                              [&](const std::string& file) {
                                return file.find(device) != std::string::npos &&
                                       why_mapping_does_not_fit(file, table).empty();
                              }))
          << "no " << device << " for the " << kind;
  // the game pads come before the keyboards: a pad plugged in is used
  const auto first_of = [&](const std::string& part) {
    for (std::size_t n = 0; n < desktop.mappings.size(); ++n)
      if (desktop.mappings[n].find(part) != std::string::npos) return n;
    return desktop.mappings.size();
  };
  EXPECT_LT(first_of("gamepad_reach_stacker"), first_of("keyboard"));
  // every shipped mapping, found by its class in the device folder (a new machine's join without an edit):
  // sticks, then game pads, then keyboards; the cabin has no keyboard
  std::size_t shipped = 0;
  for (const auto& entry : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/devices"))
    shipped += entry.path().extension() == ".yaml";
  EXPECT_EQ(desktop.mappings.size(), shipped);
  EXPECT_TRUE(std::is_sorted(
      desktop.mappings.begin(), desktop.mappings.end(),
      [](const std::string& a, const std::string& b) { return device_class_of(a) < device_class_of(b); }));
  EXPECT_EQ(device_class_of(desktop.mappings.front()), DeviceClass::kSticks);
  EXPECT_EQ(device_class_of(desktop.mappings.back()), DeviceClass::kKeyboards);
  // a monitor shows the machine's design view: its line of sight and field of view
  EXPECT_TRUE(desktop.displays[0].from_sight && desktop.displays[0].fov_from_sight);
  EXPECT_FALSE(load_profile(resolve_profile("immersive", HARBOUR_DATA_DIR)).displays[0].from_sight);
  const Profile medium = load_profile(resolve_profile("medium", HARBOUR_DATA_DIR));
  EXPECT_EQ(medium.displays[0].width, 3840);
  const Profile immersive = load_profile(resolve_profile("immersive", HARBOUR_DATA_DIR));
  EXPECT_EQ(immersive.displays.size(), 4u);
  EXPECT_TRUE(immersive.motion.has_value());
  EXPECT_NEAR(immersive.displays[1].yaw_rad, std::numbers::pi / 3.0, 1e-12);
  ASSERT_TRUE(immersive.displays[3].frustum_rad.has_value());  // the floor window behind the eye
  EXPECT_NEAR((*immersive.displays[3].frustum_rad)[2], -28.0 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_FALSE(immersive.displays[0].frustum_rad.has_value());
  EXPECT_EQ(immersive.windows, Profile::Windows::kPerDisplay);  // a window on each projector
  EXPECT_EQ(desktop.windows, Profile::Windows::kShared);
  // the sound: a headset at the desktop, two speakers by the big screen, 5.1 round the cabin
  ASSERT_TRUE(desktop.sound && medium.sound && immersive.sound);
  EXPECT_EQ(desktop.sound->output, Profile::Sound::Output::kHeadphones);
  EXPECT_EQ(medium.sound->output, Profile::Sound::Output::kSpeakers);
  EXPECT_EQ(immersive.sound->output, Profile::Sound::Output::kSurround51);
  EXPECT_FALSE(desktop.stereo.has_value());
  EXPECT_THROW(resolve_profile("cockpit", HARBOUR_DATA_DIR), std::runtime_error);
}

std::string profile_error(const std::string& text) {
  const std::string path = scenes::temp_path("harbour_profile.yaml");
  { std::ofstream(path) << text; }
  try {
    load_profile(path);
  } catch (const io::DataError& e) {
    return e.what();
  }
  return "";
}

TEST(Profiles, BadProfilesNameFileLineAndField) {
  const std::string display =
      "    - {name: m, width: 1920, height: 1080, view: {yaw_deg: 0, pitch_deg: 0, roll_deg: 0}, fov: "
      "{horizontal_deg: 60, vertical_deg: 40}}\n";
  const std::string ok =
      "profile:\n  name: p\n  devices: []\n  displays:\n" + display + "  motion: off\n  head_tracking: off\n";
  EXPECT_EQ(profile_error(ok), "");
  EXPECT_NE(profile_error("profile:\n  name: p\n  devices: [nowhere.yaml]\n  displays:\n" + display +
                          "  motion: off\n  head_tracking: off\n")
                .find("harbour_profile.yaml:3: profile.devices[0]: no such file"),
            std::string::npos);
  EXPECT_NE(profile_error(
                "profile:\n  name: p\n  devices: []\n  displays: []\n  motion: off\n  head_tracking: off\n")
                .find("profile.displays: at least one display"),
            std::string::npos);
  EXPECT_NE(profile_error(ok + "  steroe: true\n").find("unknown key 'steroe'"), std::string::npos);
  // a class of mappings in a folder: the folder there, the class one of three, some mapping of it in it
  const std::string devices =
      "profile:\n  name: p\n  devices:\n    - {folder: " HARBOUR_DATA_DIR "/devices, class: ";
  const std::string rest = "}\n  displays:\n" + display + "  motion: off\n  head_tracking: off\n";
  EXPECT_EQ(profile_error(devices + "game_pads" + rest), "");
  EXPECT_NE(profile_error(devices + "wheels" + rest)
                .find("harbour_profile.yaml:4: profile.devices[0].class: sticks, game_pads or keyboards, not "
                      "'wheels'"),
            std::string::npos);
  EXPECT_NE(profile_error("profile:\n  name: p\n  devices:\n    - {folder: nowhere, class: sticks" + rest)
                .find("profile.devices[0].folder: no such folder"),
            std::string::npos);
  const std::string empty = scenes::temp_path("harbour_no_devices");
  std::filesystem::create_directories(empty);
  EXPECT_NE(
      profile_error("profile:\n  name: p\n  devices:\n    - {folder: " + empty + ", class: sticks" + rest)
          .find("profile.devices[0]: no sticks mapping in"),
      std::string::npos);
  // a file there that is no mapping is named, not passed over
  EXPECT_NE(profile_error("profile:\n  name: p\n  devices:\n    - {folder: " HARBOUR_DATA_DIR
                          "/profiles, class: sticks" +
                          rest)
                .find("mapping: missing"),
            std::string::npos);
  const std::string skewed =
      "    - {name: m, width: 1920, height: 1080, view: {yaw_deg: 0, pitch_deg: 0, roll_deg: 0}, fov: "
      "{left_deg: 10, right_deg: -10, bottom_deg: -5, top_deg: 5}}\n";
  EXPECT_NE(profile_error("profile:\n  name: p\n  devices: []\n  displays:\n" + skewed +
                          "  motion: off\n  head_tracking: off\n")
                .find("needs left < right and bottom < top"),
            std::string::npos);
  EXPECT_NE(profile_error("profile:\n  name: p\n  devices: []\n  displays:\n" + display +
                          "  motion: maybe\n  head_tracking: off\n")
                .find("profile.motion: expected off or a mapping"),
            std::string::npos);
  EXPECT_NE(profile_error("profile:\n  name: p\n  devices: []\n  displays:\n" + display +
                          "  motion: off\n  head_tracking: {opentrack_port: 70000}\n")
                .find("opentrack_port"),
            std::string::npos);
  // stereo and windows
  const std::string stereo = "profile:\n  name: p\n  devices: []\n  displays:\n" + display +
                             "  motion: off\n  head_tracking: off\n  windows: per_display\n  stereo: ";
  EXPECT_EQ(profile_error(stereo + "{mode: anaglyph, eye_separation_mm: 63, convergence_m: 2.5}\n"), "");
  {
    const std::string path = scenes::temp_path("harbour_profile.yaml");
    const Profile p = load_profile(path);
    ASSERT_TRUE(p.stereo.has_value());
    EXPECT_EQ(p.stereo->mode, Profile::Stereo::Mode::kAnaglyph);
    EXPECT_NEAR(p.stereo->eye_separation_m, 0.063, 1e-12);
    EXPECT_NEAR(p.stereo->convergence_m, 2.5, 1e-12);
    EXPECT_EQ(p.windows, Profile::Windows::kPerDisplay);
  }
  EXPECT_NE(
      profile_error(stereo + "{mode: quad_buffer, eye_separation_mm: 64, convergence_m: 3}\n")
          .find("harbour_profile.yaml:9: profile.stereo.mode: quad_buffer needs an OpenGL stereo visual"),
      std::string::npos);
  // sound: two speakers where it does not say; off; a volume; an output that is not one
  EXPECT_EQ(profile_error(ok), "");
  EXPECT_TRUE(load_profile(scenes::temp_path("harbour_profile.yaml")).sound.has_value());
  EXPECT_EQ(profile_error(ok + "  sound: off\n"), "");
  EXPECT_FALSE(load_profile(scenes::temp_path("harbour_profile.yaml")).sound.has_value());
  EXPECT_EQ(profile_error(ok + "  sound: {output: headphones, volume: 0.5}\n"), "");
  EXPECT_EQ(load_profile(scenes::temp_path("harbour_profile.yaml")).sound->volume, 0.5);
  EXPECT_NE(profile_error(ok + "  sound: {output: mono}\n")
                .find("harbour_profile.yaml:8: profile.sound.output: 'mono' is not speakers, headphones or "
                      "surround_5_1"),
            std::string::npos);
  EXPECT_NE(profile_error(stereo + "{mode: sbs, eye_separation_mm: 64, convergence_m: 3}\n")
                .find("'sbs' is not side_by_side or anaglyph"),
            std::string::npos);
  EXPECT_NE(profile_error(stereo + "{mode: anaglyph, eye_separation_mm: 640, convergence_m: 3}\n")
                .find("eye_separation_mm"),
            std::string::npos);
  EXPECT_EQ(profile_error(stereo + "off\n"), "");
  EXPECT_NE(profile_error("profile:\n  name: p\n  devices: []\n  displays:\n" + display +
                          "  motion: off\n  head_tracking: off\n  windows: many\n")
                .find("profile.windows: 'many' is not shared or per_display"),
            std::string::npos);
}

}  // namespace
}  // namespace harbour::station
