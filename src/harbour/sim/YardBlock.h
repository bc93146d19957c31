#pragma once

#include <optional>
#include <string>

#include "harbour/core/Vec3.h"

namespace harbour::sim {

/// A container yard block as data (settings): ground slots by bay, row and tier. Bays run along world y: odd
/// bays are 20 ft slots `bay_pitch_m` apart, an even bay the 40 ft slot over the two odd ones beside it (bay
/// 2 over 1 and 3), as terminals number them. Rows run along world x, `row_pitch_m` apart (negative: towards
/// -x); tiers count up from 1 on the ground, each `tier_height_m` (the boxes the block stacks: 2.896 m high
/// cubes). A stack holds `tiers` boxes: an RTG lifting one box over it (1-over-5 for 5).
struct YardBlock {
  core::Vec3 first_slot_m;  ///< [m] ground centre of bay 1, row 1 (z: the ground)
  int bays = 1;             ///< 20 ft bays
  int rows = 6;
  int tiers = 5;
  double bay_pitch_m = 6.4;
  double row_pitch_m = 2.8;
  double tier_height_m = 2.896;

  /// The centre of a box standing in slot (bay, row, tier), or nullopt with `why` set when the block has no
  /// such slot.
  std::optional<core::Vec3> slot_centre(int bay, int row, int tier, std::string& why) const {
    if (bay < 1 || bay > 2 * bays - 1) {
      why = "bay " + std::to_string(bay) + " is not in the block (1-" + std::to_string(2 * bays - 1) + ")";
      return std::nullopt;
    }
    if (row < 1 || row > rows) {
      why = "row " + std::to_string(row) + " is not in the block (1-" + std::to_string(rows) + ")";
      return std::nullopt;
    }
    if (tier < 1 || tier > tiers) {
      why = "tier " + std::to_string(tier) + " is not in the block: it stacks " + std::to_string(tiers) +
            " high";
      return std::nullopt;
    }
    return first_slot_m +
           core::Vec3{(row - 1) * row_pitch_m, 0.5 * (bay - 1) * bay_pitch_m, (tier - 0.5) * tier_height_m};
  }
};

}  // namespace harbour::sim
