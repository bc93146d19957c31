#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "harbour/audio/Synth.h"
#include "harbour/core/Vec3.h"
#include "harbour/scene/RadioScript.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::audio {

/// What a sound is and what drives it.
enum class SourceKind : std::uint8_t {
  kElectricDrive,  ///< a drive's motor: its speed and load (ElectricDriveSettings)
  kDiesel,         ///< an engine: its speed and load (DieselSettings)
  kHydraulic,      ///< a cylinder's pump and valves: its speed (flow) and load (pressure)
  kImpact,         ///< the contacts' impacts: a knock per impact, its strength the impulse (KnockSettings)
  kClunk,          ///< a knock when an indicator changes (twistlocks turning, flippers)
  kBrake,          ///< a knock when a drive comes to rest (its brake setting) or starts (released)
  kAlarm,          ///< a tone while a condition holds (ToneSettings)
  kWind,           ///< the wind's speed [m/s] (NoiseSettings)
  kRain,           ///< the rain's rate [mm/h]
  kSea,            ///< the sea's state from the wind [m/s]
  kHarbour,        ///< the harbour's distant hum (always)
  kPour,           ///< material leaving the tool: an indicator's rate of fall [t/s]
  kRadio,          ///< the cab's radio: the exercise's scripted calls and the instructor's, spoken
};

/// One sound of a machine (its machine file's `sounds`) or of the harbour (data/sounds/harbour.yaml), as
/// data.
struct SoundSource {
  std::string name;  ///< "hoist motors"
  SourceKind kind = SourceKind::kElectricDrive;
  std::string drive;      ///< the machine's drive it follows (SceneDescription::drives)
  std::string indicator;  ///< the indicator it follows (clunk: changes; alarm: above `above`; pour: falls)
  double above = 0.5;     ///< alarm: sounds while the indicator is above this (or the drive moves)
  double wind_above_mps = -1.0;  ///< alarm: sounds while the wind is stronger than this (an anemometer's)
  bool at_ends = false;          ///< clunk: only when the indicator arrives at 0 or 1 (a flipper on its stop)
  std::string at;  ///< the entity it sits on ("trolley"); empty: round the listener (ambience); an impact
                   ///< sounds where the contact was
  core::Vec3 offset_m;                   ///< [m] on that entity, its frame
  double reference_distance_m = 10.0;    ///< [m] where its level is as set (halved at twice it)
  double reference_impulse_ns = 2000.0;  ///< [N s] impact: the impulse whose knock has the set level
  bool optional = false;     ///< skipped where the scene lacks what it names (a grab's sound on a hook)
  double radio_level = 0.3;  ///< radio: a call's peak amplitude
  ElectricDriveSettings electric;
  DieselSettings diesel;
  HydraulicSettings hydraulic;
  KnockSettings knock;
  ToneSettings tone;
  NoiseSettings noise;
};

/// The harbour's sounds: each machine kind's, and the ambience every scene has.
struct SoundSettings {
  std::map<std::string, std::vector<SoundSource>> machines;
  std::vector<SoundSource> ambience;
};

/// The listener: the operator's head in the cab (world).
struct Listener {
  core::Vec3 position_m, forward, up{0.0, 0.0, 1.0};
};

/// The sounds of one scene, rendered block by block from its snapshots: machine-blind (the machine's
/// sounds come as data by its kind, bound by name to its drives, indicators and entities). Deterministic:
/// the same snapshots give the same samples.
class SoundScape {
 public:
  static constexpr std::size_t kBlockFrames = 480;  ///< 10 ms at 48 kHz

  /// Binds the machine's sounds (by `scene.machine`) and, with `ambience`, the harbour's; throws
  /// std::invalid_argument naming the source and what it names that the scene lacks.
  SoundScape(const scene::SceneDescription& scene, const SoundSettings& settings, bool ambience = true);
  ~SoundScape();
  SoundScape(const SoundScape&) = delete;
  SoundScape& operator=(const SoundScape&) = delete;

  /// Renders the next block: from the last snapshot's state to `snapshot`'s (the block's end), each
  /// source's mono samples, its place and where the listener is.
  void update(const scene::Snapshot& snapshot);
  /// The exercise's radio script, spoken now (each call heard when the snapshots' time passes it); throws
  /// AudioError when espeak-ng cannot speak its language. Ignored without a radio among the sounds.
  void set_radio_script(const scene::RadioScript& script);
  /// A call spoken on the radio from the next block (the instructor's, in the script's language); throws
  /// AudioError when espeak-ng cannot speak it. Returns false without a radio among the sounds.
  bool say(const std::string& text);
  /// A call already spoken (speak_on_radio) heard from the next block; ignored without a radio.
  void hear(std::shared_ptr<const std::vector<float>> call);
  bool has_radio() const { return radio_ >= 0; }
  const std::string& radio_language() const { return language_; }
  double radio_level() const {
    return radio_ >= 0 ? sources_[static_cast<std::size_t>(radio_)].settings.radio_level : 0.0;
  }

  std::size_t source_count() const { return sources_.size(); }
  const SoundSource& source(std::size_t k) const { return sources_[k].settings; }
  std::span<const float> block(std::size_t k) const { return sources_[k].block; }
  /// Where source k sits [m, world]; ambience sits on the listener (`relative`).
  core::Vec3 position_m(std::size_t k) const { return sources_[k].position_m; }
  bool relative(std::size_t k) const {
    return sources_[k].entity < 0 && sources_[k].settings.kind != SourceKind::kImpact;
  }
  const Listener& listener() const { return listener_; }

 private:
  struct Voice;
  struct Bound {
    SoundSource settings;
    int drive = -1, indicator = -1, entity = -1;
    std::unique_ptr<Voice> voice;
    std::vector<float> block;
    core::Vec3 position_m;
    double speed = 0.0, load = 0.0, amount = 0.0, value = 0.0;  // at the last block's end
    bool moving = false;
  };
  void render(Bound& b, const scene::Snapshot& s, bool powered);

  std::vector<Bound> sources_;
  using Clip = std::shared_ptr<const std::vector<float>>;
  std::vector<std::pair<double, Clip>> script_;  // [s] exercise time, the call as heard
  std::string language_ = "en";
  std::vector<Clip> said_;  // the instructor's, from the next block
  int radio_ = -1;          // the radio's source
  Listener listener_;
  std::int64_t last_step_ = -1;
  double last_time_s_ = 0.0;
  std::int64_t knocks_heard_ = 0;
};

}  // namespace harbour::audio
