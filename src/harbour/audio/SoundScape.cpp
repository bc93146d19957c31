#include "harbour/audio/SoundScape.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

#include "harbour/audio/Radio.h"
#include "harbour/core/Text.h"

namespace harbour::audio {

struct SoundScape::Voice {
  std::variant<ElectricDriveVoice, DieselVoice, HydraulicVoice, KnockVoice, ToneVoice, NoiseVoice, ClipVoice>
      v;
};

namespace {

// a seed per source from its name (FNV-1a): the same scene sounds the same every time
std::uint32_t seed_of(const std::string& name) {
  std::uint32_t h = 2166136261u;
  for (const char c : name)
    h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return h;
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

bool follows_drive(SourceKind kind) {
  return kind == SourceKind::kElectricDrive || kind == SourceKind::kDiesel ||
         kind == SourceKind::kHydraulic || kind == SourceKind::kBrake;
}

}  // namespace

SoundScape::SoundScape(const scene::SceneDescription& scene, const SoundSettings& settings, bool ambience) {
  std::vector<SoundSource> wanted;
  if (const auto it = settings.machines.find(scene.machine); it != settings.machines.end())
    wanted = it->second;
  if (ambience) wanted.insert(wanted.end(), settings.ambience.begin(), settings.ambience.end());
  std::vector<std::string> entities;
  for (const scene::SceneDescription::Entity& e : scene.entities)
    entities.push_back(e.name);
  const auto lacks = [&](const SoundSource& s, const std::string& what, const std::vector<std::string>& has) {
    if (s.optional) return true;
    throw std::invalid_argument("sound '" + s.name + "' of " + scene.machine + ": " + what +
                                " (it has: " + core::comma_separated(has) + ")");
  };
  for (const SoundSource& s : wanted) {
    Bound b;
    b.settings = s;
    if (follows_drive(s.kind) || (s.kind == SourceKind::kAlarm && !s.drive.empty())) {
      b.drive = index_of(scene.drives, s.drive);
      if (b.drive < 0 && lacks(s, "no drive '" + s.drive + "'", scene.drives)) continue;
    }
    if (!s.indicator.empty()) {
      b.indicator = index_of(scene.indicators, s.indicator);
      if (b.indicator < 0 && lacks(s, "no indicator '" + s.indicator + "'", scene.indicators)) continue;
    }
    if (!s.at.empty()) {
      b.entity = index_of(entities, s.at);
      if (b.entity < 0 && lacks(s, "no entity '" + s.at + "'", entities)) continue;
    }
    const std::uint32_t seed = seed_of(s.name);
    switch (s.kind) {
      case SourceKind::kElectricDrive:
        b.voice.reset(new Voice{ElectricDriveVoice(s.electric, seed)});
        break;
      case SourceKind::kDiesel:
        b.voice.reset(new Voice{DieselVoice(s.diesel, seed)});
        break;
      case SourceKind::kHydraulic:
        b.voice.reset(new Voice{HydraulicVoice(s.hydraulic, seed)});
        break;
      case SourceKind::kImpact:
      case SourceKind::kClunk:
      case SourceKind::kBrake:
        b.voice.reset(new Voice{KnockVoice(s.knock, seed)});
        break;
      case SourceKind::kAlarm:
        b.voice.reset(new Voice{ToneVoice(s.tone)});
        break;
      case SourceKind::kWind:
      case SourceKind::kRain:
      case SourceKind::kSea:
      case SourceKind::kHarbour:
      case SourceKind::kPour:
        b.voice.reset(new Voice{NoiseVoice(s.noise, seed)});
        break;
      case SourceKind::kRadio:
        b.voice.reset(new Voice{ClipVoice()});
        radio_ = static_cast<int>(sources_.size());
        break;
    }
    b.block.assign(kBlockFrames, 0.0f);
    sources_.push_back(std::move(b));
  }
}

SoundScape::~SoundScape() = default;

void SoundScape::set_radio_script(const scene::RadioScript& script) {
  if (radio_ < 0) return;
  language_ = script.language;
  script_.clear();
  const double level = radio_level();
  for (const scene::RadioCall& call : script.calls)
    script_.emplace_back(
        call.at_s, std::make_shared<const std::vector<float>>(speak_on_radio(call.text, language_, level)));
}

bool SoundScape::say(const std::string& text) {
  if (radio_ < 0) return false;
  hear(std::make_shared<const std::vector<float>>(speak_on_radio(text, language_, radio_level())));
  return true;
}

void SoundScape::hear(std::shared_ptr<const std::vector<float>> call) {
  if (radio_ >= 0) said_.push_back(std::move(call));
}

void SoundScape::update(const scene::Snapshot& s) {
  // the listener: the operator's eye, looking where the head (tracked, or turned by keys) looks
  const double yaw = s.cab.look_yaw_rad + s.cab.head_yaw_pitch_roll_rad.x;
  const double pitch = s.cab.look_pitch_rad + s.cab.head_yaw_pitch_roll_rad.y;
  const core::Mat3 head =
      s.cab.pose.rotation * core::Mat3::rotation({0, 0, 1}, yaw) * core::Mat3::rotation({0, 1, 0}, -pitch);
  listener_.position_m = s.cab.pose.to_parent(s.cab.eye_m + s.cab.head_offset_m);
  listener_.forward = head.column(0);
  listener_.up = head.column(2);

  if (last_step_ < 0) knocks_heard_ = s.knocks_total;  // it hears the impacts from its first snapshot on
  const bool powered = !s.power_off && !s.held && !s.diverged;
  for (Bound& b : sources_) {
    std::fill(b.block.begin(), b.block.end(), 0.0f);
    // an impact sounds where it happened (render() places it); the others where they sit
    if (b.entity >= 0 && b.entity < s.entity_count && b.settings.kind != SourceKind::kImpact)
      b.position_m = s.entities[static_cast<std::size_t>(b.entity)].pose.to_parent(b.settings.offset_m);
    render(b, s, powered);
  }
  knocks_heard_ = s.knocks_total;
  last_step_ = s.step;
  last_time_s_ = s.time_s;
}

void SoundScape::render(Bound& b, const scene::Snapshot& s, bool powered) {
  const std::span<float> out(b.block);
  const auto drive = [&]() {
    return b.drive >= 0 && b.drive < s.drive_count && powered ? s.drives[static_cast<std::size_t>(b.drive)]
                                                              : scene::Snapshot::Drive{};
  };
  const double value = b.indicator >= 0 && b.indicator < s.indicator_count
                           ? s.indicators[static_cast<std::size_t>(b.indicator)]
                           : 0.0;
  const double dt_s = s.time_s - last_time_s_;
  const bool first = last_step_ < 0;
  // where in this block a moment (a step) falls
  const auto sample_at = [&](std::int64_t step) {
    const double span = static_cast<double>(std::max<std::int64_t>(s.step - last_step_, 1));
    const double at = static_cast<double>(step - last_step_) / span * static_cast<double>(kBlockFrames);
    return static_cast<std::size_t>(std::clamp(at, 0.0, static_cast<double>(kBlockFrames - 1)));
  };
  std::visit(
      [&](auto& voice) {
        using V = std::decay_t<decltype(voice)>;
        if constexpr (std::is_same_v<V, ElectricDriveVoice> || std::is_same_v<V, DieselVoice> ||
                      std::is_same_v<V, HydraulicVoice>) {
          const scene::Snapshot::Drive d = drive();
          // an engine runs while the machine has power: at rest it idles (speed 0 is its idle)
          voice.render(out, {first ? d.speed : b.speed, d.speed}, {first ? d.load : b.load, d.load});
          if constexpr (std::is_same_v<V, DieselVoice>)
            if (!powered) std::fill(out.begin(), out.end(), 0.0f);
          b.speed = d.speed;
          b.load = d.load;
        } else if constexpr (std::is_same_v<V, KnockVoice>) {
          if (b.settings.kind == SourceKind::kImpact && !s.held) {
            for (std::int64_t k = s.first_knock_after(knocks_heard_); k < s.knocks_total; ++k) {
              const scene::Snapshot::Knock& knock = s.knock(k);
              const double strength = knock.impulse_ns / b.settings.reference_impulse_ns;
              if (strength < 0.01) continue;
              voice.strike(std::min(strength, 4.0), sample_at(knock.step));
              b.position_m = knock.point_m;
            }
          } else if (b.settings.kind == SourceKind::kClunk) {
            const bool arrived = !b.settings.at_ends || value == 0.0 || value == 1.0;
            if (!first && powered && value != b.value && arrived) voice.strike(1.0, 0);
          } else if (b.settings.kind == SourceKind::kBrake) {
            const bool moving = std::abs(drive().speed) > 0.005;
            if (!first && moving != b.moving) voice.strike(moving ? 0.5 : 1.0, 0);
            b.moving = moving;
          }
          voice.render(out);
        } else if constexpr (std::is_same_v<V, ClipVoice>) {
          // the script's calls due in this block, at their moment in it; the instructor's at its start
          const double from_s = first ? s.time_s - 0.01 : last_time_s_;
          for (const auto& [at_s, clip] : script_)
            if (at_s > from_s && at_s <= s.time_s) {
              const double share = dt_s > 0.0 ? (at_s - from_s) / (s.time_s - from_s) : 0.0;
              voice.start(clip, std::min(static_cast<std::size_t>(share * kBlockFrames), kBlockFrames - 1));
            }
          for (const auto& clip : said_)
            voice.start(clip, 0);
          said_.clear();
          voice.render(out);
        } else if constexpr (std::is_same_v<V, ToneVoice>) {
          const bool on = b.settings.wind_above_mps >= 0.0
                              ? core::length(s.wind_mps) > b.settings.wind_above_mps
                          : b.drive >= 0 ? std::abs(drive().speed) > 0.005
                                         : value > b.settings.above;
          voice.render(out, powered && on);
        } else {
          double amount = 0.0;
          switch (b.settings.kind) {
            case SourceKind::kWind:
            case SourceKind::kSea:
              amount = core::length(s.wind_mps);
              break;
            case SourceKind::kRain:
              amount = s.rain_mm_per_h;
              break;
            case SourceKind::kHarbour:
              amount = b.settings.noise.reference;
              break;
            case SourceKind::kPour:
              amount = !first && dt_s > 0.0 && powered ? std::max(0.0, (b.value - value) / dt_s) : 0.0;
              break;
            default:
              break;
          }
          voice.render(out, {first ? amount : b.amount, amount});
          b.amount = amount;
        }
      },
      b.voice->v);
  b.value = value;
}

}  // namespace harbour::audio
