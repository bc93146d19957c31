#include "harbour/scene/HandSignals.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::scene {
namespace {

using Hand = SignalHand;
using Motion = SignalMotion;
constexpr ArmPose kOut{90.0, 90.0};  // held out sideways
constexpr ArmPose kForearmUp{90.0, 180.0};
constexpr ArmPose kPointingDown{25.0, 25.0};
constexpr ArmPose kFistBeforeChest{25.0, -110.0};

const HandSignal kSignals[] = {
    {.name = "stop",
     .words = "stop",
     .how = "right arm held out sideways, palm down, moved back and forth",
     .signalling = kOut,
     .motion = Motion::kWave},
    {.name = "emergency-stop",
     .words = "emergency stop",
     .how = "both arms held out sideways, palms down, moved back and forth",
     .emergency = true,
     .signalling = kOut,
     .other = kOut,
     .motion = Motion::kWave},
    {.name = "hoist",
     .words = "hoist",
     .how = "right forearm upright, index finger up, small circles",
     .controls = {"hoist"},
     .sense = 1,
     .signalling = kForearmUp,
     .hand = Hand::kIndexUp,
     .motion = Motion::kCircles},
    {.name = "lower",
     .words = "lower",
     .how = "right arm down and out, index finger down, small circles",
     .controls = {"hoist"},
     .sense = -1,
     .signalling = kPointingDown,
     .hand = Hand::kIndexDown,
     .motion = Motion::kCircles},
    {.name = "hoist-slowly",
     .words = "hoist slowly",
     .how = "the hoist signal, the left palm held over the right hand",
     .controls = {"hoist"},
     .sense = 1,
     .slowly = true,
     .signalling = kForearmUp,
     .hand = Hand::kIndexUp,
     .motion = Motion::kCircles},
    {.name = "lower-slowly",
     .words = "lower slowly",
     .how = "the lower signal, the left palm held under the right hand",
     .controls = {"hoist"},
     .sense = -1,
     .slowly = true,
     .signalling = kPointingDown,
     .hand = Hand::kIndexDown,
     .motion = Motion::kCircles},
    {.name = "trolley-out",
     .words = "trolley out",
     .how = "right arm out, fist, thumb pointing out, the hand jerked outwards",
     .controls = {"trolley"},
     .sense = 1,
     .signalling = kOut,
     .hand = Hand::kThumbOut,
     .motion = Motion::kJerkOut},
    {.name = "trolley-in",
     .words = "trolley in",
     .how = "right arm out, fist, thumb pointing in, the hand jerked inwards",
     .controls = {"trolley"},
     .sense = -1,
     .signalling = kOut,
     .hand = Hand::kThumbIn,
     .motion = Motion::kJerkIn},
    {.name = "boom-up",
     .words = "boom up",
     .how = "right arm out, fist, thumb up",
     .controls = {"boom", "luff"},
     .sense = 1,
     .signalling = kOut,
     .hand = Hand::kThumbUp},
    {.name = "boom-down",
     .words = "boom down",
     .how = "right arm out, fist, thumb down",
     .controls = {"boom", "luff"},
     .sense = -1,
     .signalling = kOut,
     .hand = Hand::kThumbDown},
    {.name = "slew-left",
     .words = "slew left",
     .how = "right arm out, index finger pointing the way to slew (the operator's left)",
     .controls = {"slew"},
     .sense = 1,
     .signalling = kOut,
     .hand = Hand::kIndexOut},
    {.name = "slew-right",
     .words = "slew right",
     .how = "left arm out, index finger pointing the way to slew (the operator's right)",
     .controls = {"slew"},
     .sense = -1,
     .signalling = kOut,
     .left_arm = true,
     .hand = Hand::kIndexOut},
    {.name = "extend",
     .words = "extend",
     .how = "both fists before the chest, thumbs pointing outwards",
     .controls = {"telescope"},
     .sense = 1,
     .signalling = kFistBeforeChest,
     .other = kFistBeforeChest,
     .hand = Hand::kFists,
     .motion = Motion::kJerkOut},
    {.name = "retract",
     .words = "retract",
     .how = "both fists before the chest, thumbs pointing at each other",
     .controls = {"telescope"},
     .sense = -1,
     .signalling = kFistBeforeChest,
     .other = kFistBeforeChest,
     .hand = Hand::kFists,
     .motion = Motion::kJerkIn},
};

// the reading of an axis as a share of half its range from its neutral (positive: the + way)
double lever(const ControlSpec& c, double value) {
  return (value - c.neutral) / ((c.max - c.min) / 2.0);
}

bool every_motion_at_rest(const ControlTable& table, const Controls& read) {
  for (const std::string_view label : kSignalStopControls) {
    const int slot = table.find(label);
    if (slot < 0 || table[slot].kind != ControlKind::kAxis) continue;
    if (std::abs(lever(table[slot], read.value[static_cast<std::size_t>(slot)])) > kSignalRestBand)
      return false;
  }
  return true;
}

int asked_slot(const HandSignal& signal, const ControlTable& table) {
  for (const std::string_view label : signal.controls) {
    if (label.empty()) continue;
    const int slot = table.find(label);
    if (slot >= 0 && table[slot].kind == ControlKind::kAxis) return slot;
  }
  return -1;
}

}  // namespace

