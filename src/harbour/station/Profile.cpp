#include "harbour/station/Profile.h"

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "harbour/station/DeviceMappingFile.h"

namespace harbour::station {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

std::string existing(const io::YamlFile& f, const YAML::Node& map, const std::string& key,
                     const std::string& at, const std::string& folder) {
  const std::string name = f.text(map, key, at);
  const std::string path = (std::filesystem::path(folder) / name).lexically_normal().string();
  if (!std::filesystem::is_regular_file(path)) f.fail(map[key], at + "." + key, "no such file: " + path);
  return path;
}

std::string existing_folder(const io::YamlFile& f, const YAML::Node& map, const std::string& at,
                            const std::string& folder) {
  const std::string name = f.text(map, "folder", at);
  const std::string path = (std::filesystem::path(folder) / name).lexically_normal().string();
  if (!std::filesystem::is_directory(path)) f.fail(map["folder"], at + ".folder", "no such folder: " + path);
  return path;
}

// `off`, or a mapping
std::optional<YAML::Node> switched(const io::YamlFile& f, const YAML::Node& map, const std::string& key,
                                   const std::string& at) {
  const YAML::Node node = f.required(map, key, at);
  if (node.IsScalar() && node.Scalar() == "off") return std::nullopt;
  if (!node.IsMap()) f.fail(node, at + "." + key, "expected off or a mapping");
  return f.required_map(map, key, at);
}

// The mapping files of a folder whose devices are of `wanted`, by file name
std::vector<std::string> mappings_of_class(const std::string& folder, DeviceClass wanted) {
  std::vector<std::string> files;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().extension() == ".yaml")
      files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  std::erase_if(files, [&](const std::string& file) { return device_class_of(file) != wanted; });
  return files;
}

// profile.devices: mapping files, and {folder, class} entries for every mapping of a class in a folder
std::vector<std::string> read_mappings(const io::YamlFile& f, const YAML::Node& root,
                                       const std::string& folder) {
  std::vector<std::string> mappings;
  const YAML::Node devices = f.sequence(root, "devices", "profile", 16);
  for (std::size_t n = 0; n < devices.size(); ++n) {
    const std::string field = "profile.devices[" + std::to_string(n) + "]";
    if (devices[n].IsMap()) {
      const std::string in = existing_folder(f, devices[n], field, folder);
      const std::string name = f.text(devices[n], "class", field);
      std::optional<DeviceClass> wanted;
      for (const DeviceClass c : {DeviceClass::kSticks, DeviceClass::kGamePads, DeviceClass::kKeyboards})
        if (name == to_string(c)) wanted = c;
      if (!wanted)
        f.fail(devices[n]["class"], field + ".class", "sticks, game_pads or keyboards, not '" + name + "'");
      const std::vector<std::string> files = mappings_of_class(in, *wanted);
      if (files.empty()) f.fail(devices[n], field, "no " + name + " mapping in " + in);
      mappings.insert(mappings.end(), files.begin(), files.end());
      continue;
    }
    if (!devices[n].IsScalar()) f.fail(devices[n], field, "expected a mapping file or {folder, class}");
    const std::string file =
        (std::filesystem::path(folder) / devices[n].Scalar()).lexically_normal().string();
    if (!std::filesystem::is_regular_file(file)) f.fail(devices[n], field, "no such file: " + file);
    mappings.push_back(file);
  }
  return mappings;
}
}  // namespace

