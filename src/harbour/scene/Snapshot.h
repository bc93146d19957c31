#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "harbour/core/Vec3.h"

namespace harbour::scene {

inline constexpr std::uint32_t kSnapshotVersion = 5;
inline constexpr int kMaxSwells = 4;
inline constexpr int kMaxEntities = 2200;  ///< 2000 containers, the machine's bodies, vessel, trucks
inline constexpr int kMaxRopes = 8;
inline constexpr int kMaxRopePoints = 1024;
inline constexpr int kMaxIndicators = 32;
inline constexpr int kMaxDrives = 8;
inline constexpr int kMaxKnocks = 16;

/// The operator's design view from the cab, as the machine's file gives it: where a desktop picture looks
/// and how much of the world it shows. Yaw from the cab's x axis towards its y, pitch above its xy plane.
struct CabSight {
  double yaw_rad = 0.0;
  double pitch_rad = 0.0;          ///< negative: looking down
  double fov_vertical_rad = 0.75;  ///< of a picture on one screen (its width from the screen's shape)
  /// How far the operator can look round from it, left or right and up or down (the cab's windows)
  double look_yaw_rad = 1.92, look_pitch_rad = 1.05;
};

/// The look key of an ISO container `length_m` long: "container.20ft", "container.40ft" or "container.45ft".
inline const char* container_look(double length_m) {
  const double feet = length_m / 0.3048;
  return feet < 30 ? "container.20ft" : feet < 42 ? "container.40ft" : "container.45ft";
}

/// A name's livery key (32-bit FNV-1a of its bytes): an item is painted liveries[key % count] of its look, so
/// a box keeps its operator's colour wherever it is drawn (another station, the console, a later exercise).
constexpr std::uint32_t livery_key(std::string_view name) {
  std::uint32_t h = 2166136261u;
  for (const char c : name) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 16777619u;
  }
  return h;
}

/// The entity a truck's machine names its trailer's load by; a box handed onto it in a team session is drawn
/// by the box's own name instead (in the station's pictures, the consoles' views and the replays).
inline constexpr const char* kTrailerLoad = "load";

/// What a scene holds, fixed for a session: entities (what they look like and how big) and the names of the
/// indicators. Consumers read it once; each Snapshot then carries only numbers by index (as CIGI does).
struct SceneDescription {
  struct Entity {
    std::string name;           ///< "gantry", "spreader", a container's id, "truck 2"
    std::string visual;         ///< look key (data): "sts.gantry", "container.40ft", "hatch_cover", ...
    core::Vec3 half_extents_m;  ///< [m] box bounds in its frame (x along its length)
  };
  std::string machine;  ///< machine kind: "sts", ...
  std::vector<Entity> entities;
  int machine_entities = 0;  ///< the first this many are the machine's own (a chase view frames them)
  std::vector<std::string> indicators;  ///< "trolley_x_m", "load_t", "lamp_locked", ...
  std::vector<std::string> drives;      ///< the machine's drives and engines: "hoist", "engine", ...
  int rope_count = 0;
};

/// The published state of a running simulation: plain, fixed-size data (no allocation to write or copy),
/// written once per step into a triple buffer; the image generator, the console and the network read only
/// this. Versioned; step and time let a reader interpolate between two.
struct Snapshot {
  // header
  std::uint32_t version = kSnapshotVersion;
  std::uint32_t warnings = 0;  ///< physics warnings so far
  std::int64_t step = 0;
  double time_s = 0.0;
  bool held = false;        ///< frozen by the instructor
  bool diverged = false;    ///< the physics stopped
  int devices_missing = 0;  ///< input devices of the station's mapping not present (their controls read safe)
  bool power_off = false;   ///< the machine's supply has failed (an instructor's emergency)
  bool awaiting_zero = false;  ///< the supply is back; the drives wait for every lever at zero
  bool emergency_stop =
      false;             ///< the machine's emergency stop is in force (the trainee's or the instructor's)
  int hand_signal = -1;  ///< the signaller's latest hand signal (scene::hand_signals()), -1: none yet
  double hand_signal_at_s = 0.0;  ///< [s] when it was given

  // environment
  core::Vec3 wind_mps;  ///< [m/s] world
  double time_of_day_h = 12.0;
  double visibility_m = 20000.0;
  double rain_mm_per_h = 0.0;
  double cloud_oktas = 0.0;    ///< eighths of the sky under cloud
  double day_of_year = 80.0;   ///< sun and moon positions (80: the March equinox)
  double latitude_deg = 40.0;  ///< the harbour's

