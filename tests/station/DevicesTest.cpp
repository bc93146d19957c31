// The station driven through real SDL2 joysticks (virtual ones, SDL_JoystickAttachVirtualEx) and a shipped
// mapping: a scripted person moves the sticks and presses the buttons; nothing reaches the simulation but
// what SDL reports through the mapping.

#include <gtest/gtest.h>

#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include <yaml-cpp/yaml.h>

#include "harbour/io/RecordingFile.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/station/DeviceMappingFile.h"
#include "harbour/station/Station.h"
#include "scenes/StationScenes.h"
#include "scenes/StsScenes.h"

namespace harbour::station {
namespace {

// A T.16000M-like flight stick; its instance id.
int attach_stick() {
  const int index = scenes::attach_flight_stick();
  EXPECT_GE(index, 0) << SDL_GetError();
  return SDL_JoystickGetDeviceInstanceID(index);
}

// A pad as Linux's xpad driver presents an Xbox 360 controller (axes: left x, y, left trigger, right x, y,
// right trigger; 11 buttons; the d-pad a hat) under a name SDL's database does not know.
SDL_VirtualJoystickDesc raw_pad() {
  SDL_VirtualJoystickDesc desc{};
  desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
  desc.type = SDL_JOYSTICK_TYPE_UNKNOWN;
  desc.naxes = 6;
  desc.nbuttons = 11;
  desc.nhats = 1;
  desc.vendor_id = 0x1209;  // pid.codes' test vendor and product: in no pad database
  desc.product_id = 0x0001;
  desc.name = "Harbour test pad";
  return desc;
}

// Attaches the raw pad; its instance id.
int attach_raw_pad() {
  const SDL_VirtualJoystickDesc desc = raw_pad();
  const int index = SDL_JoystickAttachVirtualEx(&desc);
  EXPECT_GE(index, 0) << SDL_GetError();
  return SDL_JoystickGetDeviceInstanceID(index);
}

// SDL's own mapping of the Xbox 360 pad on Linux, for the test pad's GUID: what a person puts in
// SDL_GAMECONTROLLERCONFIG for a pad SDL does not know (its GUID read from `harboursim devices`).
std::string xbox_mapping_for_the_raw_pad() {
  init_sdl_joysticks();
  const SDL_VirtualJoystickDesc desc = raw_pad();
  const int index = SDL_JoystickAttachVirtualEx(&desc);
  char guid[33];
  SDL_JoystickGetGUIDString(SDL_JoystickGetDeviceGUID(index), guid, sizeof guid);
  EXPECT_FALSE(SDL_IsGameController(index));  // SDL does not know it
  SDL_JoystickDetachVirtual(index);
  char* xbox =
      SDL_GameControllerMappingForGUID(SDL_JoystickGetGUIDFromString("030000005e0400008e02000010010000"));
  EXPECT_NE(xbox, nullptr);
  std::string line = xbox ? xbox : "";
  SDL_free(xbox);
  quit_sdl_joysticks();
  const std::size_t name_end = line.find(',', line.find(',') + 1);
  return std::string(guid) + ",Harbour test pad" + line.substr(name_end);
}

int index_of(SDL_JoystickID instance) {
  for (int i = 0; i < SDL_NumJoysticks(); ++i)
    if (SDL_JoystickGetDeviceInstanceID(i) == instance) return i;
  return -1;
}

// The raw axis value that reads `value` through binding `b` (inverse of calibration, dead zone, expo).
Sint16 raw_for(const Binding& b, double value) {
  double s = b.invert ? -value : value;
  if (std::abs(s) < 1e-9) return static_cast<Sint16>(b.calibration.center);
  const double target = std::min(std::abs(s), 1.0);
  double x = target;  // solve (1 - e) x + e x^3 = target
  for (int k = 0; k < 30; ++k)
    x -= ((1.0 - b.expo) * x + b.expo * x * x * x - target) / ((1.0 - b.expo) + 3.0 * b.expo * x * x);
  const double n = b.dead_zone + x * (1.0 - b.dead_zone);
  const double raw = s > 0 ? b.calibration.center + n * (b.calibration.max - b.calibration.center)
                           : b.calibration.center - n * (b.calibration.center - b.calibration.min);
  return static_cast<Sint16>(std::lround(std::clamp(raw, -32768.0, 32767.0)));
}

// A person at the desk: decides like the autopilot, acts only through the sticks' axes, buttons and hats.
class StickPerson {
 public:
  StickPerson(const sim::ExerciseSettings& exercise, const DeviceMapping& mapping, scene::ControlTable table)
      : pilot_(exercise), mapping_(mapping), table_(std::move(table)) {
    for (const DeviceMatch& d : mapping.devices)
      plug(d.id);
  }
  ~StickPerson() {
    for (auto& [id, stick] : sticks_) {
      if (stick.controller) SDL_GameControllerClose(stick.controller);
      SDL_JoystickClose(stick.joystick);
    }
  }
  void plug(const std::string& id) {
    Stick& s = sticks_[id];
    const bool pad = std::any_of(mapping_.devices.begin(), mapping_.devices.end(),
                                 [&](const DeviceMatch& d) { return d.id == id && d.game_controller; });
    s.instance = pad ? attach_raw_pad() : attach_stick();
    s.joystick = SDL_JoystickOpen(index_of(s.instance));
    if (pad) {
      s.controller = SDL_GameControllerOpen(index_of(s.instance));
      EXPECT_NE(s.controller, nullptr) << "SDL has no mapping for the pad: " << SDL_GetError();
    }
  }
  void unplug(const std::string& id) {
    Stick& s = sticks_[id];
    if (s.controller) SDL_GameControllerClose(s.controller);
    SDL_JoystickClose(s.joystick);
    SDL_JoystickDetachVirtual(index_of(s.instance));
    s = {};
  }
  // on the step thread, before the station samples the devices
  void act(const sim::Simulation& sim) {
    const scene::Controls want = pilot_.next(sim);
    std::map<std::pair<std::string, int>, Uint8> hats;
    for (std::size_t n = 0; n < mapping_.bindings.size(); ++n) {
      const Binding& b = mapping_.bindings[n];
      const std::string& id = mapping_.devices[static_cast<std::size_t>(b.device)].id;
      const Stick& stick = sticks_[id];
      SDL_Joystick* j = stick.joystick;
      if (!j) continue;
      const double v = want.value[static_cast<std::size_t>(b.slot)];
      // the physical input: the binding's own, or on a game controller what SDL's mapping reads it from
      Binding::Source source = b.source;
      int index = b.index, hat_direction = b.hat_direction;
      bool trigger = false;
      if (stick.controller) {
        const SDL_GameControllerButtonBind bind =
            b.source == Binding::Source::kAxis
                ? SDL_GameControllerGetBindForAxis(stick.controller,
                                                   static_cast<SDL_GameControllerAxis>(b.index))
                : SDL_GameControllerGetBindForButton(stick.controller,
                                                     static_cast<SDL_GameControllerButton>(b.index));
        trigger = b.index >= SDL_CONTROLLER_AXIS_TRIGGERLEFT && b.source == Binding::Source::kAxis;
        if (bind.bindType == SDL_CONTROLLER_BINDTYPE_AXIS) {
          index = bind.value.axis;
        } else if (bind.bindType == SDL_CONTROLLER_BINDTYPE_BUTTON) {
          source = Binding::Source::kButton;
          index = bind.value.button;
        } else if (bind.bindType == SDL_CONTROLLER_BINDTYPE_HAT) {
          source = Binding::Source::kHat;
          index = bind.value.hat.hat;
          hat_direction = bind.value.hat.hat_mask;
        }
      }
      // a button selecting a switch's position is held while the switch should be there; one on an axis
      // while the lever should be on its side
      const bool selects = table_[b.slot].kind == scene::ControlKind::kSwitch && !b.toggle;
      const bool held = selects ? std::abs(v - b.value) < 0.5 : v * b.value > 0.5;
      switch (source) {
        case Binding::Source::kAxis: {
          const Sint16 raw = raw_for(b, v);  // a trigger reads the raw axis's whole travel as 0..32767
          SDL_JoystickSetVirtualAxis(j, index, trigger ? static_cast<Sint16>(2 * raw - 32768) : raw);
          break;
        }
        case Binding::Source::kHat:
          if (held)
            hats[{id, index}] |= static_cast<Uint8>(hat_direction);
          else
            hats[{id, index}] |= 0;
          break;
        case Binding::Source::kButton:
          if (b.toggle) {
            // a toggle: press once when the switch should change, release the next step
            bool& pressed = toggle_pressed_[n];
            double& position = toggle_position_[b.slot];
            const bool press = !pressed && position != v;
            if (press) position = v;
            pressed = press;
            SDL_JoystickSetVirtualButton(j, index, press);
          } else {
            SDL_JoystickSetVirtualButton(j, index, held);
          }
          break;
        case Binding::Source::kKeys:
          break;
      }
    }
    for (const auto& [at, bits] : hats)
      if (SDL_Joystick* j = sticks_[at.first].joystick) SDL_JoystickSetVirtualHat(j, at.second, bits);
  }