std::span<const HandSignal> hand_signals() {
  return kSignals;
}

int find_hand_signal(std::string_view name) {
  for (std::size_t n = 0; n < std::size(kSignals); ++n)
    if (kSignals[n].name == name) return static_cast<int>(n);
  return -1;
}

std::string hand_signal_names() {
  std::string names;
  for (const HandSignal& s : kSignals)
    names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

std::string why_not_for(const HandSignal& signal, const ControlTable& table) {
  if (signal.sense != 0) {
    if (asked_slot(signal, table) >= 0) return "";
    return "no " + std::string(signal.controls[0]) + " control to follow '" + std::string(signal.words) + "'";
  }
  for (const std::string_view label : kSignalStopControls)
    if (const int slot = table.find(label); slot >= 0 && table[slot].kind == ControlKind::kAxis) return "";
  return "no motion a signaller stops";
}

bool follows(const HandSignal& signal, const ControlTable& table, const Controls& controls) {
  const Controls read = table.in_range(controls);
  if (signal.sense == 0) {
    if (signal.emergency) {
      const int stop = table.find("emergency_stop");
      if (stop >= 0 && read.value[static_cast<std::size_t>(stop)] > 0.5) return true;
    }
    return every_motion_at_rest(table, read);
  }
  const int slot = asked_slot(signal, table);
  if (slot < 0) return false;
  const double moved = signal.sense * lever(table[slot], read.value[static_cast<std::size_t>(slot)]);
  return moved >= kSignalMovedBand && (!signal.slowly || moved <= kSignalSlowlyBand);
}

std::vector<std::vector<double>> signal_strokes(const HandSignal& signal) {
  std::vector<std::vector<double>> strokes;
  const auto circle = [&](double cx, double cy, double rx, double ry) {
    std::vector<double> c;
    for (int k = 0; k <= 16; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 16.0;
      c.insert(c.end(), {cx + rx * std::cos(a), cy + ry * std::sin(a)});
    }
    strokes.push_back(std::move(c));
  };
  const auto arrow = [&](double x0, double y0, double x1, double y1, bool both_ends) {
    strokes.push_back({x0, y0, x1, y1});
    const auto head = [&](double tx, double ty, double fx, double fy) {
      const double l = std::hypot(tx - fx, ty - fy), ux = (tx - fx) / l, uy = (ty - fy) / l;
      strokes.push_back({tx - 0.05 * ux + 0.03 * uy, ty - 0.05 * uy - 0.03 * ux, tx, ty,
                         tx - 0.05 * ux - 0.03 * uy, ty - 0.05 * uy + 0.03 * ux});
    };
    head(x1, y1, x0, y0);
    if (both_ends) head(x0, y0, x1, y1);
  };
  // the body: head, trunk, shoulders, legs
  circle(0.0, 1.62, 0.11, 0.11);
  strokes.push_back({0.0, 1.51, 0.0, 0.95});
  strokes.push_back({-0.2, 1.42, 0.2, 1.42});
  strokes.push_back({-0.14, 0.0, 0.0, 0.95, 0.14, 0.0});
  // the arms: side -1 on the operator's left (the signaller's right)
  const double signalling_side = signal.left_arm ? 1.0 : -1.0;
  const auto hand_of = [&](const ArmPose& pose, double side, std::vector<double>& arm) {
    const double to_rad = std::numbers::pi / 180.0;
    const double sx = 0.2 * side, sy = 1.42;
    const double ex = sx + 0.30 * side * std::sin(pose.upper_deg * to_rad),
                 ey = sy - 0.30 * std::cos(pose.upper_deg * to_rad);
    const double hx = ex + 0.28 * side * std::sin(pose.fore_deg * to_rad),
                 hy = ey - 0.28 * std::cos(pose.fore_deg * to_rad);
    arm = {sx, sy, ex, ey, hx, hy};
    return std::pair{hx, hy};
  };
  std::vector<double> arm;
  const auto [hx, hy] = hand_of(signal.signalling, signalling_side, arm);
  strokes.push_back(arm);
  const double other_side = -signalling_side;
  if (signal.slowly) {  // the other palm held at the signalling hand
    const double sx = 0.2 * other_side, py = signal.sense > 0 ? hy + 0.07 : hy - 0.07;
    strokes.push_back({sx, 1.42, (sx + hx) / 2.0, std::min(1.42, py) - 0.18, hx, py});
    strokes.push_back({hx - 0.06, py, hx + 0.06, py});
  } else {
    hand_of(signal.other, other_side, arm);
    strokes.push_back(arm);
  }
  // the hand
  const double out = signalling_side;  // away from the body, on the signalling side
  const auto fist = [&](double x, double y) {
    strokes.push_back(
        {x - 0.03, y - 0.03, x + 0.03, y - 0.03, x + 0.03, y + 0.03, x - 0.03, y + 0.03, x - 0.03, y - 0.03});
  };
  switch (signal.hand) {
    case Hand::kPalmDown:
      strokes.push_back({hx - 0.06, hy, hx + 0.06, hy});
      if (signal.emergency) strokes.push_back({-hx - 0.06, hy, -hx + 0.06, hy});
      break;
    case Hand::kIndexUp:
      strokes.push_back({hx, hy, hx, hy + 0.12});
      break;
    case Hand::kIndexDown:
      strokes.push_back({hx, hy, hx, hy - 0.12});
      break;
    case Hand::kIndexOut:
      strokes.push_back({hx, hy, hx + 0.12 * out, hy});
      break;
    case Hand::kThumbUp:
      fist(hx, hy);
      strokes.push_back({hx, hy + 0.03, hx, hy + 0.1});
      break;
    case Hand::kThumbDown:
      fist(hx, hy);
      strokes.push_back({hx, hy - 0.03, hx, hy - 0.1});
      break;
    case Hand::kThumbOut:
      fist(hx, hy);
      strokes.push_back({hx + 0.03 * out, hy, hx + 0.1 * out, hy});
      break;
    case Hand::kThumbIn:
      fist(hx, hy);
      strokes.push_back({hx, hy + 0.03, hx - 0.07 * out, hy + 0.06});
      break;
    case Hand::kFists:
      fist(hx, hy);
      fist(-hx, hy);
      break;
  }
  // how it moves
  switch (signal.motion) {
    case Motion::kStill:
      break;
    case Motion::kCircles:
      circle(hx, signal.hand == Hand::kIndexUp ? hy + 0.12 : hy - 0.12, 0.09, 0.035);
      break;
    case Motion::kWave:
      arrow(hx - 0.16, hy - 0.1, hx + 0.16, hy - 0.1, true);
      if (signal.emergency) arrow(-hx - 0.16, hy - 0.1, -hx + 0.16, hy - 0.1, true);
      break;
    case Motion::kJerkOut:
    case Motion::kJerkIn: {
      const bool outwards = signal.motion == Motion::kJerkOut;
      for (const double side : signal.hand == Hand::kFists ? std::vector{-1.0, 1.0} : std::vector{out}) {
        const double x = signal.hand == Hand::kFists ? side * std::abs(hx) : hx, y = hy + 0.12;
        outwards ? arrow(x, y, x + 0.2 * side, y, false) : arrow(x + 0.2 * side, y, x, y, false);
      }
      break;
    }
  }
  return strokes;
}

}  // namespace harbour::scene