  /// The sea: its still level and the swell that moves the moored vessel, one long-crested wave per heave
  /// harmonic, in phase with the vessel's heave at `reference_m` (the vessel's midship waterline point), so
  /// the water round the hull rises and falls with it. The wind sea on top is the image generator's own,
  /// from the wind.
  struct Swell {
    double amplitude_m = 0.0, period_s = 10.0, phase_rad = 0.0;
    double direction_rad = 0.0;  ///< it travels towards (cos, sin) of this, world
  };
  struct Sea {
    double water_level_m = -3.5;
    core::Vec3 reference_m;
    int swell_count = 0;
    std::array<Swell, kMaxSwells> swells{};
  } sea;

  /// The operator's cab: where it is, where the eye sits in it, and what the operator's head feels (motion
  /// cues, in the cab frame: x forward, y left, z up).
  struct Cab {
    core::Pose pose;                 ///< cab frame in the world
    core::Vec3 eye_m;                ///< [m] design eye point, cab frame
    CabSight sight;                  ///< the design line of sight and field of view
    core::Vec3 specific_force_mps2;  ///< [m/s^2] acceleration minus gravity at the head (1 g up at rest)
    core::Vec3 angular_velocity_radps;
    /// Head tracking (the station fills these): the eye's offset from the design eye point [m, cab frame]
    /// and the head's yaw, pitch, roll [rad].
    core::Vec3 head_offset_m, head_yaw_pitch_roll_rad;
    /// Looking round without a tracker (keys, a mouse drag; the station fills them): the view turned left and
    /// up from where it looks [rad], about the picture's own up and right axes.
    double look_yaw_rad = 0.0, look_pitch_rad = 0.0;
  } cab;

  struct Entity {
    std::uint32_t index = 0;  ///< into SceneDescription::entities
    std::uint32_t flags = 0;  ///< kLocked, ...
    core::Pose pose;          ///< centre, world
  };
  static constexpr std::uint32_t kLocked = 1;  ///< held by the machine (on the spreader)
  /// Not drawn: not there yet (a load still to be handed over), or another station's to draw (a team truck,
  /// a box handed over to it)
  static constexpr std::uint32_t kHidden = 2;
  /// A box set down on a team truck, its cones holding it: to be handed over to the truck's station
  static constexpr std::uint32_t kOnTeamTruck = 4;
  int entity_count = 0;
  std::array<Entity, kMaxEntities> entities;

  /// Rope polylines: rope r's points are points[rope_first[r], rope_first[r] + rope_points[r]).
  int rope_count = 0;
  std::array<std::uint16_t, kMaxRopes> rope_first{}, rope_points{};
  std::array<core::Vec3, kMaxRopePoints> points;

  /// Indicator values, named by SceneDescription::indicators.
  int indicator_count = 0;
  std::array<double, kMaxIndicators> indicators{};

  /// What a drive or an engine is doing (what its sound and the platform's engine cues come from): its speed
  /// as a fraction of its rated speed (signed: + raises, drives out, forward; an engine's speed from idle,
  /// 0, to its governed speed, 1) and the force it gives as a fraction of its rated force or torque.
  struct Drive {
    double speed = 0.0;
    double load = 0.0;
  };
  int drive_count = 0;  ///< named by SceneDescription::drives
  std::array<Drive, kMaxDrives> drives{};

  /// Contact impacts of the recent steps (a landing, a collision, the grab on the material), newest last,
  /// each with the step it closed on, so a reader at a slower rate misses none of the last kMaxKnocks.
  struct Knock {
    std::int64_t step = 0;
    double impulse_ns = 0.0;  ///< [N s] normal contact impulse
    double speed_mps = 0.0;   ///< [m/s] closing speed along the contact normal
    core::Vec3 point_m;       ///< [m] world
  };
  std::int64_t knocks_total = 0;  ///< knocks since the start: knock k sits at knocks[k % kMaxKnocks]
  std::array<Knock, kMaxKnocks> knocks{};
  /// The first knock after the `seen` a reader has had that the snapshot still holds, and knock k.
  std::int64_t first_knock_after(std::int64_t seen) const {
    return seen > knocks_total - kMaxKnocks ? seen : knocks_total - kMaxKnocks;
  }
  const Knock& knock(std::int64_t k) const { return knocks[static_cast<std::size_t>(k % kMaxKnocks)]; }
};
static_assert(std::is_trivially_copyable_v<Snapshot>);

}  // namespace harbour::scene