 private:
  struct Stick {
    SDL_JoystickID instance = -1;
    SDL_Joystick* joystick = nullptr;
    SDL_GameController* controller = nullptr;  // a pad SDL maps
  };

  sim::GantryAutopilot pilot_;
  DeviceMapping mapping_;
  scene::ControlTable table_;
  std::map<std::string, Stick> sticks_;
  std::map<std::size_t, bool> toggle_pressed_;
  std::map<int, double> toggle_position_;
};

struct Desk {
  sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  SessionOptions options;
  std::unique_ptr<Session> session;
  std::unique_ptr<Station> station;
  std::unique_ptr<StickPerson> person;
  DeviceMapping mapping;

  explicit Desk(const std::string& name, const std::string& mapping_file = "sts_dual_joystick.yaml") {
    init_sdl_joysticks();
    options.trainee = "t1";
    options.database = scenes::fresh_database(name + ".db");
    options.record = scenes::temp_path(name + ".hsrc");
    options.loop.time_scale = 10.0;
    session = std::make_unique<Session>(exercise, options);
    mapping = load_device_mapping(std::string(HARBOUR_DATA_DIR) + "/devices/" + mapping_file,
                                  session->simulation().control_table());
    person = std::make_unique<StickPerson>(exercise, mapping, session->simulation().control_table());
    station = std::make_unique<Station>(*session);
    station->use_devices(std::make_unique<DeviceInput>(session->simulation().control_table(), mapping));
  }
  ~Desk() { quit_sdl_joysticks(); }

