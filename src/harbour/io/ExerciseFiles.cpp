#include "harbour/io/ExerciseFiles.h"

#include <sodium.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>

#include "harbour/core/StateHash.h"
#include "harbour/core/Text.h"
#include "harbour/core/Units.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/BulkFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/MachineFiles.h"
#include "harbour/io/VesselFiles.h"
#include "harbour/sim/Trucks.h"

namespace harbour::io {

std::string iso6346_code(const std::string& owner_and_category, int serial) {
  char digits[8];
  std::snprintf(digits, sizeof digits, "%06d", serial % 1000000);
  const std::string code = owner_and_category + digits;
  // each character's value (letters 10-38 skipping the multiples of 11) times 2 to its place, mod 11
  long sum = 0;
  for (std::size_t n = 0; n < code.size(); ++n) {
    const char c = code[n];
    static constexpr int kLetter[26] = {10, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 23, 24,
                                        25, 26, 27, 28, 29, 30, 31, 32, 34, 35, 36, 37, 38};
    const long value = c >= 'A' && c <= 'Z' ? kLetter[c - 'A'] : c - '0';
    sum += value << n;
  }
  return code + std::to_string(sum % 11 % 10);
}

const std::map<std::string, IsoType>& iso_types() {
  // ISO 668 external dimensions [m] and typical tare [kg] (../shared/data/reference.md)
  static const std::map<std::string, IsoType> types = {{"20ft", {{6.058, 2.438, 2.591}, 2300}},
                                                       {"40ft", {{12.192, 2.438, 2.591}, 3750}},
                                                       {"40ftHC", {{12.192, 2.438, 2.896}, 3940}},
                                                       {"45ftHC", {{13.716, 2.438, 2.896}, 4820}}};
  return types;
}

namespace {

// the scripted faults: the instructor's commands of the same name (as exercise files spell it:
// file_spelling)
struct FaultEvent {
  sim::InstructorCommand::Kind command;
  sim::MachineFault fault;
  sim::ScriptedEvent::Kind event;
  const char* part;  // what the fault breaks
};
constexpr FaultEvent kFaultEvents[] = {
    {sim::InstructorCommand::Kind::kHoistBrakeFault, sim::MachineFault::kHoistBrake,
     sim::ScriptedEvent::Kind::kHoistBrakeFault, "hoist brake"},
    {sim::InstructorCommand::Kind::kLandedSensorFault, sim::MachineFault::kLandedSensor,
     sim::ScriptedEvent::Kind::kLandedSensorFault, "twistlocks"},
    {sim::InstructorCommand::Kind::kLimiterFault, sim::MachineFault::kLoadMomentLimiter,
     sim::ScriptedEvent::Kind::kLimiterFault, "load-moment limiter"},
};

// by its name, spelt with underscores or (as the console and the command line do) hyphens
const FaultEvent* find_fault_event(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  for (const FaultEvent& e : kFaultEvents)
    if (name == file_spelling(e.command)) return &e;
  return nullptr;
}

// the events an exercise file may script: a gust, and each fault `has_fault` lets the machine suffer
template <typename HasFault>
std::vector<std::string> scriptable_events(HasFault has_fault) {
  std::vector<std::string> kinds{"gust"};
  for (const FaultEvent& e : kFaultEvents)
    if (has_fault(e.fault)) kinds.push_back(file_spelling(e.command));
  return kinds;
}

// counts an exercise may hold (docs/reliability.md): far above any real exercise, bounded so that a
// generated or damaged file cannot make loading or stepping unbounded
constexpr std::size_t kMaxContainers = 2000, kMaxMoves = 500, kMaxEvents = 500, kMaxBlocks = 200;

// ISO 668 corner casting centres [m] (length, width): 20 ft, and 40 ft (also on 45 ft boxes and hatch covers)
constexpr double kCastings20_m[2] = {5.853, 2.259};
constexpr double kCastings40_m[2] = {11.985, 2.259};
constexpr double kCastings45_m = 13.509;  // a 45 ft box's end castings, lengthwise

std::string item(const std::string& list, std::size_t n) {
  return list + "[" + std::to_string(n) + "]";
}

}  // namespace

namespace {

// a slot address [bay, row, tier] of whole numbers 0-200 (on a vessel or in a yard block)
sim::SlotAddress read_slot_address(const YamlFile& f, const YAML::Node& slot, const std::string& at) {
  if (!slot.IsSequence() || slot.size() != 3) f.fail(slot, at, "must be [bay, row, tier]");
  sim::SlotAddress address;
  int* parts[] = {&address.bay, &address.row, &address.tier};
  for (std::size_t k = 0; k < 3; ++k) {
    double v = 0.5;  // not a number: refused below
    try {
      v = slot[k].as<double>();
    } catch (const YAML::Exception&) {
    }
    if (!(v >= 0.0 && v <= 200.0 && v == std::floor(v)))
      f.fail(slot, at, "bay, row and tier must be whole numbers 0-200");
    *parts[k] = static_cast<int>(v);
  }
  return address;
}

// a [bay, row, tier] in the exercise's yard block: the centre of a box standing there
core::Vec3 block_slot_centre(const YamlFile& f, const YAML::Node& slot, const std::string& at,
                             const std::optional<sim::YardBlock>& block) {
  if (!block) f.fail(slot, at, "a block slot needs the exercise's yard_block");
  const sim::SlotAddress a = read_slot_address(f, slot, at);
  std::string why;
  const std::optional<core::Vec3> centre = block->slot_centre(a.bay, a.row, a.tier, why);
  if (!centre) f.fail(slot, at, why);
  return *centre;
}

std::optional<sim::ExerciseAbout> read_about(const YamlFile& f, const YAML::Node& exercise) {
  const std::optional<YAML::Node> node = f.optional_map(exercise, "about", "exercise");
  if (!node) return std::nullopt;
  const std::string at = "exercise.about";
  const auto words = [&](const char* key, std::size_t most) {
    std::string text = f.text(*node, key, at);
    if (text.empty() || text.size() > most)
      f.fail((*node)[key], at + "." + key, "1 to " + std::to_string(most) + " characters");
    return text;
  };
  sim::ExerciseAbout about;
  about.title = words("title", 80);
  about.objective = words("objective", 400);
  about.difficulty = f.text(*node, "difficulty", at);
  if (about.difficulty != "beginner" && about.difficulty != "intermediate" && about.difficulty != "advanced")
    f.fail((*node)["difficulty"], at + ".difficulty",
           "'" + core::printable(about.difficulty, 40) + "': beginner, intermediate or advanced");
  about.expected_min = f.number(*node, "expected_min", at, 0.0, 600.0, true);
  return about;
}

// the vessel alongside and its hatch covers (listed after the containers)
std::optional<sim::VesselGeometry> read_vessel(const YamlFile& f, const YAML::Node& x,
                                               const std::string& folder, sim::ScenarioSettings& s,
                                               std::vector<sim::ContainerPlacement>& hatch_covers) {
  std::optional<sim::VesselGeometry> vessel;
  if (const auto v_node = f.optional_map(x, "vessel", "exercise")) {
    const YAML::Node& v = *v_node;
    const std::string file = f.text(v, "file", "exercise.vessel");
    const std::string path = (std::filesystem::path(folder) / file).lexically_normal().string();
    if (!std::filesystem::is_regular_file(path))
      f.fail(v["file"], "exercise.vessel.file", "no such file: " + path);
    sim::VesselPlacement placement;
    placement.vessel = load_vessel(path);
    placement.keel_midship_m = f.vector3(f.required(v, "keel_midship_m", "exercise.vessel"),
                                         "exercise.vessel.keel_midship_m", kSite_m);
    if (const auto sea = f.optional_map(v, "sea_state", "exercise.vessel"))
      placement.sea = read_sea_state(f, *sea, "exercise.vessel.sea_state");
    if (placement.keel_midship_m.x - placement.vessel.beam_m / 2 < s.quay_edge_x_m)
      f.fail(v["keel_midship_m"], "exercise.vessel.keel_midship_m",
             "the hull overlaps the quay (quay_edge_x_m)");
    s.vessel = placement;
    vessel.emplace(placement);
    // the hatch covers, each with lifting pockets where a 40 ft box has its castings
    for (const sim::VesselGeometry::Panel& panel : vessel->hatch_panels()) {
      sim::ContainerPlacement c;
      c.id = panel.id;
      c.kind = sim::ContainerPlacement::Kind::kHatchCover;
      c.half_extents_m = {panel.half_extents_m.y, panel.half_extents_m.x, panel.half_extents_m.z};
      c.gross_mass_kg = placement.vessel.hatch_cover_mass_kg;
      c.pose = vessel->stowed_pose_at(0.0, panel.centre_m);
      c.pocket_half_length_m = kCastings40_m[0] / 2;
      c.pocket_half_width_m = kCastings40_m[1] / 2;
      c.on_vessel = true;
      hatch_covers.push_back(c);
    }
  }
  return vessel;
}

// the quay's truck lane, yard block and fixed blocks
void read_site(const YamlFile& f, const YAML::Node& x, sim::ScenarioSettings& s) {
  if (const auto t_node = f.optional_map(x, "trucks", "exercise")) {
    const YAML::Node& t = *t_node;
    const std::string at = "exercise.trucks";
    sim::TruckLaneSettings& lane = s.trucks;
    lane.trucks = f.integer(t, "count", at, 1, 100);
    lane.lane_x_m = f.number(t, "lane_x_m", at, -kSite_m, kSite_m);
    lane.stop_y_m = f.number(t, "stop_y_m", at, -kSite_m, kSite_m);
    lane.chassis_top_m = f.number_or(t, "chassis_top_m", at, lane.chassis_top_m, 0.5, 3.0);
    lane.delivering = f.flag(t, "delivering", at, false);
    lane.team = f.flag(t, "team", at, false);
    lane.clearance_m = f.number_or(t, "clearance_m", at, lane.clearance_m, 0.2, 10.0);
    if (lane.team && lane.delivering)
      f.fail(t["team"], at + ".team",
             "a team's tractors take boxes away (delivering is not for a team lane)");
  }

  if (const auto y_node = f.optional_map(x, "yard_block", "exercise")) {
    const YAML::Node& y = *y_node;
    const std::string at = "exercise.yard_block";
    sim::YardBlock block;
    block.first_slot_m = f.vector3(f.required(y, "first_slot_m", at), at + ".first_slot_m", kSite_m);
    block.bays = f.integer(y, "bays", at, 1, 100);
    block.rows = f.integer(y, "rows", at, 1, 20);
    block.tiers = f.integer(y, "tiers", at, 1, 10);
    block.bay_pitch_m = f.number(y, "bay_pitch_m", at, 6.1, 10.0);
    block.row_pitch_m = f.number(y, "row_pitch_m", at, -6.0, 6.0);
    if (std::abs(block.row_pitch_m) < 2.5)
      f.fail(y["row_pitch_m"], at + ".row_pitch_m", "rows lie 2.5-6 m apart");
    block.tier_height_m = f.number(y, "tier_height_m", at, 2.5, 3.0);
    s.yard_block = block;
  }

  if (f.optional(x, "blocks", "exercise")) {
    const YAML::Node blocks = f.sequence(x, "blocks", "exercise", kMaxBlocks);
    for (std::size_t n = 0; n < blocks.size(); ++n) {
      const std::string at = item("exercise.blocks", n);
      const core::Vec3 half =
          f.vector3(f.required(blocks[n], "half_extents_m", at), at + ".half_extents_m", kSite_m);
      if (!(half.x > 0 && half.y > 0 && half.z > 0))
        f.fail(blocks[n]["half_extents_m"], at + ".half_extents_m", "must be positive");
      s.blocks.push_back(
          {half, f.vector3(f.required(blocks[n], "position_m", at), at + ".position_m", kSite_m)});
    }
  }
}

// the containers, by id: on the quay, on a chassis, in the yard block or stowed on the vessel; then the hatch
// covers
std::map<std::string, std::size_t> read_containers(const YamlFile& f, const YAML::Node& x,
                                                   sim::ScenarioSettings& s,
                                                   const std::optional<sim::VesselGeometry>& vessel,
                                                   const std::vector<sim::ContainerPlacement>& hatch_covers,
                                                   bool handles_containers) {
  const YAML::Node containers = handles_containers ? f.sequence(x, "containers", "exercise", kMaxContainers)
                                                   : YAML::Node(YAML::NodeType::Sequence);
  std::map<std::string, std::size_t> container_index;  // by id
  struct Stowed {                                      // a box given by its slot on the vessel
    std::size_t index;
    sim::SlotAddress slot;
    core::Vec3 lowest_centre;  // vessel frame: where it would stand in its stack's lowest tier
  };
  std::vector<Stowed> stowed;
  auto two_digits = [](int tier) { return (tier < 10 ? "0" : "") + std::to_string(tier); };
  for (std::size_t n = 0; n < containers.size(); ++n) {
    const YAML::Node c = containers[n];
    const std::string at = item("exercise.containers", n);
    sim::ContainerPlacement p;
    p.id = f.text(c, "id", at);
    if (!container_index.emplace(p.id, n).second)
      f.fail(c["id"], at + ".id", "duplicate container '" + p.id + "'");
    const std::string type = f.text(c, "type", at);
    const auto t = iso_types().find(type);
    if (t == iso_types().end())
      f.fail(c["type"], at + ".type", "unknown container type '" + type + "' (20ft, 40ft, 40ftHC, 45ftHC)");
    p.half_extents_m = t->second.size_m * 0.5;
    // the gross mass, or the cargo on the tare (the type's typical tare unless given); up to 40 t, above the
    // ISO 30 480 kg maximum, so that an exercise can hide an overweight box
    const bool gross_given = f.optional(c, "gross_mass_kg", at).has_value();
    if (gross_given == f.optional(c, "cargo_mass_kg", at).has_value())
      f.fail(c, at, "give either gross_mass_kg or cargo_mass_kg (with an optional tare_kg), not both");
    if (gross_given) {
      p.gross_mass_kg = f.number(c, "gross_mass_kg", at, 1000.0, 40000.0);
    } else {
      const double tare = f.number_or(c, "tare_kg", at, t->second.tare_kg, 1000.0, 10000.0);
      p.gross_mass_kg = tare + f.number(c, "cargo_mass_kg", at, 0.0, 40000.0 - tare);
    }
    const bool twenty = type == "20ft";
    p.pocket_half_length_m = (twenty ? kCastings20_m[0] : kCastings40_m[0]) / 2;
    p.pocket_half_width_m = (twenty ? kCastings20_m[1] : kCastings40_m[1]) / 2;
    if (type == "45ftHC") p.end_pocket_half_length_m = kCastings45_m / 2;
    if (const auto com = f.optional(c, "center_of_mass_m", at)) {
      p.center_of_mass_m = f.vector3(*com, at + ".center_of_mass_m");
      const core::Vec3& h = p.half_extents_m;
      if (std::abs(p.center_of_mass_m.x) > h.x || std::abs(p.center_of_mass_m.y) > h.y ||
          std::abs(p.center_of_mass_m.z) > h.z)
        f.fail(c["center_of_mass_m"], at + ".center_of_mass_m", "lies outside the container");
    }
    const std::optional<YAML::Node> slot_node = f.optional(c, "slot", at);
    const std::optional<YAML::Node> block_node = f.optional(c, "block_slot", at);
    if (slot_node.has_value() + block_node.has_value() + f.optional(c, "position_m", at).has_value() != 1)
      f.fail(
          c, at,
          "give one of slot: [bay, row, tier] on the vessel, block_slot: [bay, row, tier] in the yard block "
          "or position_m");
    if (block_node) {
      const core::Vec3 centre = block_slot_centre(f, *block_node, at + ".block_slot", s.yard_block);
      if (std::abs(2.0 * p.half_extents_m.z - s.yard_block->tier_height_m) > 1e-3)
        f.fail(c["type"], at + ".type",
               "the yard block stacks boxes " + std::to_string(s.yard_block->tier_height_m).substr(0, 5) +
                   " m high (exercise.yard_block.tier_height_m)");
      if (centre.z > s.yard_block->first_slot_m.z + s.yard_block->tier_height_m) {
        bool stands = false;  // on a box in the tier below whose length spans its centre
        for (const sim::ContainerPlacement& other : s.containers)
          stands |= std::abs(other.pose.position.z + s.yard_block->tier_height_m - centre.z) < 0.05 &&
                    std::abs(other.pose.position.x - centre.x) < 0.05 &&
                    std::abs(other.pose.position.y - centre.y) < other.half_extents_m.x;
        if (!stands)
          f.fail(*block_node, at + ".block_slot",
                 "nothing stands under it in the tier below (list boxes bottom up)");
      }
      p.pose = {core::Mat3::rotation({0, 0, 1}, 0.5 * std::numbers::pi), centre};
    } else if (slot_node) {
      const YAML::Node& slot = *slot_node;
      if (!vessel) f.fail(slot, at + ".slot", "a slot needs the exercise's vessel");
      const sim::SlotAddress address = read_slot_address(f, slot, at + ".slot");
      std::string why;
      const std::optional<core::Vec3> centre = vessel->slot_centre(address, 2.0 * p.half_extents_m.z, why);
      if (!centre) f.fail(slot, at + ".slot", why);
      if (address.tier < 80 && type != "40ft" && type != "40ftHC")
        f.fail(c["type"], at + ".type", "the holds have 40 ft cells: " + type + " goes on deck");
      p.pose = vessel->stowed_pose_at(0.0, *centre);
      p.on_vessel = true;
      p.in_cell = address.tier < 80;
      const sim::SlotAddress lowest{address.bay, address.row, p.in_cell ? 2 : 82};
      stowed.push_back({n, address, *vessel->slot_centre(lowest, 2.0 * p.half_extents_m.z, why)});
    } else {
      // on the quay or a chassis: along the quay unless turned
      const double yaw = core::deg_to_rad(f.number_or(c, "yaw_deg", at, 90.0, -360.0, 360.0));
      p.pose = {core::Mat3::rotation({0, 0, 1}, yaw),
                f.vector3(c["position_m"], at + ".position_m", kSite_m)};
    }
    s.containers.push_back(p);
  }
  // each stowed box stands on the one below it in its stack (high cubes are 30 cm taller than a tier): no
  // gaps, no two in a slot, and a hold stack must fit under the hatch covers
  std::stable_sort(stowed.begin(), stowed.end(), [](const Stowed& a, const Stowed& b) {
    return std::tie(a.slot.bay, a.slot.row, a.slot.tier) < std::tie(b.slot.bay, b.slot.row, b.slot.tier);
  });
  double stack_top = 0.0;  // vessel frame
  for (std::size_t k = 0; k < stowed.size(); ++k) {
    const Stowed& box = stowed[k];
    sim::ContainerPlacement& p = s.containers[box.index];
    const std::string at = item("exercise.containers", box.index) + ".slot";
    const bool same_stack = k > 0 && stowed[k - 1].slot.bay == box.slot.bay &&
                            stowed[k - 1].slot.row == box.slot.row &&
                            (stowed[k - 1].slot.tier < 80) == (box.slot.tier < 80);
    const int lowest_tier = box.slot.tier < 80 ? 2 : 82;
    const int expected_tier = same_stack ? stowed[k - 1].slot.tier + 2 : lowest_tier;
    if (box.slot.tier < expected_tier)
      f.fail(containers[box.index]["slot"], at, "two containers in one slot");
    if (box.slot.tier > expected_tier)
      f.fail(containers[box.index]["slot"], at,
             "nothing stowed under it in tier " + two_digits(box.slot.tier - 2) +
                 " (stacks start at tier 02 in the hold, 82 on deck)");
    const double height = 2.0 * p.half_extents_m.z;
    const double bottom = same_stack ? stack_top : box.lowest_centre.z - height / 2.0;
    stack_top = bottom + height;
    const core::Vec3 centre{box.lowest_centre.x, box.lowest_centre.y, bottom + height / 2.0};
    if (p.in_cell && bottom + height > vessel->coaming_top_m())
      f.fail(containers[box.index]["slot"], at,
             "the hold stack would stand " +
                 std::to_string(std::lround((bottom + height - vessel->coaming_top_m()) * 1000)) +
                 " mm into the hatch covers");
    p.pose = vessel->stowed_pose_at(0.0, centre);
  }
  for (const sim::ContainerPlacement& cover : hatch_covers) {
    if (!container_index.emplace(cover.id, s.containers.size()).second)
      f.fail(containers, "exercise.containers", "'" + cover.id + "' is a hatch cover's id");
    s.containers.push_back(cover);
  }
  return container_index;
}

// general cargo pieces for the hook: boxes of a given size and mass standing on the quay; how many
std::size_t read_cargo(const YamlFile& f, const YAML::Node& x, sim::ScenarioSettings& s,
                       std::map<std::string, std::size_t>& container_index, bool on_hook) {
  const YAML::Node cargo =
      on_hook ? f.sequence(x, "cargo", "exercise", kMaxContainers) : YAML::Node(YAML::NodeType::Sequence);
  for (std::size_t n = 0; n < cargo.size(); ++n) {
    const YAML::Node c = cargo[n];
    const std::string at = item("exercise.cargo", n);
    sim::ContainerPlacement p;
    p.kind = sim::ContainerPlacement::Kind::kGeneralCargo;
    p.id = f.text(c, "id", at);
    if (!container_index.emplace(p.id, s.containers.size()).second)
      f.fail(c["id"], at + ".id", "duplicate cargo '" + p.id + "'");
    p.half_extents_m = f.vector3(f.required(c, "size_m", at), at + ".size_m", 50.0) * 0.5;
    if (!(p.half_extents_m.x >= 0.25 && p.half_extents_m.y >= 0.25 && p.half_extents_m.z >= 0.25))
      f.fail(c["size_m"], at + ".size_m", "must be at least 0.5 m each");
    p.gross_mass_kg = f.number(c, "mass_kg", at, 100.0, 500000.0);
    const double yaw = core::deg_to_rad(f.number_or(c, "yaw_deg", at, 0.0, -360.0, 360.0));
    p.pose = {core::Mat3::rotation({0, 0, 1}, yaw),
              f.vector3(f.required(c, "position_m", at), at + ".position_m", kSite_m)};
    s.containers.push_back(p);
  }
  return cargo.size();
}

// the moves: what each takes (a container, a cargo piece, the trailer) and where to
void read_moves(const YamlFile& f, const YAML::Node& x, sim::ExerciseSettings& e,
                std::map<std::string, std::size_t>& container_index, bool handles_containers, bool on_hook,
                const std::optional<sim::BroughtTrailer>& trailer, std::size_t cargo_count) {
  sim::ScenarioSettings& s = e.scenario;
  const bool tows = trailer.has_value();
  const YAML::Node moves = handles_containers || on_hook || tows
                               ? f.sequence(x, "moves", "exercise", kMaxMoves)
                               : YAML::Node(YAML::NodeType::Sequence);
  const char* moved_key = on_hook ? "cargo" : tows ? "trailer" : "container";  // what a move names
  if (tows) container_index[trailer->id] = s.containers.size();
  std::map<std::string, std::size_t> moved;  // container or cargo id -> the move that takes it
  for (std::size_t n = 0; n < moves.size(); ++n) {
    const std::string at = item("exercise.moves", n);
    sim::MoveGoal g;
    g.container_id = f.text(moves[n], moved_key, at);
    const auto known = container_index.find(g.container_id);
    if (known == container_index.end())
      f.fail(moves[n][moved_key], at + "." + moved_key,
             std::string("no ") + moved_key + " '" + g.container_id + "' in this exercise");
    if (const auto [first, fresh] = moved.emplace(g.container_id, n); !fresh)
      f.fail(moves[n][moved_key], at + "." + moved_key,
             "'" + g.container_id + "' is already moved by exercise.moves[" + std::to_string(first->second) +
                 "]");
    if (f.optional(moves[n], "to", at)) {
      if (f.text(moves[n], "to", at) != "truck") f.fail(moves[n]["to"], at + ".to", "only 'truck' is known");
      if (s.trucks.trucks == 0) f.fail(moves[n]["to"], at + ".to", "the exercise has no trucks");
      const double height = 2.0 * s.containers[known->second].half_extents_m.z;
      g.target_m = {s.trucks.lane_x_m, s.trucks.stop_y_m, s.trucks.chassis_top_m + height / 2};
      g.to_truck = true;
    } else if (const auto slot = f.optional(moves[n], "block_slot", at)) {
      g.target_m = block_slot_centre(f, *slot, at + ".block_slot", s.yard_block);
    } else {
      g.target_m = f.vector3(f.required(moves[n], "target_m", at), at + ".target_m", kSite_m);
    }
    g.tolerance_m = f.number_or(moves[n], "tolerance_m", at, g.tolerance_m, 0.0, 5.0, true);
    g.on_wheels = tows;  // a trailer stands where its wheels carry it: its height is not checked
    if (f.optional(moves[n], "heading_deg", at)) {
      // placed square: a box either way round, a trailer facing the way it should
      g.heading_rad = core::deg_to_rad(f.number(moves[n], "heading_deg", at, -360.0, 360.0));
      g.heading_tolerance_rad =
          core::deg_to_rad(f.number_or(moves[n], "heading_tolerance_deg", at, 3.0, 0.0, 90.0, true));
    } else if (f.optional(moves[n], "heading_tolerance_deg", at)) {
      f.fail(moves[n]["heading_tolerance_deg"], at + ".heading_tolerance_deg", "needs a heading_deg");
    }
    if (tows && g.heading_rad) {
      // its bay painted where it is to stand: the trailer's footprint and the tolerance around it
      const core::Vec3& half = trailer->half_extents_m;
      s.markings.push_back({"bay " + g.container_id, g.target_m, *g.heading_rad, half.x + g.tolerance_m,
                            half.y + g.tolerance_m});
    } else if (g.heading_rad && !g.to_truck && known->second < s.containers.size()) {
      // a box set down on the ground (not on a stack or a truck): its place painted, as a terminal marks its
      // transfer and buffer slots, the box's footprint and the tolerance around it
      const core::Vec3& half = s.containers[known->second].half_extents_m;
      if (std::abs(g.target_m.z - half.z) < 0.05)
        s.markings.push_back({"slot " + g.container_id, g.target_m, *g.heading_rad, half.x + g.tolerance_m,
                              half.y + g.tolerance_m});
    }
    e.moves.push_back(g);
  }
  if ((handles_containers || cargo_count > 0) && e.moves.empty())
    f.fail(moves, "exercise.moves", "an exercise needs at least one move");
}

// bulk material and its goal: a delivery into a hopper or a pile trimmed
void read_bulk(const YamlFile& f, const YAML::Node& x, const std::string& folder,
               const std::optional<sim::VesselGeometry>& vessel, sim::ExerciseSettings& e) {
  sim::ScenarioSettings& s = e.scenario;
  if (const auto b_node = f.optional_map(x, "bulk", "exercise")) {
    // bulk material: the materials file (relative to the exercise), the material, grids and heaps
    const std::string file = f.text(*b_node, "materials", "exercise.bulk");
    const std::string path = (std::filesystem::path(folder) / file).lexically_normal().string();
    if (!std::filesystem::is_regular_file(path))
      f.fail((*b_node)["materials"], "exercise.bulk.materials", "no such file: " + path);
    s.bulk = read_bulk_scene(f, *b_node, "exercise.bulk", load_materials(path), vessel ? &*vessel : nullptr);
  }

  if (const auto d_node = f.optional_map(x, "deliver", "exercise")) {
    // a bulk goal: tonnes dropped into one of the bulk section's grids (a hopper)
    const std::string at = "exercise.deliver";
    if (!s.bulk) f.fail(*d_node, at, "a delivery goal needs the exercise's bulk section");
    sim::BulkGoal goal;
    goal.grid = f.text(*d_node, "into", at);
    const auto& grids = s.bulk->grids;
    const auto found =
        std::find_if(grids.begin(), grids.end(), [&](const auto& g) { return g.name == goal.grid; });
    if (found == grids.end())
      f.fail((*d_node)["into"], at + ".into", "no bulk grid named '" + goal.grid + "'");
    goal.grid_index = static_cast<int>(found - grids.begin());
    goal.tonnes = f.number(*d_node, "tonnes", at, 0.0, 1e6, true);
    e.deliver = goal;
  }
  if (const auto t_node = f.optional_map(x, "trim", "exercise")) {
    // a bulk goal: a pile's top brought down to a height
    const std::string at = "exercise.trim";
    if (!s.bulk) f.fail(*t_node, at, "a trim goal needs the exercise's bulk section");
    if (e.deliver) f.fail(*t_node, at, "an exercise has a delivery goal or a trim goal, not both");
    sim::TrimGoal goal;
    goal.grid = f.text(*t_node, "grid", at);
    const auto& grids = s.bulk->grids;
    const auto found =
        std::find_if(grids.begin(), grids.end(), [&](const auto& g) { return g.name == goal.grid; });
    if (found == grids.end() || found->on_vessel || found->outflow_m3_per_s > 0.0)
      f.fail((*t_node)["grid"], at + ".grid", "no pile on the quay named '" + goal.grid + "'");
    goal.grid_index = static_cast<int>(found - grids.begin());
    goal.top_m = f.number(*t_node, "top_m", at, -100.0, 100.0);
    e.trim = goal;
  }
}

void read_weather(const YamlFile& f, const YAML::Node& x, sim::ScenarioSettings& s) {
  if (const auto w_node = f.optional_map(x, "weather", "exercise")) {
    const YAML::Node& w = *w_node;
    const std::string at = "exercise.weather";
    sim::WeatherSettings& ws = s.weather;
    ws.wind_mean_mps = f.number_or(w, "wind_mean_mps", at, ws.wind_mean_mps, 0.0, sim::kMaxMeanWind_mps);
    ws.wind_from_rad = core::deg_to_rad(f.number_or(w, "wind_from_deg", at, 0.0, 0.0, 360.0));
    ws.turbulence_intensity = f.number_or(w, "turbulence_intensity", at, ws.turbulence_intensity, 0.0, 1.0);
    ws.visibility_m = f.number_or(w, "visibility_m", at, ws.visibility_m, 1.0, 1e5);
    ws.rain_mm_per_h = f.number_or(w, "rain_mm_per_h", at, ws.rain_mm_per_h, 0.0, 500.0);
    ws.cloud_oktas = f.number_or(w, "cloud_oktas", at, ws.cloud_oktas, 0.0, sim::kOvercast_oktas);
    ws.time_of_day_h = f.number_or(w, "time_of_day_h", at, ws.time_of_day_h, 0.0, 24.0, false, true);
    ws.day_of_year = f.number_or(w, "day_of_year", at, ws.day_of_year, 1.0, 366.0);
    ws.latitude_deg = f.number_or(w, "latitude_deg", at, ws.latitude_deg, -80.0, 80.0);
  }
}

// scripted events: gusts and the machine's faults, at a time or after the first lift
void read_events(const YamlFile& f, const YAML::Node& x, sim::ScenarioSettings& s,
                 const std::string& machine_kind, const sim::MachineType& machine_type) {
  if (f.optional(x, "events", "exercise")) {
    const YAML::Node events = f.sequence(x, "events", "exercise", kMaxEvents);
    for (std::size_t n = 0; n < events.size(); ++n) {
      const YAML::Node ev = events[n];
      const std::string at = item("exercise.events", n);
      sim::ScriptedEvent event;
      // at an exercise time, or timed from the machine's first lift
      const bool after_lift = f.optional(ev, "after_lift_s", at).has_value();
      if (after_lift && f.optional(ev, "at_s", at))
        f.fail(ev["after_lift_s"], at + ".after_lift_s", "an event comes at_s or after_lift_s, not both");
      const char* time_key = after_lift ? "after_lift_s" : "at_s";
      event.at_s = f.number(ev, time_key, at, 0.0, 86400.0);
      const std::string kind = f.text(ev, "kind", at);
      if (kind == "gust") {
        event.kind = sim::ScriptedEvent::Kind::kGust;
        event.gust.amplitude_mps = f.number(ev, "amplitude_mps", at, 0.0, sim::kMaxGust_mps, true);
        event.gust.duration_s = f.number_or(ev, "duration_s", at, 3.0, 0.0, 600.0, true);
      } else if (const FaultEvent* fault = find_fault_event(kind)) {
        if (!machine_type.has_fault(fault->fault))
          f.fail(ev["kind"], at + ".kind",
                 "the " + machine_kind + " has no " + fault->part +
                     " to fail (its events: " + core::comma_separated(event_kinds(machine_type)) + ")");
        event.kind = fault->event;
        if (fault->fault == sim::MachineFault::kLandedSensor)
          event.corner = f.integer(ev, "corner", at, 0, 3);
      } else {
        const auto any_machine = [](sim::MachineFault) { return true; };
        f.fail(ev["kind"], at + ".kind",
               "'" + kind + "' is not an event: " + core::comma_separated(scriptable_events(any_machine)));
      }
      std::vector<sim::ScriptedEvent>& queue = after_lift ? s.lift_events : s.events;
      if (!queue.empty() && event.at_s < queue.back().at_s)
        f.fail(ev[time_key], at + "." + time_key,
               after_lift ? "events after the first lift must be in time order"
                          : "events must be in time order");
      queue.push_back(event);
    }
  }
}

// a vehicle's course: the ro-ro ramp, a team's load stop, speed zones and the route with its load
void read_course(const YamlFile& f, const YAML::Node& x, sim::ExerciseSettings& e, bool vehicle,
                 const std::string& machine_kind) {
  sim::ScenarioSettings& s = e.scenario;
  if (const auto r = f.optional_map(x, "ramp", "exercise")) {
    // a ro-ro vessel's stern ramp and vehicle deck: the ground a vehicle drives on
    const std::string at = "exercise.ramp";
    if (!vehicle)
      f.fail(x["ramp"], at, "only a vehicle drives up a ramp (the " + machine_kind + " is a crane)");
    sim::RampSettings ramp;
    ramp.toe_m = f.vector3(f.required(*r, "toe_m", at), at + ".toe_m", kSite_m);
    ramp.heading_rad = core::deg_to_rad(f.number(*r, "heading_deg", at, -360.0, 360.0));
    ramp.length_m = f.number(*r, "length_m", at, 3.0, 60.0);
    ramp.width_m = f.number(*r, "width_m", at, 3.0, 40.0);
    ramp.deck_length_m = f.number(*r, "deck_length_m", at, 5.0, 300.0);
    ramp.deck_height_m = f.number(*r, "deck_height_m", at, -5.0, 10.0);
    const auto swing = [&](const char* key, sim::Harmonic& h, double most_m) {
      const auto node = f.optional_map(*r, key, at);
      if (!node) return;
      const std::string p = at + "." + key;
      h.amplitude = f.number(*node, "amplitude_m", p, 0.0, most_m);
      h.period_s = f.number(*node, "period_s", p, 1.0, 1e6);
      h.phase_rad = core::deg_to_rad(f.number_or(*node, "phase_deg", p, 0.0, -360.0, 360.0));
    };
    swing("tide", ramp.tide, 6.0);
    swing("heave", ramp.heave, 2.0);
    ramp.grip = f.number_or(*r, "grip", at, 1.0, 0.05, 1.5);
    const double steepest = std::abs(ramp.deck_height_m) + ramp.tide.amplitude + ramp.heave.amplitude;
    if (steepest / ramp.length_m > 0.25)
      f.fail(x["ramp"], at, "is steeper than 1:4 at the tide's and swell's extremes");
    s.ramp = ramp;
  }

  if (const auto stop = f.optional_map(x, "load_stop", "exercise")) {
    // a team's tractor collects a box under the crane first: {trailer_at_m: [x, y], heading_deg}
    const std::string at = "exercise.load_stop";
    if (const auto trailer = s.machine.trailer(); !trailer || !trailer->receives_box)
      f.fail(x["load_stop"], at,
             "only a tractor whose trailer receives a box (vehicle.trailer.receives) stops for one");
    const YAML::Node c = f.required(*stop, "trailer_at_m", at);
    if (!c.IsSequence() || c.size() != 2) f.fail(c, at + ".trailer_at_m", "is [x, y] in metres");
    sim::LoadStop load_stop;
    load_stop.trailer_at_m = {f.number_at(c[0], at + ".trailer_at_m[0]"),
                              f.number_at(c[1], at + ".trailer_at_m[1]"), 0.0};
    if (!(std::abs(load_stop.trailer_at_m.x) <= kSite_m && std::abs(load_stop.trailer_at_m.y) <= kSite_m))
      f.fail(c, at + ".trailer_at_m", "lies off the site");
    load_stop.heading_rad = core::deg_to_rad(f.number(*stop, "heading_deg", at, -360.0, 360.0));
    e.load_stop = load_stop;
  }

  if (f.optional(x, "speed_zones", "exercise")) {
    // areas with a speed limit for a vehicle: [{name, min_m: [x, y], max_m: [x, y], limit_kmh}]
    const YAML::Node zones = f.sequence(x, "speed_zones", "exercise", 64);
    for (std::size_t n = 0; n < zones.size(); ++n) {
      const std::string at = item("exercise.speed_zones", n);
      sim::SpeedZone z;
      z.name = f.text(zones[n], "name", at);
      const auto corner = [&](const char* key, double& x_m, double& y_m) {
        const YAML::Node c = f.required(zones[n], key, at);
        if (!c.IsSequence() || c.size() != 2) f.fail(c, at + "." + key, "is [x, y] in metres");
        x_m = f.number_at(c[0], at + "." + key + "[0]");
        y_m = f.number_at(c[1], at + "." + key + "[1]");
        if (!(std::abs(x_m) <= kSite_m && std::abs(y_m) <= kSite_m))
          f.fail(c, at + "." + key, "lies off the site");
      };
      corner("min_m", z.min_x_m, z.min_y_m);
      corner("max_m", z.max_x_m, z.max_y_m);
      if (!(z.max_x_m > z.min_x_m && z.max_y_m > z.min_y_m))
        f.fail(zones[n]["max_m"], at + ".max_m", "must lie beyond min_m in x and y");
      z.limit_kmh = f.number(zones[n], "limit_kmh", at, 1.0, 100.0);
      e.speed_zones.push_back(z);
    }
    if (!vehicle && zones.size() > 0)
      f.fail(zones, "exercise.speed_zones",
             "only a vehicle's speed is limited (the " + machine_kind + " is a crane)");
  }

  if (f.optional(x, "route_m", "exercise")) {
    // the way a vehicle takes with its load: [[x, y], ...]
    const YAML::Node route = f.sequence(x, "route_m", "exercise", 64);
    for (std::size_t n = 0; n < route.size(); ++n) {
      const std::string at = item("exercise.route_m", n);
      if (!route[n].IsSequence() || route[n].size() != 2) f.fail(route[n], at, "is [x, y] in metres");
      const core::Vec3 p{f.number_at(route[n][0], at + "[0]"), f.number_at(route[n][1], at + "[1]"), 0.0};
      if (!(std::abs(p.x) <= kSite_m && std::abs(p.y) <= kSite_m)) f.fail(route[n], at, "lies off the site");
      if (n > 0 && core::length(p - e.route_m.back()) < 1.0)
        f.fail(route[n], at, "lies within a metre of the point before it");
      e.route_m.push_back(p);
    }
    if (!vehicle && route.size() > 0)
      f.fail(route, "exercise.route_m",
             "only a vehicle drives a route (the " + machine_kind + " is a crane)");
  }
}

void read_radio(const YamlFile& f, const YAML::Node& x, sim::ExerciseSettings& e) {
  if (const auto radio = f.optional_map(x, "radio", "exercise")) {
    // the signaller's calls on the cab's radio: {language, calls: [{at_s, say}]}
    e.radio.language = f.text(*radio, "language", "exercise.radio");
    if (e.radio.language.size() > 16 ||
        e.radio.language.find_first_not_of("abcdefghijklmnopqrstuvwxyz-") != std::string::npos)
      f.fail((*radio)["language"], "exercise.radio.language", "an espeak-ng voice: en, de, es, fr, nl, ...");
    const YAML::Node calls = f.sequence(*radio, "calls", "exercise.radio", 200);
    for (std::size_t n = 0; n < calls.size(); ++n) {
      const std::string at = item("exercise.radio.calls", n);
      scene::RadioCall call;
      call.at_s = f.number(calls[n], "at_s", at, 0.0, 86400.0);
      call.text = f.text(calls[n], "say", at);
      if (call.text.size() > 200) f.fail(calls[n]["say"], at + ".say", "is longer than 200 bytes");
      if (!e.radio.calls.empty() && call.at_s < e.radio.calls.back().at_s)
        f.fail(calls[n]["at_s"], at + ".at_s", "comes before the call before it");
      e.radio.calls.push_back(call);
    }
  }
}

void read_rules(const YamlFile& f, const YAML::Node& x, sim::ExerciseSettings& e) {
  if (const auto r_node = f.optional_map(x, "rules", "exercise")) {
    const YAML::Node& r = *r_node;
    sim::EvaluationRules& rules = e.rules;
    for (const RuleField& field : rule_thresholds())
      rules.*field.value = f.number_or(r, field.key, "exercise.rules", rules.*field.value, field.min,
                                       field.max, field.above_min);
    if (const auto d_node = f.optional(r, "deductions", "exercise.rules")) {
      const YAML::Node& d = *d_node;
      const std::string at = "exercise.rules.deductions";
      if (!d.IsMap()) f.fail(d, at, "must be a map of metric: points");
      for (const auto& entry : d) {
        const std::string key = entry.first.as<std::string>();
        const auto& points = rule_deductions();
        const auto known =
            std::find_if(points.begin(), points.end(), [&](const RuleField& p) { return key == p.key; });
        if (known == points.end()) {
          std::string names;
          for (const RuleField& p : points)
            names += (names.empty() ? "" : ", ") + std::string(p.key);
          f.fail(entry.first, at + "." + key, "unknown deduction (" + names + ")");
        }
        rules.*known->value = f.number(d, key, at, known->min, known->max, known->above_min);
      }
    }
  }
}

sim::ExerciseSettings read_exercise(const YamlFile& f, const std::string& folder) {
  sim::ExerciseSettings e;
  const YAML::Node x = f.required(f.root(), "exercise", "");
  e.name = f.text(x, "name", "exercise");
  e.about = read_about(f, x);
  sim::ScenarioSettings& s = e.scenario;
  s.name = e.name;
  const std::string machine = f.text(x, "machine", "exercise");
  const std::string machine_path = (std::filesystem::path(folder) / machine).lexically_normal().string();
  if (!std::filesystem::is_regular_file(machine_path))
    f.fail(x["machine"], "exercise.machine", "no such file: " + machine_path);
  const std::string machine_kind = machine_file_kind(machine_path);
  const MachineFileType& files = *find_machine_file_type(machine_kind);  // machine_file_kind() checked it
  const std::string pose_at = std::string("exercise.") + files.start_section;
  const StartBlock start{f, f.required_map(x, files.start_section, "exercise"), pose_at, folder};
  s.machine = files.read(machine_path, start);
  e.machine_file = machine_path;
  const bool vehicle = std::string_view(files.start_section) == "vehicle";  // it drives (ramps, routes)
  // container exercises (the STS), general cargo on a hook, bulk on a grab
  const sim::MachineType& machine_type = s.machine.type();
  const bool handles_containers = machine_type.handles == sim::Handles::kContainers;
  const bool on_hook = s.machine.slings_cargo();
  const std::optional<sim::BroughtTrailer> trailer = s.machine.trailer();
  const bool tows = trailer.has_value();
  const bool grabs_bulk = machine_type.handles == sim::Handles::kBulkOrCargo && !on_hook;
  const std::string handles = handles_containers ? "containers with its spreader"
                              : on_hook          ? "general cargo on its hook (exercise.cargo)"
                              : grabs_bulk       ? "bulk with its grab (crane.tool: hook for general cargo)"
                              : tows             ? "its trailer (exercise.vehicle.trailer)"
                                                 : "a trailer (exercise.vehicle.trailer)";
  for (const char* key : {"containers", "trucks", "cargo", "moves"}) {
    const bool fits = handles_containers ? std::string(key) != "cargo"
                      : on_hook          ? std::string(key) == "cargo" || std::string(key) == "moves"
                                         : tows && std::string(key) == "moves";
    if (!fits && f.optional(x, key, "exercise"))
      f.fail(x[key], std::string("exercise.") + key, "the " + machine_kind + " handles " + handles);
  }

  std::vector<sim::ContainerPlacement> hatch_covers;
  s.quay_edge_x_m = f.number_or(x, "quay_edge_x_m", "exercise", s.quay_edge_x_m, -kSite_m, kSite_m);
  const std::optional<sim::VesselGeometry> vessel = read_vessel(f, x, folder, s, hatch_covers);
  read_site(f, x, s);
  std::map<std::string, std::size_t> container_index =
      read_containers(f, x, s, vessel, hatch_covers, handles_containers);
  const std::size_t cargo_count = read_cargo(f, x, s, container_index, on_hook);
  read_moves(f, x, e, container_index, handles_containers, on_hook, trailer, cargo_count);
  read_bulk(f, x, folder, vessel, e);
  read_weather(f, x, s);
  read_events(f, x, s, machine_kind, machine_type);
  read_course(f, x, e, vehicle, machine_kind);
  read_radio(f, x, e);
  read_rules(f, x, e);
  return e;
}

}  // namespace

StartPoseForm start_pose_form(const sim::MachineSetup& machine) {
  const MachineFileType* files = find_machine_file_type(machine.kind());
  if (!files) throw std::logic_error(std::string("no reader of machine files for the ") + machine.kind());
  return files->start_pose_form(machine);
}

const std::vector<RuleField>& rule_thresholds() {
  using R = sim::EvaluationRules;
  static const std::vector<RuleField> fields = {
      {"time_limit_s", &R::time_limit_s, 0.0, 86400.0, true},
      {"pass_score", &R::pass_score, 0.0, 100.0, false},
      {"hard_landing_mps", &R::hard_landing_mps, 0.0, 10.0, true},
      {"sway_limit_m", &R::sway_limit_m, 0.0, 10.0, true},
      {"collision_speed_mps", &R::collision_speed_mps, 0.0, 10.0, true},
      {"body_contact_impulse_ns", &R::body_contact_impulse_ns, 0.0, 1e7, true},
      {"horn_warning_s", &R::horn_warning_s, 0.0, 600.0, true},
      {"signal_reaction_s", &R::signal_reaction_s, 0.0, 60.0, true},
      {"load_drop_mps", &R::load_drop_mps, 0.0, 100.0, true},
      {"overtime_s", &R::overtime_s, 0.0, 3600.0, false},
      {"poor_bite_fill", &R::poor_bite_fill, 0.0, 1.0, false},
      {"harsh_jerk_mps3", &R::harsh_jerk_mps3, 0.0, 1000.0, true}};
  return fields;
}

const std::vector<RuleField>& rule_deductions() {
  using R = sim::EvaluationRules;
  static const std::vector<RuleField> fields = {
      {"collision", &R::points_collision, 0.0, 100.0, false},
      {"hard_landing", &R::points_hard_landing, 0.0, 100.0, false},
      {"landing_while_swaying", &R::points_sway, 0.0, 100.0, false},
      {"twistlock_misuse", &R::points_twistlock_misuse, 0.0, 100.0, false},
      {"rope_overload", &R::points_overload, 0.0, 100.0, false},
      {"limit_switch_hit", &R::points_limit_hit, 0.0, 100.0, false},
      {"emergency_stop", &R::points_emergency_stop, 0.0, 100.0, false},
      {"gantry_travel_without_horn", &R::points_unwarned_travel, 0.0, 100.0, false},
      {"move_not_completed", &R::points_per_move_missing, 0.0, 100.0, false},
      {"minute_over_time_limit", &R::points_per_minute_over, 0.0, 100.0, false},
      {"tonne_spilled", &R::points_per_spilled_t, 0.0, 100.0, false},
      {"tonne_short", &R::points_per_missing_t, 0.0, 100.0, false},
      {"poor_bite", &R::points_poor_bite, 0.0, 100.0, false},
      {"limiter_trip", &R::points_limiter_trip, 0.0, 100.0, false},
      {"pad_lift_off", &R::points_pad_lift_off, 0.0, 100.0, false},
      {"harsh_move", &R::points_harsh_move, 0.0, 100.0, false},
      {"jackknife", &R::points_jackknife, 0.0, 100.0, false},
      {"tip_over", &R::points_tip_over, 0.0, 100.0, false},
      {"speeding", &R::points_overspeed, 0.0, 100.0, false},
      {"decimetre_above_trim", &R::points_per_trim_dm, 0.0, 100.0, false},
      {"load_drop", &R::points_load_drop, 0.0, 100.0, false},
      {"lift_under_fault", &R::points_lift_under_fault, 0.0, 100.0, false},
      {"late_stop_signal", &R::points_late_stop_signal, 0.0, 100.0, false}};
  return fields;
}

std::vector<std::string> exercise_names(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
    if (entry.path().extension() == ".yaml" && entry.path().filename().string()[0] != '.')
      names.push_back(entry.path().stem().string());  // not hidden ones (the designer's checks)
  std::sort(names.begin(), names.end());
  return names;
}

ExerciseCard read_exercise_card(const std::string& file) {
  ExerciseCard card;
  card.name = std::filesystem::path(file).stem().string();
  try {
    const YamlFile f = YamlFile::load(file);
    const YAML::Node x = f.required(f.root(), "exercise", "");
    card.name = f.text(x, "name", "exercise");
    card.about = read_about(f, x);
    const std::string machine = f.text(x, "machine", "exercise");
    card.machine =
        machine_file_kind((std::filesystem::path(file).parent_path() / machine).lexically_normal().string());
  } catch (const std::exception& e) {
    card.error = e.what();
  }
  return card;
}

std::vector<ExerciseCard> exercise_cards(const std::vector<std::string>& folders) {
  std::map<std::string, ExerciseCard> by_name;
  for (const std::string& folder : folders)
    for (const std::string& name : exercise_names(folder))
      if (!by_name.count(name))
        by_name.emplace(name,
                        read_exercise_card((std::filesystem::path(folder) / (name + ".yaml")).string()));
  std::vector<ExerciseCard> cards;
  for (auto& [name, card] : by_name)
    cards.push_back(std::move(card));
  return cards;
}

std::string why_title_taken(const std::vector<std::string>& folders, const std::string& title,
                            const std::string& except) {
  const auto folded = [](std::string s) {
    for (char& c : s)
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
  };
  for (const std::string& folder : folders)
    for (const std::string& name : exercise_names(folder)) {
      const std::filesystem::path file = std::filesystem::path(folder) / (name + ".yaml");
      const ExerciseCard card = read_exercise_card(file.string());
      if (card.name == except) continue;
      if (card.about && folded(card.about->title) == folded(title))
        return "'" + title + "' is the title of exercise '" + card.name +
               "': give this one a title of its own";
    }
  return "";
}

std::string exercise_text_version(const std::string& text) {
  if (sodium_init() < 0) throw std::runtime_error("libsodium could not start");
  unsigned char digest[crypto_hash_sha256_BYTES];
  crypto_hash_sha256(digest, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  static constexpr char kHex[] = "0123456789abcdef";
  std::string version;
  for (int n = 0; n < 8; ++n) {
    version += kHex[digest[n] >> 4];
    version += kHex[digest[n] & 15];
  }
  return version;
}

ExerciseSource read_exercise_source(const std::string& file) {
  std::string why;
  std::optional<std::string> text = read_bounded_file(file, YamlFile::kMaxFileBytes, why);
  if (!text) throw DataError(file, 0, "(file)", why);
  ExerciseSource source;
  source.file = file;
  std::filesystem::path folder = std::filesystem::path(file).parent_path();
  if (folder.filename() == "versions") folder = folder.parent_path();
  source.folder = folder.string();
  source.version = exercise_text_version(*text);
  source.text = std::move(*text);
  return source;
}

sim::ExerciseSettings load_exercise_source(const ExerciseSource& source) {
  return load_exercise(YamlFile::parse(source.text, source.file), source.folder);
}

std::string exercise_version(const std::string& path) {
  return read_exercise_source(path).version;
}

sim::ExerciseSettings load_exercise(const std::string& path) {
  return load_exercise(YamlFile::load(path), std::filesystem::path(path).parent_path().string());
}

sim::ExerciseSettings load_exercise(const YamlFile& f, const std::string& folder) {
  sim::ExerciseSettings e = read_exercise(f, folder);
  f.check_unknown_keys();
  return e;
}

std::vector<std::string> event_kinds(const sim::MachineType& type) {
  return scriptable_events([&](sim::MachineFault fault) { return type.has_fault(fault); });
}

std::vector<std::string> instructor_faults(const sim::MachineType& type) {
  std::vector<std::string> faults;
  for (const FaultEvent& e : kFaultEvents)
    if (type.has_fault(e.fault)) faults.emplace_back(command_name(e.command));
  return faults;
}

}  // namespace harbour::io
