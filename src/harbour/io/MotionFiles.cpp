#include "harbour/io/MotionFiles.h"

#include <cstdio>

#include "harbour/core/Units.h"

namespace harbour::io {
namespace {

using core::deg_to_rad;
using motion::PlatformPose;

// per-axis limits: three linear fields [unit] and three angular fields [deg unit], e.g. surge_mps /
// roll_deg_s
PlatformPose axis_limits(const YamlFile& f, const YAML::Node& map, const std::string& path,
                         const std::string& unit) {
  const YAML::Node node = f.required(map, path, "platform");
  const std::string at = "platform." + path;
  PlatformPose p;
  const char* linear[] = {"surge_", "sway_", "heave_"};
  const char* angular[] = {"roll_deg_", "pitch_deg_", "yaw_deg_"};
  for (int i = 0; i < 3; ++i) {
    p[i] = f.number(node, linear[i] + unit, at, 0.0, 100.0, true);
    p[3 + i] = deg_to_rad(f.number(node, angular[i] + (unit == "mps" ? std::string("s") : std::string("s2")),
                                   at, 0.0, 1e5, true));
  }
  return p;
}

std::string format_length(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", v);
  return text;
}

}  // namespace

PlatformFile load_platform(const YamlFile& f) {
  PlatformFile out;
  const YAML::Node p = f.required(f.root(), "platform", "");
  const std::string at = "platform";
  out.name = f.text(p, "name", at);
  motion::StewartGeometry& g = out.geometry;
  g.neutral_height_m = f.number(p, "neutral_height_m", at, 0.0, 20.0, true);
  g.min_length_m = f.number(p, "min_length_m", at, 0.0, 20.0, true);
  g.max_length_m = f.number(p, "max_length_m", at, 0.0, 20.0, true);
  if (g.max_length_m <= g.min_length_m)
    f.fail(p["max_length_m"], at + ".max_length_m", "must exceed min_length_m");
  for (const char* key : {"base_joints_m", "platform_joints_m"}) {
    const YAML::Node list = f.sequence(p, key, at);
    const std::string field = at + "." + key;
    if (list.size() != motion::kActuators)
      f.fail(list, field, "expected 6 joints, found " + std::to_string(list.size()));
    auto& joints = std::string(key) == "base_joints_m" ? g.base_joints : g.platform_joints;
    for (std::size_t i = 0; i < list.size(); ++i)
      joints[i] = f.vector3(list[i], field + "[" + std::to_string(i) + "]");
  }
  out.limits.max_velocity = axis_limits(f, p, "max_velocity", "mps");
  out.limits.max_acceleration = axis_limits(f, p, "max_acceleration", "mps2");

  const YAML::Node s = f.required(p, "sequencer", at);
  const std::string sat = at + ".sequencer";
  motion::SequencerSettings& q = out.sequencer;
  q.engage_time_s = f.number(s, "engage_time_s", sat, 0.0, 600.0, true);
  q.park_time_s = f.number(s, "park_time_s", sat, 0.0, 600.0, true);
  q.watchdog_timeout_s = f.number(s, "watchdog_timeout_s", sat, 0.0, 60.0, true);
  const double fade_speed = f.number(s, "fade_speed_mps", sat, 0.0, 10.0, true);
  const double fade_rate = deg_to_rad(f.number(s, "fade_rate_deg_s", sat, 0.0, 360.0, true));
  const double fade_acc = f.number(s, "fade_acceleration_mps2", sat, 0.0, 100.0, true);
  const double fade_ang_acc =
      deg_to_rad(f.number(s, "fade_angular_acceleration_deg_s2", sat, 0.0, 1e4, true));
  for (int i = 0; i < 3; ++i) {
    q.fade_limits.max_velocity[i] = fade_speed;
    q.fade_limits.max_velocity[3 + i] = fade_rate;
    q.fade_limits.max_acceleration[i] = fade_acc;
    q.fade_limits.max_acceleration[3 + i] = fade_ang_acc;
  }
  q.parked_pose[motion::kHeave] = f.number(s, "parked_heave_m", sat, -g.neutral_height_m, 0.0);

  // the actuators must reach neutral and the parked pose
  const motion::StewartPlatform platform(g);
  const std::pair<const char*, PlatformPose> checks[] = {{"neutral_height_m", {}},
                                                         {"sequencer.parked_heave_m", q.parked_pose}};
  for (const auto& [field, pose] : checks) {
    const motion::ActuatorLengths lengths = platform.inverse(pose);
    for (int i = 0; i < motion::kActuators; ++i)
      if (!(lengths[i] >= g.min_length_m && lengths[i] <= g.max_length_m))
        f.fail(std::string(field) == "neutral_height_m" ? p["neutral_height_m"] : s["parked_heave_m"],
               at + "." + field,
               "actuator " + std::to_string(i) + " would need " + format_length(lengths[i]) +
                   " m, outside its stroke [" + format_length(g.min_length_m) + ", " +
                   format_length(g.max_length_m) + "] m");
  }
  f.check_unknown_keys();
  return out;
}

PlatformFile load_platform(const std::string& path) {
  return load_platform(YamlFile::load(path));
}

namespace {

void read_translational(const YamlFile& f, const YAML::Node& n, const std::string& at,
                        motion::TranslationalSettings& s) {
  if (!n.IsDefined()) return;
  s.gain = f.number_or(n, "gain", at, s.gain, 0.0, 10.0);
  s.limit_mps2 = f.number_or(n, "limit_mps2", at, s.limit_mps2, 0.0, 100.0, true);
  s.wn_rad_s = f.number_or(n, "wn_rad_s", at, s.wn_rad_s, 0.0, 100.0, true);
  s.zeta = f.number_or(n, "zeta", at, s.zeta, 0.0, 10.0, true);
  s.break_rad_s = f.number_or(n, "break_rad_s", at, s.break_rad_s, 0.0, 100.0, true);
}

void read_channels(const YamlFile& f, const YAML::Node& n, const std::string& at,
                   motion::WashoutSettings& w) {
  if (const auto c = f.optional_map(n, "surge_sway", at))
    read_translational(f, *c, at + ".surge_sway", w.surge_sway);
  if (const auto c = f.optional_map(n, "heave", at)) read_translational(f, *c, at + ".heave", w.heave);
  if (const auto tilt = f.optional_map(n, "tilt", at)) {
    const YAML::Node& t = *tilt;
    const std::string tat = at + ".tilt";
    w.tilt.gain = f.number_or(t, "gain", tat, w.tilt.gain, 0.0, 10.0);
    w.tilt.limit_mps2 = f.number_or(t, "limit_mps2", tat, w.tilt.limit_mps2, 0.0, 100.0, true);
    w.tilt.wn_rad_s = f.number_or(t, "wn_rad_s", tat, w.tilt.wn_rad_s, 0.0, 100.0, true);
    w.tilt.zeta = f.number_or(t, "zeta", tat, w.tilt.zeta, 0.0, 10.0, true);
    w.tilt.max_angle_rad =
        deg_to_rad(f.number_or(t, "max_angle_deg", tat, core::rad_to_deg(w.tilt.max_angle_rad), 0.0, 45.0));
    w.tilt.max_rate_rad_s = deg_to_rad(
        f.number_or(t, "max_rate_deg_s", tat, core::rad_to_deg(w.tilt.max_rate_rad_s), 0.0, 90.0, true));
  }
  if (const auto rotation = f.optional_map(n, "rotation", at)) {
    const YAML::Node& r = *rotation;
    const std::string rat = at + ".rotation";
    w.rotation.gain = f.number_or(r, "gain", rat, w.rotation.gain, 0.0, 10.0);
    w.rotation.limit_rad_s = deg_to_rad(
        f.number_or(r, "limit_deg_s", rat, core::rad_to_deg(w.rotation.limit_rad_s), 0.0, 360.0, true));
    w.rotation.wn_rad_s = f.number_or(r, "wn_rad_s", rat, w.rotation.wn_rad_s, 0.0, 100.0, true);
    w.rotation.zeta = f.number_or(r, "zeta", rat, w.rotation.zeta, 0.0, 10.0, true);
  }
}

// a machine file's motion cues over `w`
void read_motion_cues(const YamlFile& machine_file, motion::WashoutSettings& w) {
  if (const auto cues = machine_file.optional_map(machine_file.root(), "motion_cues", ""))
    read_channels(machine_file, *cues, "motion_cues", w);
}

}  // namespace

motion::WashoutSettings load_washout(const YamlFile& washout_file, const YamlFile& machine_file) {
  const YamlFile& f = washout_file;
  motion::WashoutSettings w;
  w.rate_hz = f.number(f.root(), "rate_hz", "", 1.0, 10000.0);
  if (const auto defaults = f.optional_map(f.root(), "defaults", ""))
    read_channels(f, *defaults, "defaults", w);
  f.check_unknown_keys();
  read_motion_cues(machine_file, w);
  return w;
}

motion::WashoutSettings load_washout(const std::string& washout_path, const std::string& machine_path) {
  return load_washout(YamlFile::load(washout_path), YamlFile::load(machine_path));
}

void check_motion_cues(const YamlFile& machine_file) {
  motion::WashoutSettings scratch;
  read_motion_cues(machine_file, scratch);
}

}  // namespace harbour::io