  // The person at the devices until the exercise is over (a minute at most); the attempt as stored.
  SessionResult play() {
    DeviceInput* input = station->devices();
    session->loop().set_sampler([this, input] {
      person->act(session->simulation());
      return input->sample();
    });
    station->start();
    session->start();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!session->over() && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    station->stop();
    return session->finish(SessionEnd::kRan);
  }
};

TEST(Devices, APersonOnTwoJoysticksDischargesABoxOntoTheTruck) {
  Desk desk("harbour_desk_discharge");
  ASSERT_EQ(desk.station->devices()->bound_devices(), 2);
  const SessionResult result = desk.play();
  EXPECT_EQ(result.metrics.moves_completed, 1);  // the box is on the truck
  EXPECT_EQ(result.metrics.collisions, 0);
  EXPECT_EQ(result.status, "finished");
  const sim::Recording recording = io::read_recording(desk.options.record);
  // the evaluation made live, on the step thread, is the one a replay of the recording makes
  sim::Evaluator replayed(desk.exercise);
  const sim::ReplayResult replay =
      sim::replay(desk.exercise.scenario, recording, -1,
                  [&](const sim::Simulation& s, const scene::Controls& in) { replayed.observe(s, in); });
  EXPECT_FALSE(replay.first_mismatch.has_value());
  EXPECT_EQ(replay.checkpoints_checked, static_cast<int>(recording.checkpoints.size()));
  EXPECT_EQ(replayed.metrics().moves_completed, result.metrics.moves_completed);
  EXPECT_EQ(replayed.metrics().cycle_times_s, result.metrics.cycle_times_s);
  EXPECT_EQ(replayed.metrics().landing_sway_m, result.metrics.landing_sway_m);
  EXPECT_EQ(replayed.score().total, result.score.total);
}

TEST(Devices, APersonOnAGamePadDischargesABoxOntoTheTruck) {
  // a pad SDL does not know, made a game controller by a mapping line in SDL_GAMECONTROLLERCONFIG: the
  // shipped gamepad.yaml reads it by SDL's names (left stick the trolley and gantry, right stick the hoist)
  const std::string line = xbox_mapping_for_the_raw_pad();
  ASSERT_EQ(why_bad_controller_mapping(line), "");
  setenv("SDL_GAMECONTROLLERCONFIG", line.c_str(), 1);
  {
    Desk desk("harbour_desk_pad", "gamepad.yaml");
    ASSERT_EQ(desk.station->devices()->bound_devices(), 1);
    bool connected = false;
    for (const DeviceEvent& e : desk.station->devices()->take_events())
      connected = connected || (e.kind == DeviceEvent::Kind::kConnected && e.name == "Harbour test pad");
    EXPECT_TRUE(connected);
    const SessionResult result = desk.play();
    EXPECT_EQ(result.metrics.moves_completed, 1);  // the box is on the truck
    EXPECT_EQ(result.metrics.collisions, 0);
    EXPECT_EQ(result.status, "finished");
    const sim::ReplayResult replay =
        sim::replay(desk.exercise.scenario, io::read_recording(desk.options.record));
    EXPECT_FALSE(replay.first_mismatch.has_value());
  }
  unsetenv("SDL_GAMECONTROLLERCONFIG");
}

TEST(Devices, APadIsReadThroughTheMappingFilesOwnLineAndOneLackingAnInputIsUnfit) {
  init_sdl_joysticks();
  const int instance = attach_raw_pad();
  char guid[33];
  SDL_JoystickGetGUIDString(SDL_JoystickGetDeviceGUID(index_of(instance)), guid, sizeof guid);
  SDL_Joystick* pad = SDL_JoystickOpen(index_of(instance));
  ASSERT_NE(pad, nullptr);
  // an odd wiring, as an interface box might have: the mapping line says where each input is
  const std::string file = scenes::temp_path("harbour_odd_pad.yaml");
  std::ofstream(file) << "mapping:\n  name: odd pad\n  devices:\n    - {id: pad, game_controller: true}\n"
                         "  bindings:\n"
                         "    - {control: trolley, device: pad, axis: lefty, invert: true}\n"
                         "    - {control: lock, device: pad, button: a}\n"
                         "    - {control: boom, device: pad, button: dpup, value: 1.0}\n"
                         "    - {control: emergency_stop, device: pad, button: back, hold_s: 0.5}\n"
                         "  controller_mappings:\n"
                         "    - \""
                      << guid << ",Odd pad,a:b7,back:b4,lefty:a2,leftx:a3,dpup:h0.1,platform:Linux,\"\n";
  const scene::ControlTable table = scenes::sts_controls();
  const auto at = [&](const char* label) { return static_cast<std::size_t>(table.find(label)); };
  {
    DeviceInput input(table, load_device_mapping(file, table));
    input.maintain();
    ASSERT_EQ(input.bound_devices(), 1);
    const std::vector<DeviceEvent> events = input.take_events();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].name, "Odd pad");        // its name as a game controller
    SDL_JoystickSetVirtualAxis(pad, 2, -32768);  // raw axis 2 is its left stick's y: pushed up
    SDL_JoystickSetVirtualButton(pad, 0, 1);     // raw button 0 is nothing here
    scene::Controls c = input.sample();
    EXPECT_EQ(c.value[at("trolley")], 1.0);
    EXPECT_EQ(c.value[at("lock")], 0.0);
    SDL_JoystickSetVirtualButton(pad, 7, 1);  // its A
    SDL_JoystickSetVirtualHat(pad, 0, SDL_HAT_UP);
    SDL_JoystickSetVirtualButton(pad, 4, 1);  // its Back, the emergency stop: held
    c = input.sample();
    EXPECT_EQ(c.value[at("lock")], 1.0);
    EXPECT_EQ(c.value[at("boom")], 1.0);
    EXPECT_EQ(c.value[at("emergency_stop")], 0.0);  // not yet held half a second
    std::this_thread::sleep_for(std::chrono::milliseconds(600));
    EXPECT_EQ(input.sample().value[at("emergency_stop")], 1.0);
  }
  {
    // the shipped pad mapping binds inputs this wiring lacks: the pad is unfit, and the event says which
    DeviceInput input(table,
                      load_device_mapping(std::string(HARBOUR_DATA_DIR) + "/devices/gamepad.yaml", table));
    input.maintain();
    EXPECT_EQ(input.bound_devices(), 0);
    const std::vector<DeviceEvent> events = input.take_events();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, DeviceEvent::Kind::kUnfit);
    EXPECT_NE(events[0].detail.find("gamepad.yaml:13: bindings.hoist: 'righty'"), std::string::npos)
        << events[0].detail;
  }
  SDL_JoystickClose(pad);
  quit_sdl_joysticks();
  // without the line SDL maps nothing: a game_controller device does not take a raw joystick
  init_sdl_joysticks();
  attach_raw_pad();
  const DeviceMapping plain =
      load_device_mapping(std::string(HARBOUR_DATA_DIR) + "/devices/gamepad.yaml", table);
  {
    DeviceInput input(table, plain);
    input.maintain();
    EXPECT_EQ(input.bound_devices(), 0);
    EXPECT_TRUE(input.take_events().empty());
  }
  quit_sdl_joysticks();
}

