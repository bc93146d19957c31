#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace harbour::scene {

/// Most controls one machine declares (an STS cab has 15).
inline constexpr int kMaxControls = 32;

/// The operator's controls as the executive steps with them: one value per control of the machine's control
/// table, at the control's slot (axes in their range, buttons 0/1, switches their position's index). Plain
/// and trivially copyable: latched once per step, recorded bit for bit.
struct Controls {
  std::array<double, kMaxControls> value{};
  friend bool operator==(const Controls&, const Controls&) = default;
};
static_assert(std::is_trivially_copyable_v<Controls>);

enum class ControlKind : std::uint8_t {
  kAxis,    ///< a lever, pedal or stick: a number in [min, max]
  kButton,  ///< pressed (1) or not (0) while held
  kSwitch,  ///< a selector with named positions: the position's index
};

/// One control of a machine (its data file's `controls:` entry).
struct ControlSpec {
  std::string label;  ///< hoist, trolley, gantry, lock, spreader_20, flipper_1, horn, emergency_stop, ...
  ControlKind kind = ControlKind::kAxis;
  double min = -1.0, max = 1.0;        ///< axis range
  std::vector<std::string> positions;  ///< switch positions, in order
  double neutral = 0.0;  ///< at rest: centred lever, released button, a switch's rest position (index)
  double safe = 0.0;     ///< what the control reads when its device is lost (by default: neutral)
  std::string meaning;   ///< what it does, for people (device binding, docs)
  friend bool operator==(const ControlSpec&, const ControlSpec&) = default;
};

/// A machine's controls, by label. Slots are the entries' order.
class ControlTable {
 public:
  ControlTable() = default;
  /// Throws std::invalid_argument naming the control: a duplicate or empty label, more than kMaxControls,
  /// min >= max, a switch with fewer than two positions, a neutral or safe value outside the control's range.
  explicit ControlTable(std::vector<ControlSpec> controls);

  int size() const { return static_cast<int>(controls_.size()); }
  const ControlSpec& operator[](int slot) const { return controls_[static_cast<std::size_t>(slot)]; }
  std::span<const ControlSpec> controls() const { return controls_; }
  /// Slot of `label`, or -1.
  int find(std::string_view label) const;
  /// Slot of `label` with this kind; throws std::invalid_argument naming what is missing or of another kind.
  int slot(std::string_view label, ControlKind kind) const;
  /// Every control at rest (neutral), or as a lost device leaves it (safe).
  Controls neutral() const;
  Controls safe() const;
  /// The controls as the machine reads them: an axis clamped into its range, a button 0 or 1, a switch at a
  /// whole position; a non-finite value (a device or link fault) reads as neutral; unused slots 0.
  Controls in_range(const Controls& controls) const;
  friend bool operator==(const ControlTable&, const ControlTable&) = default;

 private:
  std::vector<ControlSpec> controls_;
};

const char* to_string(ControlKind kind);

}  // namespace harbour::scene
