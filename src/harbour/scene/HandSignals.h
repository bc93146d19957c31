#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harbour/scene/Controls.h"

namespace harbour::scene {

/// What the signaller's hand shows at the end of the signalling arm.
enum class SignalHand : std::uint8_t {
  kPalmDown,
  kIndexUp,
  kIndexDown,
  kIndexOut,  ///< pointing away from the body
  kThumbUp,
  kThumbDown,
  kThumbOut,
  kThumbIn,
  kFists,  ///< both fists before the chest
};
/// How the hand moves while it signals.
enum class SignalMotion : std::uint8_t { kStill, kCircles, kWave, kJerkOut, kJerkIn };

/// One arm of the signaller as the operator sees it: the upper arm's angle from hanging down, outwards from
/// the body (negative: across it), and the forearm's, both [deg] in the picture's plane.
struct ArmPose {
  double upper_deg = 0.0, fore_deg = 0.0;
};

/// A hand signal (ISO 16715:2014, "Cranes - Hand signals used with cranes"), as the signaller gives it to the
/// operator, and what following it means at the controls: a motion's control moved in its sense (gently for
/// a "slowly"), or every motion's control back at rest.
struct HandSignal {
  std::string_view name;   ///< "hoist-slowly": the command's value, the records' word
  std::string_view words;  ///< "hoist slowly": said on the radio, shown in the cab
  std::string_view how;    ///< how it is given
  /// The control it asks for, by either label (the crane's boom is `boom` or `luff`); none: stop every motion
  std::array<std::string_view, 2> controls{};
  int sense = 0;           ///< +1 or -1 on that control; 0: stop
  bool slowly = false;     ///< the other hand's palm over the signalling hand: at most half the lever
  bool emergency = false;  ///< both arms: the emergency stop pressed also follows it
  /// The arm that signals and the other, as the operator sees them: the signaller's right arm (on the
  /// operator's left) signals unless `left_arm`
  ArmPose signalling, other;
  bool left_arm = false;
  SignalHand hand = SignalHand::kPalmDown;
  SignalMotion motion = SignalMotion::kStill;
};

/// Every hand signal, in the order the console offers them (a signal is its index here in a command).
std::span<const HandSignal> hand_signals();
/// The index of the signal named `name`, or -1.
int find_hand_signal(std::string_view name);
/// The names, comma-separated (for messages).
std::string hand_signal_names();

/// The controls a stop signal wants at rest, those of them a machine has (its motions and its drive).
inline constexpr std::array<std::string_view, 9> kSignalStopControls = {
    "hoist", "trolley", "gantry", "boom", "luff", "slew", "telescope", "rotate", "throttle"};
/// Beyond this share of half its range from neutral a lever is moved; within kSignalRestBand, at rest.
inline constexpr double kSignalMovedBand = 0.10;
inline constexpr double kSignalRestBand = 0.05;
/// A "slowly" signal is followed with the lever at most this share of its way.
inline constexpr double kSignalSlowlyBand = 0.5;

/// Why a machine with `table` cannot follow `signal` ("" when it can): it has none of its controls.
std::string why_not_for(const HandSignal& signal, const ControlTable& table);
/// Whether `controls` (as the operator holds them) follow `signal` on a machine with `table`.
bool follows(const HandSignal& signal, const ControlTable& table, const Controls& controls);

/// The signaller drawn as strokes (polylines of x, y pairs, metres, feet at the origin, x to the operator's
/// right, y up), the signalling hand's motion marked: what the cab's picture and the console draw.
std::vector<std::vector<double>> signal_strokes(const HandSignal& signal);

}  // namespace harbour::scene
