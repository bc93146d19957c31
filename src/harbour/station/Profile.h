#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "harbour/io/PlatformLink.h"
#include "harbour/io/YamlFile.h"

namespace harbour::station {

/// One display channel of the image generator: a window or projector, and where it looks from the eye.
struct DisplayChannel {
  std::string name;
  int width = 1920, height = 1080;
  bool fullscreen = false;
  /// Drawn by a `harboursim channel` process (a projector's own host, fed over the network), not the station
  bool remote = false;
  bool hud = false;  ///< it carries the heads-up display (the profile's first display)
  double yaw_rad = 0.0, pitch_rad = 0.0, roll_rad = 0.0;  ///< view offset from the cab's forward axis
  /// No pitch given: yaw_rad and pitch_rad are offsets from the machine's design line of sight (a desktop
  /// monitor looks where the operator looks)
  bool from_sight = false;
  /// No field of view given: the machine's design one (the width from the picture's shape)
  bool fov_from_sight = false;
  double fov_horizontal_rad = 1.2, fov_vertical_rad = 0.75;  ///< symmetric frustum
  /// An asymmetric frustum (a projection screen not centred on the eye): angles of its left, right, bottom
  /// and top edges from the view axis [rad], left and bottom negative; empty: the symmetric one above.
  std::optional<std::array<double, 4>> frustum_rad;
};

/// A hardware configuration (data/profiles/*.yaml): desktop, medium or fully immersive.
struct Profile {
  std::string name;
  std::string file;
  /// device mapping files, in order of preference: as the profile lists them, a `{folder, class}` entry
  /// standing for every mapping of that class in the folder, by file name (a new machine's mappings join
  /// without an edit to the profile)
  std::vector<std::string> mappings;
  std::vector<DisplayChannel> displays;
  /// One window for all the displays, side by side (a desktop, or projectors on one wide desktop), or one
  /// window per display, each full screen on its own output where the display system has one.
  enum class Windows { kShared, kPerDisplay };
  Windows windows = Windows::kShared;
  /// Stereo: each eye drawn with the eyes `eye_separation_m` apart and no parallax at `convergence_m`;
  /// side by side (each eye half the width: 3D televisions and projectors) or a red-cyan anaglyph.
  struct Stereo {
    enum class Mode { kSideBySide, kAnaglyph };
    Mode mode = Mode::kSideBySide;
    double eye_separation_m = 0.064, convergence_m = 3.0;
  };
  std::optional<Stereo> stereo;
  struct Motion {
    std::string platform, washout;  ///< files
    io::DriverSettings driver;
  };
  std::optional<Motion> motion;
  std::optional<std::uint16_t> opentrack_port;
  /// The machine's and the harbour's sound: on two speakers, headphones (through an HRTF: sound from all
  /// round) or 5.1 speakers round a cabin, at a master volume.
  struct Sound {
    enum class Output { kSpeakers, kHeadphones, kSurround51 };
    Output output = Output::kSpeakers;
    double volume = 1.0;  ///< [0, 2]
  };
  std::optional<Sound> sound;
};

/// The profile with only the displays `keep` says yes to (the station's own; a remote channel's one), each
/// drawn there as a display of its own (not remote).
Profile with_displays(const Profile& profile, const std::function<bool(const DisplayChannel&)>& keep);

/// Reads and checks a profile (every file it names exists; displays 1-8, sizes, angles); errors name file,
/// line and field.
Profile load_profile(const std::string& path);

/// A shipped profile's file (<data_dir>/profiles/<name>.yaml), or `name_or_path` itself when it is a file.
std::string resolve_profile(const std::string& name_or_path, const std::string& data_dir);

}  // namespace harbour::station