TEST(Devices, SdlKnowsTheCommonPadsAndTheyHaveEveryInputTheShippedPadMappingsBind) {
  init_sdl_joysticks();
  // as Linux reports them: Xbox 360, Xbox One, DualShock 4 (two models, and over Bluetooth), Switch Pro
  const std::vector<std::string> pads{"030000005e0400008e02000010010000", "030000005e040000ea02000001030000",
                                      "030000004c050000cc09000011810000", "030000004c050000c405000011810000",
                                      "050000004c050000cc09000000810000", "030000007e0500000920000011810000"};
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(HARBOUR_DATA_DIR) + "/devices")) {
    const YAML::Node root = YAML::LoadFile(entry.path().string())["mapping"];
    if (!root["devices"][0]["game_controller"]) continue;
    for (const std::string& pad : pads) {
      char* raw = SDL_GameControllerMappingForGUID(SDL_JoystickGetGUIDFromString(pad.c_str()));
      ASSERT_NE(raw, nullptr) << pad;
      const std::string mapping = std::string(",") + raw;
      SDL_free(raw);
      for (const YAML::Node& b : root["bindings"]) {
        const std::string input = b["axis"] ? b["axis"].Scalar() : b["button"].Scalar();
        EXPECT_NE(mapping.find("," + input + ":"), std::string::npos)
            << entry.path().filename() << " binds " << input << ", which " << mapping << " lacks";
      }
    }
    ++checked;
  }
  EXPECT_GE(checked, static_cast<int>(sim::machine_types().size()));  // a pad for every machine at least
  quit_sdl_joysticks();
}

