#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "harbour/core/Vec3.h"

namespace harbour::sim {

/// What the other stations of a team session make happen in this one: its inputs from the network, applied
/// before a step like an instructor's command and recorded with that step, so that a replay of this station's
/// machine runs bit for bit as the session ran, the others' states read back as they arrived.
struct TeamInput {
  enum class Kind : std::uint8_t {
    /// A team truck of the crane's lane (truck `slot`: another station's trailer) stands at `pose` (its
    /// deck's
    /// top centre, x along its length), moving at `velocity_mps` and turning at `angular_velocity_radps`.
    kTruckAt,
    /// The box seated on team truck `slot` has been taken over by the truck's station: it is that station's
    /// now (simulated and drawn there); here it stays, fixed to the truck, as something to collide with, and
    /// is no longer drawn.
    kTakenOver,
    /// A box handed over to this station's trailer: `mass_kg` set down at `pose` (its centre in the trailer's
    /// frame); the trailer's locating cones hold it from now on.
    kLoadOn,
    /// Another member's machine body, obstacle `slot` of this station (TeamObstacles): a box of
    /// `half_extents_m` (zero: gone, its member left) centred at `pose`, moving so (recording version 10).
    kObstacleAt,
  };
  static constexpr std::uint8_t kKinds = 4;
  Kind kind = Kind::kTruckAt;
  int slot = 0;
  core::Pose pose;
  core::Vec3 velocity_mps, angular_velocity_radps;
  double mass_kg = 0.0;
  core::Vec3 half_extents_m;  ///< kObstacleAt's
  /// kLoadOn's: the handed box's name (its ISO 6346 code), printable ASCII, NUL-padded (recording version 11;
  /// a fixed array: the input crosses the step thread's queues without allocating).
  static constexpr std::size_t kMostItemChars = 19;
  std::array<char, kMostItemChars + 1> item{};

  std::string item_name() const;
  /// `item` set to `name`; false (and `item` left empty) where it is longer than kMostItemChars.
  bool name_item(std::string_view name);
};

/// A trailer's deck (its top centre, in the trailer's orientation) from the trailer body's pose and half
/// height: where a crane's team truck stands for it.
inline core::Pose deck_of_trailer(const core::Pose& trailer, double half_height_m) {
  return {trailer.rotation, trailer.to_parent({0, 0, half_height_m})};
}

/// A box's pose in its trailer's frame (what kLoadOn carries), from the deck's pose and the box's (world) and
/// the trailer's half height.
inline core::Pose on_trailer(const core::Pose& deck, const core::Pose& box, double half_height_m) {
  return {deck.rotation.transposed() * box.rotation,
          deck.to_local(box.position) + core::Vec3{0, 0, half_height_m}};
}

/// Why `input` is out of range ("" when it is not): non-finite numbers, a mass outside 0-80 t, a slot < 0, an
/// obstacle's slot past TeamObstacles::kMostObstacles or a side outside 0-50 m, an item's name of other than
/// printable ASCII.
std::string why_invalid(const TeamInput& input);

}  // namespace harbour::sim
