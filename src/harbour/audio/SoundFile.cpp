#include "harbour/audio/SoundFile.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "harbour/io/MachineDataFiles.h"
#include "harbour/io/YamlFile.h"

namespace harbour::audio {

namespace {

constexpr std::pair<const char*, SourceKind> kKinds[] = {
    {"electric_drive", SourceKind::kElectricDrive},
    {"diesel", SourceKind::kDiesel},
    {"hydraulic", SourceKind::kHydraulic},
    {"impact", SourceKind::kImpact},
    {"clunk", SourceKind::kClunk},
    {"brake", SourceKind::kBrake},
    {"alarm", SourceKind::kAlarm},
    {"wind", SourceKind::kWind},
    {"rain", SourceKind::kRain},
    {"sea", SourceKind::kSea},
    {"harbour", SourceKind::kHarbour},
    {"pour", SourceKind::kPour},
    {"radio", SourceKind::kRadio},
};

SourceKind kind_named(const io::YamlFile& f, const YAML::Node& item, const std::string& at) {
  const std::string name = f.text(item, "kind", at);
  std::string known;
  for (const auto& [text, kind] : kKinds) {
    if (name == text) return kind;
    known += known.empty() ? text : std::string(", ") + text;
  }
  f.fail(item["kind"], at + ".kind", "unknown sound kind '" + name + "' (" + known + ")");
}

void read_knock(const io::YamlFile& f, const YAML::Node& item, const std::string& at, KnockSettings& k) {
  k.thump_hz = f.number_or(item, "thump_hz", at, k.thump_hz, 20.0, 2000.0);
  if (const auto ring = f.optional(item, "ring_hz", at)) {
    if (!ring->IsSequence() || ring->size() != k.ring_hz.size())
      f.fail(*ring, at + ".ring_hz", "three frequencies [Hz]");
    for (std::size_t m = 0; m < k.ring_hz.size(); ++m) {
      k.ring_hz[m] = f.number_at((*ring)[m], at + ".ring_hz[" + std::to_string(m) + "]");
      if (k.ring_hz[m] < 20.0 || k.ring_hz[m] > 15000.0)
        f.fail((*ring)[m], at + ".ring_hz[" + std::to_string(m) + "]", "out of range [20, 15000] Hz");
    }
  }
  k.decay_s = f.number_or(item, "decay_s", at, k.decay_s, 0.005, 3.0);
}

SoundSource read_source(const io::YamlFile& f, const YAML::Node& item, const std::string& at) {
  SoundSource s;
  s.name = f.text(item, "name", at);
  s.kind = kind_named(f, item, at);
  if (f.optional(item, "at", at)) s.at = f.text(item, "at", at);
  if (const auto offset = f.optional(item, "offset_m", at))
    s.offset_m = f.vector3(*offset, at + ".offset_m", 200.0);
  s.optional = f.flag(item, "optional", at, false);
  s.reference_distance_m = f.number_or(item, "reference_distance_m", at, s.reference_distance_m, 0.1, 1000.0);
  const double level = f.number(item, "level", at, 0.0, 1.0);
  const auto drive = [&] { s.drive = f.text(item, "drive", at); };
  const auto indicator = [&] { s.indicator = f.text(item, "indicator", at); };
  switch (s.kind) {
    case SourceKind::kElectricDrive:
      drive();
      s.electric.rated_hz = f.number(item, "rated_hz", at, 5.0, 2000.0);
      s.electric.carrier_hz = f.number(item, "carrier_hz", at, 200.0, 16000.0);
      s.electric.level = level;
      break;
    case SourceKind::kDiesel:
      drive();
      s.diesel.cylinders = f.integer(item, "cylinders", at, 1, 16);
      s.diesel.idle_rpm = f.number(item, "idle_rpm", at, 200.0, 3000.0);
      s.diesel.rated_rpm = f.number(item, "rated_rpm", at, s.diesel.idle_rpm, 5000.0);
      s.diesel.exhaust_hz = f.number_or(item, "exhaust_hz", at, s.diesel.exhaust_hz, 20.0, 2000.0);
      s.diesel.block_hz = f.number_or(item, "block_hz", at, s.diesel.block_hz, 50.0, 5000.0);
      s.diesel.turbo_hz = f.number_or(item, "turbo_hz", at, s.diesel.turbo_hz, 500.0, 15000.0);
      s.diesel.level = level;
      break;
    case SourceKind::kHydraulic:
      drive();
      s.hydraulic.pump_hz = f.number(item, "pump_hz", at, 20.0, 5000.0);
      s.hydraulic.level = level;
      break;
    case SourceKind::kImpact:
      s.reference_impulse_ns = f.number(item, "reference_impulse_ns", at, 1.0, 1e7);
      read_knock(f, item, at, s.knock);
      s.knock.level = level;
      break;
    case SourceKind::kClunk:
      indicator();
      s.at_ends = f.flag(item, "at_ends", at, false);
      read_knock(f, item, at, s.knock);
      s.knock.level = level;
      break;
    case SourceKind::kBrake:
      drive();
      read_knock(f, item, at, s.knock);
      s.knock.level = level;
      break;
    case SourceKind::kAlarm:
      // while an indicator is above a threshold, while a drive moves (a travel alarm) or while the wind blows
      // harder than a limit (the anemometer's)
      if (f.optional(item, "wind_above_mps", at))
        s.wind_above_mps = f.number(item, "wind_above_mps", at, 0.0, 100.0);
      else if (f.optional(item, "drive", at))
        drive();
      else
        indicator(), s.above = f.number_or(item, "above", at, 0.5, -1e6, 1e6);
      s.tone.frequency_hz = f.number(item, "frequency_hz", at, 50.0, 8000.0);
      s.tone.second_hz = f.number_or(item, "second_hz", at, 0.0, 0.0, 8000.0);
      s.tone.on_s = f.number_or(item, "on_s", at, 0.0, 0.0, 10.0);
      s.tone.off_s = f.number_or(item, "off_s", at, 0.0, 0.0, 10.0);
      s.tone.chord = f.flag(item, "chord", at, false);
      if (s.tone.chord && s.tone.second_hz <= 0.0)
        f.fail(item, at + ".second_hz", "a chord needs its second note");
      s.tone.level = level;
      break;
    case SourceKind::kRadio:
      s.radio_level = level;
      break;
    case SourceKind::kPour:
      indicator();
      [[fallthrough]];
    case SourceKind::kWind:
    case SourceKind::kRain:
    case SourceKind::kSea:
    case SourceKind::kHarbour:
      s.noise.kind = s.kind == SourceKind::kWind   ? NoiseKind::kWind
                     : s.kind == SourceKind::kRain ? NoiseKind::kRain
                     : s.kind == SourceKind::kSea  ? NoiseKind::kSea
                     : s.kind == SourceKind::kPour ? NoiseKind::kPour
                                                   : NoiseKind::kHarbour;
      s.noise.reference = f.number(item, "reference", at, 1e-3, 1e4);
      s.noise.level = level;
      break;
  }
  return s;
}

std::vector<SoundSource> read_list(const io::YamlFile& f, const YAML::Node& map, const std::string& key,
                                   const std::string& at) {
  std::vector<SoundSource> sources;
  const YAML::Node list = f.sequence(map, key, at, 64);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string item_at = (at.empty() ? key : at + "." + key) + "[" + std::to_string(i) + "]";
    sources.push_back(read_source(f, list[i], item_at));
    for (std::size_t j = 0; j + 1 < sources.size(); ++j)
      if (sources[j].name == sources.back().name)
        f.fail(list[i]["name"], item_at + ".name", "a second sound named '" + sources.back().name + "'");
  }
  return sources;
}

SoundSettings read_sounds(const io::YamlFile& f) {
  SoundSettings s;
  const YAML::Node sounds = f.required_map(f.root(), "sounds", "");
  s.ambience = read_list(f, sounds, "ambience", "sounds");
  f.check_unknown_keys();
  return s;
}

// a machine file's own sounds (`sounds`, a list; the rest of the file is its machine reader's)
std::vector<SoundSource> read_machine_sounds(const io::YamlFile& f) {
  if (!f.optional(f.root(), "sounds", "")) return {};
  std::vector<SoundSource> sources = read_list(f, f.root(), "sounds", "");
  f.check_unknown_keys(f.root()["sounds"], "sounds");
  return sources;
}

}  // namespace

SoundSettings load_sounds(const std::string& path, const std::vector<std::string>& machine_files) {
  SoundSettings s = read_sounds(io::YamlFile::load(path));
  for (const io::MachineDataFile& machine : io::load_machine_data_files(machine_files))
    s.machines[machine.kind] = read_machine_sounds(machine.file);
  return s;
}

SoundSettings load_shipped_sounds(const std::string& data_folder, std::span<const std::string_view> kinds,
                                  const std::string& machine_file) {
  return load_sounds(data_folder + "/sounds/harbour.yaml",
                     io::machine_data_files(data_folder, kinds, machine_file));
}

SoundSettings parse_sounds(const std::string& text, const std::string& name) {
  return read_sounds(io::YamlFile::parse(text, name));
}

}  // namespace harbour::audio