TEST(Devices, UnpluggingTheHoistStickStopsTheLoadSmoothlyAndPluggingItBackResumes) {
  Desk desk("harbour_desk_unplug");
  DeviceInput* input = desk.station->devices();
  StickPerson* person = desk.person.get();
  RealTimeLoop& loop = desk.session->loop();
  const int hoist = desk.session->simulation().control_table().find("hoist");
  std::int64_t unplugged_at = -1, replugged_at = -1;
  double hoist_after_unplug = 99.0, worst_jerk_mps2 = 0.0, last_vz = 0.0, speed_at_unplug = 0.0;
  std::int64_t stopped_at = -1;
  loop.set_sampler([&] {
    const sim::Simulation& sim = desk.session->simulation();
    const double vz = sim.world().linear_velocity(sim.machine_as<sim::StsCrane>().spreader_body()).z;
    if (unplugged_at < 0 && sim.machine_as<sim::StsCrane>().locked_container() && vz > 0.5) {
      person->unplug("right");  // hoisting a locked box at speed: the hoist stick's cable comes out
      unplugged_at = sim.steps();
      speed_at_unplug = vz;
    } else if (unplugged_at >= 0 && replugged_at < 0) {
      if (sim.steps() == unplugged_at + 1)
        hoist_after_unplug = loop.last_controls().value[static_cast<std::size_t>(hoist)];
      worst_jerk_mps2 = std::max(worst_jerk_mps2, std::abs(vz - last_vz) / sim::Simulation::kStep_s);
      if (stopped_at < 0 && std::abs(vz) < 0.01) stopped_at = sim.steps();
      if (sim.steps() == unplugged_at + 5000) {
        person->plug("right");
        replugged_at = sim.steps();
      }
    }
    last_vz = vz;
    person->act(sim);
    return input->sample();
  });
  desk.station->start();
  desk.session->start();
  bool saw_lost = false, saw_back = false, display_showed_it = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
  while (!desk.session->over() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    for (const std::string& m : desk.station->take_messages()) {
      saw_lost =
          saw_lost || m.find("input device right (Thrustmaster T.16000M) LOST: safe: hoist, lock, unlock") !=
                          std::string::npos;
      saw_back = saw_back || (saw_lost && m.find("input device right (Thrustmaster T.16000M) connected") !=
                                              std::string::npos);
    }
    const scene::Snapshot* s = loop.latest_snapshot(kConsoleReader);
    display_showed_it = display_showed_it || (s && s->devices_missing == 1);
  }
  desk.station->stop();
  const SessionResult result = desk.session->finish(SessionEnd::kRan);
  ASSERT_GE(unplugged_at, 0);
  EXPECT_EQ(hoist_after_unplug, 0.0);  // the very next step reads the lever neutral
  ASSERT_GE(stopped_at, 0);
  const double stop_s = static_cast<double>(stopped_at - unplugged_at) * sim::Simulation::kStep_s;
  std::printf("unplugged at %.2f m/s: stopped in %.2f s, worst change of speed %.2f m/s^2\n", speed_at_unplug,
              stop_s, worst_jerk_mps2);
  EXPECT_LT(stop_s, 4.0);           // the hoist drive ramps the load to a stop ...
  EXPECT_GT(stop_s, 0.2);           // ... it does not halt it in a step
  EXPECT_LT(worst_jerk_mps2, 8.0);  // no jump (the rope bounces a little): a one-step halt is ~500 m/s^2
  EXPECT_TRUE(saw_lost);
  EXPECT_TRUE(display_showed_it);
  EXPECT_TRUE(saw_back);
  EXPECT_GE(replugged_at, 0);
  EXPECT_EQ(result.metrics.moves_completed, 1);  // picked up again and finished
}

}  // namespace
}  // namespace harbour::station

