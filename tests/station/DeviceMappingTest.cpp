#include "harbour/station/DeviceMapping.h"

#include <gtest/gtest.h>

#include <SDL.h>

#include <filesystem>
#include <fstream>

#include "harbour/io/DataError.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/station/DeviceMappingFile.h"
#include "scenes/MachineControls.h"
#include "scenes/StsScenes.h"

namespace harbour::station {
namespace {

TEST(DeviceMapping, AxisShapingMatchesHandComputedValues) {
  Binding b;
  b.dead_zone = 0.1;
  b.expo = 0.5;
  // n = 16384 / 32767; live = (n - 0.1) / 0.9; 0.5 live + 0.5 live^3
  EXPECT_NEAR(shape_axis(b, 16384), 0.26613147100002016, 1e-12);
  // below the centre the lower half's span counts: n = -8000 / 32768
  EXPECT_NEAR(shape_axis(b, -8000), -0.08213213086128235, 1e-12);
  EXPECT_EQ(shape_axis(b, 3000), 0.0);  // inside the dead zone (3000 / 32767 < 0.1)
  EXPECT_EQ(shape_axis(b, 32767), 1.0);
  EXPECT_EQ(shape_axis(b, -32768), -1.0);
  EXPECT_EQ(shape_axis(b, 40000), 1.0);  // beyond the calibration: clamped
  b.invert = true;
  EXPECT_NEAR(shape_axis(b, 16384), -0.26613147100002016, 1e-12);
  // a pedal: one-sided 1000..9000, dead zone at rest, inverted (pressed reads low)
  Binding pedal;
  pedal.calibration = {1000.0, 0.0, 9000.0, false};
  pedal.dead_zone = 0.05;
  pedal.invert = true;
  EXPECT_NEAR(shape_axis(pedal, 5000), 0.5263157894736842, 1e-12);  // 1 - (0.5 - 0.05) / 0.95
  // a calibration whose centre is off the middle: each half scales to its own end
  Binding off;
  off.calibration = {0.0, 1000.0, 5000.0, true};
  EXPECT_DOUBLE_EQ(shape_axis(off, 500), -0.5);
  EXPECT_DOUBLE_EQ(shape_axis(off, 3000), 0.5);
}

scene::ControlTable gear_table() {
  using K = scene::ControlKind;
  return scene::ControlTable({{"throttle", K::kAxis, 0.0, 1.0, {}, 0.0, 0.0, ""},
                              {"steer", K::kAxis, -1.0, 1.0, {}, 0.0, 0.0, ""},
                              {"brake", K::kAxis, 0.0, 1.0, {}, 0.0, 1.0, "safe: full brake"},
                              {"gear", K::kSwitch, 0, 2, {"reverse", "neutral", "drive"}, 1.0, 1.0, ""},
                              {"horn", K::kButton, 0, 1, {}, 0.0, 0.0, ""}});
}

TEST(DeviceMapping, ControlsFollowAxesButtonsDetentsAndToggles) {
  DeviceMapping m;
  m.devices = {{"wheel", "", "Wheel", 0, false}, {"pedals", "", "Pedals", 0, false}};
  const scene::ControlTable table = gear_table();
  Binding steer;
  steer.control = "steer";
  steer.slot = table.find("steer");
  steer.index = 0;
  Binding throttle;  // one-sided pedal onto a 0..1 axis
  throttle.control = "throttle";
  throttle.slot = table.find("throttle");
  throttle.device = 1;
  throttle.calibration = {0.0, 0.0, 1000.0, false};
  Binding brake = throttle;
  brake.control = "brake";
  brake.slot = table.find("brake");
  brake.index = 1;
  Binding gear;  // a three-position lever read from an axis with detents
  gear.control = "gear";
  gear.slot = table.find("gear");
  gear.index = 1;
  gear.detents = {-1.0, 0.0, 1.0};
  Binding horn;
  horn.control = "horn";
  horn.slot = table.find("horn");
  horn.source = Binding::Source::kButton;
  horn.index = 2;
  m.bindings = {steer, throttle, brake, gear, horn};
  ControlMapper mapper(table, m);

  std::vector<DeviceState> states(2);
  states[0] = {true, {16383.5, 30000.0}, {false, false, true}, {}};
  states[1] = {true, {250.0, 0.0}, {}, {}};
  scene::Controls c = mapper.map(states);
  EXPECT_NEAR(c.value[1], 0.5, 1e-4);  // steer: half right
  EXPECT_DOUBLE_EQ(c.value[0], 0.25);  // throttle: a quarter pressed
  EXPECT_DOUBLE_EQ(c.value[2], 0.0);   // brake released
  EXPECT_DOUBLE_EQ(c.value[3], 2.0);   // gear lever near +1: drive
  EXPECT_DOUBLE_EQ(c.value[4], 1.0);   // horn held
  states[0].axes[1] = -200.0;
  EXPECT_DOUBLE_EQ(mapper.map(states).value[3], 1.0);  // near the middle detent: neutral

  // the pedals unplugged: throttle and brake read their safe values at once (brake full on)
  states[1].connected = false;
  c = mapper.map(states);
  EXPECT_DOUBLE_EQ(c.value[0], 0.0);
  EXPECT_DOUBLE_EQ(c.value[2], 1.0);
  EXPECT_NEAR(c.value[1], 0.5, 1e-4);  // the wheel still steers
}

// The shipped keyboard: keys drive levers and buttons; the mouse moves no control (it drove the trolley at
// full speed from the window's edge); the emergency stop counts only once Space is held half a second.
TEST(DeviceMapping, KeysDriveLeversTheMouseNothingAndTheStopWantsAHeldPress) {
  const scene::ControlTable table = scenes::sts_controls();
  const DeviceMapping m =
      load_device_mapping(std::string(HARBOUR_DATA_DIR) + "/devices/keyboard.yaml", table);
  for (const DeviceMatch& d : m.devices)
    EXPECT_FALSE(d.mouse) << "the shipped keyboard binds the mouse (" << d.id << ")";
  ControlMapper mapper(table, m);
  const auto at = [&](const char* label) { return static_cast<std::size_t>(table.find(label)); };
  std::vector<bool> keys(SDL_NUM_SCANCODES, false);
  keys[SDL_SCANCODE_S] = true;      // hoist down
  keys[SDL_SCANCODE_RIGHT] = true;  // gantry +
  keys[SDL_SCANCODE_L] = true;
  const std::vector<DeviceState> states(m.devices.size());
  scene::Controls c = mapper.map(states, keys, 10.0);
  EXPECT_EQ(c.value[at("hoist")], -1.0);
  EXPECT_EQ(c.value[at("gantry")], 1.0);
  EXPECT_EQ(c.value[at("lock")], 1.0);
  EXPECT_EQ(c.value[at("trolley")], 0.0);
  // a tap of Space is no stop; held, it stops from half a second on, until let go
  keys[SDL_SCANCODE_SPACE] = true;
  EXPECT_EQ(mapper.map(states, keys, 20.0).value[at("emergency_stop")], 0.0);
  EXPECT_EQ(mapper.map(states, keys, 20.2).value[at("emergency_stop")], 0.0);
  keys[SDL_SCANCODE_SPACE] = false;
  EXPECT_EQ(mapper.map(states, keys, 20.3).value[at("emergency_stop")], 0.0);
  keys[SDL_SCANCODE_SPACE] = true;
  EXPECT_EQ(mapper.map(states, keys, 21.0).value[at("emergency_stop")], 0.0);
  EXPECT_EQ(mapper.map(states, keys, 21.49).value[at("emergency_stop")], 0.0);
  EXPECT_EQ(mapper.map(states, keys, 21.5).value[at("emergency_stop")], 1.0);
  EXPECT_EQ(mapper.map(states, keys, 25.0).value[at("emergency_stop")], 1.0);
  keys[SDL_SCANCODE_SPACE] = false;
  EXPECT_EQ(mapper.map(states, keys, 25.1).value[at("emergency_stop")], 0.0);
}

// A mapping that binds the mouse reads it as a lever from the window's centre (a touch joystick).
TEST(DeviceMapping, AMouseBoundAsALeverReadsFromTheWindowsCentre) {
  const scene::ControlTable table = scenes::sts_controls();
  const DeviceMapping m = load_device_mapping(
      io::YamlFile::parse("mapping:\n  name: m\n  devices:\n    - {id: mouse, mouse: true}\n  bindings:\n"
                          "    - {control: trolley, device: mouse, axis: 0, dead_zone: 0.15, expo: 0.5}\n"
                          "    - {control: hoist, device: mouse, axis: 1, invert: true}\n"
                          "    - {control: unlock, device: mouse, button: 2}\n",
                          "mouse.yaml"),
      table);
  ControlMapper mapper(table, m);
  const auto at = [&](const char* label) { return static_cast<std::size_t>(table.find(label)); };
  std::vector<DeviceState> states(1);  // no window: no mouse, nothing lost
  EXPECT_EQ(mapper.map(states).value[at("trolley")], 0.0);
  states[0] = {true, {0.25 * 32767.0, -32768.0}, {false, false, true}, {}};
  const scene::Controls c = mapper.map(states);
  const double x = 0.1 / 0.85;  // (0.25 - 0.15) / 0.85, then 0.5 x + 0.5 x^3
  EXPECT_NEAR(c.value[at("trolley")], 0.5 * x + 0.5 * x * x * x, 1e-12);
  EXPECT_EQ(c.value[at("hoist")], 1.0);   // the top of the window raises
  EXPECT_EQ(c.value[at("unlock")], 1.0);  // right button
}

TEST(DeviceMapping, AToggleButtonStepsASwitchOnEachPress) {
  const scene::ControlTable table = scenes::sts_controls();
  DeviceMapping m;
  m.devices = {{"pad", "", "pad", 0, false}};
  Binding b;
  b.control = "flipper_2";
  b.slot = table.find("flipper_2");
  b.source = Binding::Source::kButton;
  b.toggle = true;
  m.bindings = {b};
  ControlMapper mapper(table, m);
  std::vector<DeviceState> s{{true, {}, {false}, {}}};
  const auto at = static_cast<std::size_t>(b.slot);
  EXPECT_EQ(mapper.map(s).value[at], 0.0);
  s[0].buttons[0] = true;
  EXPECT_EQ(mapper.map(s).value[at], 1.0);  // pressed: down
  EXPECT_EQ(mapper.map(s).value[at], 1.0);  // held: stays
  s[0].buttons[0] = false;
  EXPECT_EQ(mapper.map(s).value[at], 1.0);
  s[0].buttons[0] = true;
  EXPECT_EQ(mapper.map(s).value[at], 0.0);  // pressed again: up
}

std::string error_of(const std::string& text) {
  try {
    load_device_mapping(io::YamlFile::parse(text, "bad.yaml"), scenes::sts_controls());
  } catch (const io::DataError& e) {
    return e.what();
  }
  return "";
}

TEST(DeviceMapping, BadMappingsNameFileLineAndField) {
  const std::string head = "mapping:\n  name: x\n  devices:\n    - {id: s, name: Stick}\n  bindings:\n";
  EXPECT_EQ(error_of(head + "    - {control: hoist, device: s, axis: 1}\n"), "");
  EXPECT_NE(error_of(head + "    - {control: slew, device: s, axis: 1}\n")
                .find("bad.yaml:6: mapping.bindings[0].control: the machine has no control 'slew'"),
            std::string::npos);
  EXPECT_NE(
      error_of(head +
               "    - {control: hoist, device: s, axis: 1, calibration: {min: 10, center: 0, max: 5}}\n")
          .find("bad.yaml:6: mapping.bindings[0].calibration: needs min < center < max"),
      std::string::npos);
  EXPECT_NE(error_of(head + "    - {control: hoist, device: s, axis: 1, calibration: {min: 10, max: 5}}\n")
                .find("calibration.min: min must be below max"),
            std::string::npos);
  EXPECT_NE(error_of(head + "    - {control: hoist, device: s, axis: one}\n")
                .find("bad.yaml:6: mapping.bindings[0].axis: 'one' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of(head + "    - {control: hoist, device: t, axis: 1}\n").find("no device 't'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "    - {control: hoist, device: s, axis: 1, button: 2}\n").find("exactly one of"),
            std::string::npos);
  EXPECT_NE(error_of(head + "    - {control: flipper_1, device: s, axis: 1}\n").find("needs detents"),
            std::string::npos);
  EXPECT_NE(error_of(head + "    - {control: hoist, device: s, axis: 1, dead_zone: 2}\n").find("dead_zone"),
            std::string::npos);
  EXPECT_NE(
      error_of(head + "    - {control: hoist, device: s, axis: 1, curve: 2}\n").find("unknown key 'curve'"),
      std::string::npos);
  EXPECT_NE(error_of("mapping:\n  name: x\n  devices:\n    - {id: m, mouse: true}\n  bindings:\n    - "
                     "{control: hoist, device: m, axis: 2}\n")
                .find("the mouse has axes 0 (x) and 1 (y)"),
            std::string::npos);
  EXPECT_NE(error_of("mapping:\n  name: x\n  devices:\n    - {id: k, keyboard: true}\n  bindings:\n    - "
                     "{control: lock, device: k, key: Hyperspace}\n")
                .find("'Hyperspace' is not a key SDL knows"),
            std::string::npos);

  // an axis index beyond the device is found when the device is: named by file, line and field
  const DeviceMapping m = load_device_mapping(
      io::YamlFile::parse(head + "    - {control: hoist, device: s, axis: 5}\n", "bad.yaml"),
      scenes::sts_controls());
  EXPECT_EQ(why_unfit(m, 0, 4, 12, 1),
            "bad.yaml:6: bindings.hoist: axis 5 is beyond device 's', which has 4");
  EXPECT_EQ(why_unfit(m, 0, 6, 12, 1), "");
}

TEST(DeviceMapping, ButtonsSelectingASwitchsPositionsLeaveItWherePut) {
  // a pad's direction selector: d-pad up forward, d-pad down reverse, a stick press neutral
  const scene::ControlTable table = gear_table();
  DeviceMapping m;
  m.devices = {{"pad", "", "pad", 0, false}};
  const int gear = table.find("gear");
  for (const auto& [button, position] : std::vector<std::pair<int, double>>{{0, 2.0}, {1, 0.0}, {2, 1.0}}) {
    Binding b;
    b.control = "gear";
    b.slot = gear;
    b.source = Binding::Source::kButton;
    b.index = button;
    b.value = position;
    m.bindings.push_back(b);
  }
  ControlMapper mapper(table, m);
  std::vector<DeviceState> s{{true, {}, {false, false, false}, {}}};
  const auto at = static_cast<std::size_t>(gear);
  EXPECT_EQ(mapper.map(s).value[at], 1.0);  // neutral until a button says otherwise
  s[0].buttons[0] = true;
  EXPECT_EQ(mapper.map(s).value[at], 2.0);  // forward
  s[0].buttons[0] = false;
  EXPECT_EQ(mapper.map(s).value[at], 2.0);  // let go: still forward
  s[0].buttons[1] = true;
  EXPECT_EQ(mapper.map(s).value[at], 0.0);  // reverse
  s[0].buttons[1] = false;
  EXPECT_EQ(mapper.map(s).value[at], 0.0);
  s[0].buttons[2] = true;
  EXPECT_EQ(mapper.map(s).value[at], 1.0);  // neutral
}

TEST(DeviceMapping, AGameControllersInputsAreSdlsNames) {
  const std::string head =
      "mapping:\n  name: x\n  devices:\n    - {id: pad, game_controller: true}\n  bindings:\n";
  const auto load = [&](const std::string& bindings) {
    return load_device_mapping(io::YamlFile::parse(head + bindings, "pad.yaml"), scenes::sts_controls());
  };
  const DeviceMapping m = load(
      "    - {control: hoist, device: pad, axis: righty, invert: true}\n"
      "    - {control: trolley, device: pad, axis: righttrigger}\n"
      "    - {control: lock, device: pad, button: a}\n"
      "    - {control: boom, device: pad, button: dpup, value: 1}\n");
  ASSERT_EQ(m.bindings.size(), 4u);
  EXPECT_TRUE(m.devices[0].game_controller);
  EXPECT_EQ(m.bindings[0].index, SDL_CONTROLLER_AXIS_RIGHTY);
  EXPECT_TRUE(m.bindings[0].calibration.centered);
  EXPECT_EQ(m.bindings[1].index, SDL_CONTROLLER_AXIS_TRIGGERRIGHT);
  EXPECT_FALSE(m.bindings[1].calibration.centered);  // SDL reads a trigger 0..32767: one-sided
  EXPECT_EQ(m.bindings[1].calibration.min, 0.0);
  EXPECT_EQ(m.bindings[2].index, SDL_CONTROLLER_BUTTON_A);
  EXPECT_EQ(m.bindings[3].index, SDL_CONTROLLER_BUTTON_DPAD_UP);
  // the F1 list says it in a trainee's words
  const std::string keys = key_list(m, scenes::sts_controls());
  EXPECT_NE(keys.find("pad right stick up/down"), std::string::npos) << keys;
  EXPECT_NE(keys.find("pad A"), std::string::npos) << keys;
  EXPECT_NE(keys.find("pad d-pad up"), std::string::npos) << keys;

  const auto error = [&](const std::string& bindings) {
    try {
      load(bindings);
    } catch (const io::DataError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(
      error("    - {control: hoist, device: pad, axis: 4}\n")
          .find("pad.yaml:6: mapping.bindings[0].axis: a game controller's axis is named as SDL names it: "
                "leftx, lefty, rightx, righty, lefttrigger, righttrigger"),
      std::string::npos);
  EXPECT_NE(
      error("    - {control: lock, device: pad, button: triangle}\n")
          .find("mapping.bindings[0].button: a game controller's button is named as SDL names it: a, b"),
      std::string::npos);
  EXPECT_NE(error("    - {control: lock, device: pad, hat: 0, direction: up}\n")
                .find("a game controller's d-pad is buttons: dpup"),
            std::string::npos);
}

TEST(DeviceMapping, ControllerMappingLinesAreCheckedAsSdlReadsThem) {
  const std::string guid = "03000000aaaa0000bbbb000000010000";
  EXPECT_EQ(why_bad_controller_mapping(
                guid + ",Acme pad,a:b0,b:b1,leftx:a0,lefty:a1~,dpup:h0.1,+rightx:a3,platform:Linux,"),
            "");
  EXPECT_EQ(why_bad_controller_mapping("xinput,XInput Controller,a:b0,"), "");
  EXPECT_NE(why_bad_controller_mapping("03000000aaaa,Acme pad,a:b0").find("is not an SDL GUID"),
            std::string::npos);
  EXPECT_NE(why_bad_controller_mapping(guid + ",,a:b0").find("no name"), std::string::npos);
  EXPECT_NE(why_bad_controller_mapping(guid + ",Acme pad,cross:b0").find("'cross' is not an input SDL knows"),
            std::string::npos);
  EXPECT_NE(why_bad_controller_mapping(guid + ",Acme pad,a:x0").find("'a:x0': an input is b<button>"),
            std::string::npos);
  EXPECT_NE(why_bad_controller_mapping(guid + ",Acme pad,dpup:h0").find("'dpup:h0'"), std::string::npos);
  EXPECT_NE(why_bad_controller_mapping(guid + ",Acme pad,platform:Linux").find("maps no input"),
            std::string::npos);
  EXPECT_NE(why_bad_controller_mapping(guid).find("'GUID,name,a:b0"), std::string::npos);
  EXPECT_TRUE(for_this_platform(guid + ",Acme pad,a:b0,platform:Linux,"));
  EXPECT_FALSE(for_this_platform(guid + ",Acme pad,a:b0,platform:Windows,"));
  EXPECT_TRUE(for_this_platform(guid + ",Acme pad,a:b0"));

  // in a mapping file: inline lines, and a gamecontrollerdb.txt beside it; errors name file and line
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "harbour_controller_db";
  std::filesystem::create_directories(folder);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(folder / name) << text;
    return (folder / name).string();
  };
  write("pads.txt", "# pads\n\n" + guid + ",Acme pad,a:b0,leftx:a0,platform:Linux,\r\n" + guid +
                        ",Acme pad,a:b0,platform:Mac OS X,\n");
  const std::string head =
      "mapping:\n  name: x\n  devices:\n    - {id: pad, game_controller: true}\n  bindings:\n"
      "    - {control: lock, device: pad, button: a}\n";
  const DeviceMapping m =
      load_device_mapping(write("good.yaml", head + "  controller_mappings:\n    - \"" + guid +
                                                 ",Other pad,a:b3\"\n  controller_db: pads.txt\n"),
                          scenes::sts_controls());
  ASSERT_EQ(m.controller_mappings.size(), 2u);  // the Mac line is for another platform
  EXPECT_EQ(m.controller_mappings[0].where, (folder / "good.yaml").string() + ":8");
  EXPECT_EQ(m.controller_mappings[1].text, guid + ",Acme pad,a:b0,leftx:a0,platform:Linux,");
  EXPECT_EQ(m.controller_mappings[1].where, (folder / "pads.txt").string() + ":3");
  // written back by `harboursim devices`, they read the same
  EXPECT_EQ(
      load_device_mapping(io::YamlFile::parse(device_mapping_text(m), "written.yaml"), scenes::sts_controls())
          .controller_mappings.size(),
      2u);
  const auto error = [&](const std::string& name, const std::string& text) {
    try {
      load_device_mapping(write(name, text), scenes::sts_controls());
    } catch (const io::DataError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("bad1.yaml", head + "  controller_mappings:\n    - \"" + guid + ",Other pad,a:q3\"\n")
                .find("bad1.yaml:8: mapping.controller_mappings[0]: 'a:q3'"),
            std::string::npos);
  write("broken.txt", "# pads\n" + guid + ",Acme pad,a:b0\nnonsense\n");
  EXPECT_NE(error("bad2.yaml", head + "  controller_db: broken.txt\n").find("broken.txt:3"),
            std::string::npos);
  EXPECT_NE(error("bad3.yaml", head + "  controller_db: missing.txt\n").find("mapping.controller_db"),
            std::string::npos);
  std::filesystem::remove_all(folder);
}

TEST(DeviceMapping, EveryShippedMappingLoadsAndWritesBackTheSame) {
  // every machine's controls (each kind's, from the registry's shipped machines)
  std::vector<scene::ControlTable> machines;
  for (const auto& [kind, table] : test::shipped_machine_controls())
    machines.push_back(table);
  EXPECT_EQ(machines.size(), sim::machine_types().size());
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(HARBOUR_DATA_DIR) + "/devices")) {
    const std::string path = entry.path().string();
    // each fits exactly one family: the profiles skip those for another
    const scene::ControlTable* fits = nullptr;
    for (const scene::ControlTable& table : machines)
      if (why_mapping_does_not_fit(path, table).empty()) {
        EXPECT_EQ(fits, nullptr) << path << " fits two machines";
        fits = &table;
      }
    ASSERT_NE(fits, nullptr) << path << " fits no machine";
    const DeviceMapping m = load_device_mapping(path, *fits);
    EXPECT_FALSE(m.bindings.empty()) << path;
    // what `harboursim devices` writes reads back to the same bindings
    const DeviceMapping back =
        load_device_mapping(io::YamlFile::parse(device_mapping_text(m), "written.yaml"), *fits);
    ASSERT_EQ(back.bindings.size(), m.bindings.size()) << path;
    for (std::size_t n = 0; n < m.bindings.size(); ++n) {
      EXPECT_EQ(back.bindings[n].slot, m.bindings[n].slot);
      EXPECT_EQ(back.bindings[n].index, m.bindings[n].index);
      EXPECT_EQ(back.bindings[n].keys, m.bindings[n].keys);
      EXPECT_EQ(back.bindings[n].invert, m.bindings[n].invert);
      EXPECT_EQ(back.bindings[n].dead_zone, m.bindings[n].dead_zone);
      EXPECT_EQ(back.bindings[n].toggle, m.bindings[n].toggle);
    }
    ++files;
  }
  EXPECT_GE(files, static_cast<int>(2 * machines.size()));  // a game pad and a keyboard for each at least
}

}  // namespace
}  // namespace harbour::station