Profile load_profile(const std::string& path) {
  const io::YamlFile f = io::YamlFile::load(path);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  Profile p;
  p.file = path;
  const YAML::Node root = f.required_map(f.root(), "profile", "");
  p.name = f.text(root, "name", "profile");
  p.mappings = read_mappings(f, root, folder);
  const YAML::Node displays = f.sequence(root, "displays", "profile", 8);
  if (displays.size() == 0) f.fail(displays, "profile.displays", "at least one display");
  for (std::size_t n = 0; n < displays.size(); ++n) {
    const std::string at = "profile.displays[" + std::to_string(n) + "]";
    const YAML::Node d = displays[n];
    DisplayChannel c;
    c.name = f.text(d, "name", at);
    c.width = f.integer(d, "width", at, 320, 16384);
    c.height = f.integer(d, "height", at, 200, 16384);
    c.fullscreen = f.flag(d, "fullscreen", at, false);
    c.remote = f.flag(d, "remote", at, false);
    c.hud = n == 0;
    const YAML::Node view = f.required_map(d, "view", at);
    c.yaw_rad = f.number(view, "yaw_deg", at + ".view", -180.0, 180.0) * kDeg;
    // without a pitch the channel looks along the machine's design line of sight (a desktop monitor)
    c.from_sight = !f.optional(view, "pitch_deg", at + ".view").has_value();
    c.pitch_rad = c.from_sight ? 0.0 : f.number(view, "pitch_deg", at + ".view", -90.0, 90.0) * kDeg;
    c.roll_rad = f.number(view, "roll_deg", at + ".view", -180.0, 180.0) * kDeg;
    // without a field of view, the machine's design one (a desktop monitor shows what the cab shows)
    const std::optional<YAML::Node> given_fov = f.optional_map(d, "fov", at);
    c.fov_from_sight = !given_fov;
    if (c.fov_from_sight) {
      p.displays.push_back(c);
      continue;
    }
    const YAML::Node fov = *given_fov;
    if (f.optional(fov, "left_deg", at + ".fov")) {
      // an asymmetric frustum: each edge's angle from the view axis
      const std::string fat = at + ".fov";
      const double left = f.number(fov, "left_deg", fat, -85.0, 85.0),
                   right = f.number(fov, "right_deg", fat, -85.0, 85.0),
                   bottom = f.number(fov, "bottom_deg", fat, -85.0, 85.0),
                   top = f.number(fov, "top_deg", fat, -85.0, 85.0);
      if (!(left < right && bottom < top)) f.fail(fov, fat, "needs left < right and bottom < top");
      c.frustum_rad = std::array{left * kDeg, right * kDeg, bottom * kDeg, top * kDeg};
      c.fov_horizontal_rad = (right - left) * kDeg;
      c.fov_vertical_rad = (top - bottom) * kDeg;
    } else {
      c.fov_horizontal_rad = f.number(fov, "horizontal_deg", at + ".fov", 10.0, 170.0) * kDeg;
      c.fov_vertical_rad = f.number(fov, "vertical_deg", at + ".fov", 10.0, 170.0) * kDeg;
    }
    p.displays.push_back(c);
  }
  if (f.optional(root, "windows", "profile")) {
    const std::string windows = f.text(root, "windows", "profile");
    if (windows != "shared" && windows != "per_display")
      f.fail(root["windows"], "profile.windows", "'" + windows + "' is not shared or per_display");
    p.windows = windows == "per_display" ? Profile::Windows::kPerDisplay : Profile::Windows::kShared;
  }
  if (const auto stereo =
          f.optional(root, "stereo", "profile") ? switched(f, root, "stereo", "profile") : std::nullopt) {
    Profile::Stereo st;
    const std::string mode = f.text(*stereo, "mode", "profile.stereo");
    if (mode == "quad_buffer")
      f.fail(
          (*stereo)["mode"], "profile.stereo.mode",
          "quad_buffer needs an OpenGL stereo visual, and the station shows its frames through SDL windows: "
          "use side_by_side or anaglyph");
    if (mode != "side_by_side" && mode != "anaglyph")
      f.fail((*stereo)["mode"], "profile.stereo.mode", "'" + mode + "' is not side_by_side or anaglyph");
    st.mode = mode == "anaglyph" ? Profile::Stereo::Mode::kAnaglyph : Profile::Stereo::Mode::kSideBySide;
    st.eye_separation_m = f.number(*stereo, "eye_separation_mm", "profile.stereo", 40.0, 80.0) / 1000.0;
    st.convergence_m = f.number(*stereo, "convergence_m", "profile.stereo", 0.3, 1000.0);
    p.stereo = st;
  }
  if (const auto motion = switched(f, root, "motion", "profile")) {
    Profile::Motion m;
    m.platform = existing(f, *motion, "platform", "profile.motion", folder);
    m.washout = existing(f, *motion, "washout", "profile.motion", folder);
    m.driver.host = f.text(*motion, "host", "profile.motion");
    m.driver.port = static_cast<std::uint16_t>(f.integer(*motion, "port", "profile.motion", 1, 65535));
    const std::string format = f.text(*motion, "format", "profile.motion");
    if (format != "generic" && format != "moog")
      f.fail((*motion)["format"], "profile.motion.format", "'" + format + "' is not generic or moog");
    m.driver.format = format == "moog" ? io::PacketFormat::kMoogDof : io::PacketFormat::kGeneric;
    p.motion = m;
  }
  if (const auto head = switched(f, root, "head_tracking", "profile"))
    p.opentrack_port =
        static_cast<std::uint16_t>(f.integer(*head, "opentrack_port", "profile.head_tracking", 1, 65535));
  // sound: on two speakers where the profile does not say
  p.sound = Profile::Sound{};
  if (f.optional(root, "sound", "profile")) {
    if (const auto sound = switched(f, root, "sound", "profile")) {
      const std::string output = f.text(*sound, "output", "profile.sound");
      if (output != "speakers" && output != "headphones" && output != "surround_5_1")
        f.fail((*sound)["output"], "profile.sound.output",
               "'" + output + "' is not speakers, headphones or surround_5_1");
      p.sound->output = output == "headphones"     ? Profile::Sound::Output::kHeadphones
                        : output == "surround_5_1" ? Profile::Sound::Output::kSurround51
                                                   : Profile::Sound::Output::kSpeakers;
      p.sound->volume = f.number_or(*sound, "volume", "profile.sound", 1.0, 0.0, 2.0);
    } else {
      p.sound.reset();
    }
  }
  f.check_unknown_keys();
  return p;
}

std::string resolve_profile(const std::string& name_or_path, const std::string& data_dir) {
  namespace fs = std::filesystem;
  if (fs::is_regular_file(name_or_path)) return name_or_path;
  const fs::path shipped = fs::path(data_dir) / "profiles" / (name_or_path + ".yaml");
  if (fs::is_regular_file(shipped)) return shipped.string();
  throw std::runtime_error("no profile file '" + name_or_path +
                           "' and no shipped profile of that name (desktop, medium, immersive)");
}

Profile with_displays(const Profile& profile, const std::function<bool(const DisplayChannel&)>& keep) {
  Profile kept = profile;
  kept.displays.clear();
  for (const DisplayChannel& display : profile.displays)
    if (keep(display)) {
      kept.displays.push_back(display);
      kept.displays.back().remote = false;
    }
  return kept;
}

}  // namespace harbour::station