namespace harbour::station {
namespace {

// Two operator-chair levers as an interface box presents them (the name levers_iso.yaml matches).
int attach_lever() {
  SDL_VirtualJoystickDesc desc{};
  desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
  desc.type = SDL_JOYSTICK_TYPE_FLIGHT_STICK;
  desc.naxes = 2;
  desc.nbuttons = 4;
  desc.name = "Lever";
  const int index = SDL_JoystickAttachVirtualEx(&desc);
  EXPECT_GE(index, 0) << SDL_GetError();
  return index;
}

TEST(Devices, APersonOnTwoLeversSlewsTheMobileHarbourCraneAndShutsItsGrab) {
  // the ISO pattern: left lever sideways slews, right lever sideways works the grab (right shuts)
  init_sdl_joysticks();
  const sim::ExerciseSettings exercise =
      io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_free_practice.yaml");
  SessionOptions options;
  options.trainee = "t1";
  options.database = scenes::fresh_database("harbour_desk_mhc.db");
  options.record = scenes::temp_path("harbour_desk_mhc.hsrc");
  options.loop.time_scale = 10.0;
  Session session(exercise, options);
  const scene::ControlTable& table = session.simulation().control_table();
  ASSERT_EQ(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/levers_iso.yaml", table), "");
  EXPECT_NE(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/sts_dual_joystick.yaml", table), "");
  DeviceMapping mapping =
      load_device_mapping(std::string(HARBOUR_DATA_DIR) + "/devices/levers_iso.yaml", table);
  const int left_index = attach_lever(), right_index = attach_lever();
  SDL_Joystick* left = SDL_JoystickOpen(left_index);
  SDL_Joystick* right = SDL_JoystickOpen(right_index);
  ASSERT_TRUE(left && right);
  Station station(session);
  station.use_devices(std::make_unique<DeviceInput>(table, mapping));
  ASSERT_EQ(station.devices()->bound_devices(), 2);
  DeviceInput* input = station.devices();
  const auto& crane = dynamic_cast<const sim::MobileHarbourCrane&>(session.simulation().machine());
  session.loop().set_sampler([&] {
    const bool working = session.simulation().time_s() < 8.0;
    SDL_JoystickSetVirtualAxis(left, 0, working ? 32767 : 0);   // slew
    SDL_JoystickSetVirtualAxis(right, 0, working ? 32767 : 0);  // shut the grab
    return input->sample();
  });
  station.start();
  session.start();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (session.simulation().time_s() < 12.0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  station.stop();
  const SessionResult result = session.finish(SessionEnd::kInterrupted);
  EXPECT_GT(crane.slew_rad(), 0.3);  // about 8 s at up to 0.126 rad/s after its ramp
  EXPECT_LT(crane.grab_opening(), 0.05);
  const sim::Recording recording = io::read_recording(options.record);
  const sim::ReplayResult replay = sim::replay(exercise.scenario, recording);
  EXPECT_FALSE(replay.first_mismatch.has_value());
  SDL_JoystickClose(left);
  SDL_JoystickClose(right);
  quit_sdl_joysticks();
}

}  // namespace
}  // namespace harbour::station

namespace harbour::station {
namespace {

TEST(Devices, AKeyTappedBetweenTwoSamplesStillStepsItsSwitch) {
  // the window pumps SDL's events at its frame rate (a few a second on a slow display); a tap pressed and
  // released within one pump never shows in SDL's keyboard state, so the window passes each key that went
  // down and the next sample reads it pressed: P sets the tractor's parking brake, P again releases it
  SDL_SetHint(SDL_HINT_VIDEODRIVER, "dummy");
  ASSERT_EQ(SDL_InitSubSystem(SDL_INIT_VIDEO), 0) << SDL_GetError();
  const sim::Simulation tractor(
      io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_free_practice.yaml").scenario);
  const scene::ControlTable& table = tractor.control_table();
  const auto parking = static_cast<std::size_t>(table.find("parking_brake"));
  {
    DeviceInput input(table, load_device_mapping(HARBOUR_DATA_DIR "/devices/keyboard_driving.yaml", table));
    EXPECT_EQ(input.sample().value[parking], 0.0);  // released
    input.key_went_down(SDL_SCANCODE_P);            // pressed and up again before this sample
    EXPECT_EQ(input.sample().value[parking], 1.0);
    EXPECT_EQ(input.sample().value[parking], 1.0);  // a switch stays where it was put
    input.key_went_down(SDL_SCANCODE_P);
    EXPECT_EQ(input.sample().value[parking], 0.0);
    // without the window's word the tap is lost: SDL's state never had the key down
    EXPECT_EQ(input.sample().value[parking], 0.0);
  }
  SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

TEST(Devices, TheDrivingKeyboardFitsTheTractorAndTheCranesKeyboardsDoNot) {
  // a profile's keyboards are tried in order: each machine finds the one made for it
  const sim::Simulation tractor(
      io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_free_practice.yaml").scenario);
  const scene::ControlTable& table = tractor.control_table();
  EXPECT_EQ(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/keyboard_driving.yaml", table), "");
  EXPECT_NE(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/keyboard.yaml", table), "");
  EXPECT_NE(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/keyboard_slewing.yaml", table), "");
  const sim::Simulation mhc(io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_free_practice.yaml").scenario);
  EXPECT_NE(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/keyboard_driving.yaml", mhc.control_table()),
            "");
  // the RTG lacks the STS's boom and flippers: its own keyboard comes before the STS's does not fit it
  const sim::Simulation rtg(
      io::load_exercise(HARBOUR_DATA_DIR "/exercises/rtg_truck_to_block.yaml").scenario);
  EXPECT_EQ(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/keyboard_rtg.yaml", rtg.control_table()), "");
  EXPECT_NE(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/keyboard.yaml", rtg.control_table()), "");
  EXPECT_NE(why_mapping_does_not_fit(HARBOUR_DATA_DIR "/devices/keyboard_rtg.yaml", table), "");
}

}  // namespace
}  // namespace harbour::station
