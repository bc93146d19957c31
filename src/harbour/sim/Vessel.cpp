#include "harbour/sim/Vessel.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::sim {
namespace {

constexpr double kIsoHalfLength40_m = 12.192 / 2, kIsoHalfWidth_m = 2.438 / 2;
constexpr double kCoamingWall_m = 0.3;   // coaming plate and hatch cover overlap, assumed
constexpr double kDeckPlate_m = 0.5;     // deck and cross-deck structure depth, assumed
constexpr double kShellPlate_m = 0.4;    // side shell (double hull simplified), assumed
constexpr double kHatchGirder_m = 0.02;  // half width of the centreline girder under split covers
constexpr double kHatchLid_m = 0.6;      // a bulk carrier's closed hatch cover, assumed

double sum(const std::vector<Harmonic>& hs, double t, double* rate) {
  double value = 0.0, d = 0.0;
  for (const Harmonic& h : hs) {
    const double w = 2.0 * std::numbers::pi / h.period_s;
    value += h.amplitude * std::sin(w * t + h.phase_rad);
    d += h.amplitude * w * std::cos(w * t + h.phase_rad);
  }
  if (rate) *rate = d;
  return value;
}

core::Pose box_between(const core::Vec3& lo, const core::Vec3& hi, core::Vec3& half) {
  half = (hi - lo) * 0.5;
  return {core::Mat3::identity(), (lo + hi) * 0.5};
}

}  // namespace

core::Pose VesselGeometry::pose_at(double t) const {
  const double heave = sum(p_.sea.heave_m, t, nullptr);
  const double roll = sum(p_.sea.roll_rad, t, nullptr), pitch = sum(p_.sea.pitch_rad, t, nullptr);
  const core::Mat3 r = core::Mat3::rotation({0, 1, 0}, roll) * core::Mat3::rotation({1, 0, 0}, pitch);
  // the waterline centre heaves; the hull turns about it
  const core::Vec3 centre_world = p_.keel_midship_m + centre() + core::Vec3{0, 0, heave};
  return {r, centre_world - r * centre()};
}

core::Pose VesselGeometry::stowed_pose_at(double t_s, const core::Vec3& centre_m) const {
  const core::Pose vessel = pose_at(t_s);
  return {vessel.rotation * core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 2),
          vessel.to_parent(centre_m)};
}

void VesselGeometry::velocities_at(double t, core::Vec3& linear, core::Vec3& angular) const {
  double heave_rate = 0.0, roll_rate = 0.0, pitch_rate = 0.0;
  sum(p_.sea.heave_m, t, &heave_rate);
  const double roll = sum(p_.sea.roll_rad, t, &roll_rate);
  sum(p_.sea.pitch_rad, t, &pitch_rate);
  // R = Ry(roll) Rx(pitch): omega = roll' e_y + pitch' Ry(roll) e_x, at the waterline centre
  angular =
      core::Vec3{0, roll_rate, 0} + core::Mat3::rotation({0, 1, 0}, roll) * core::Vec3{pitch_rate, 0, 0};
  linear = {0, 0, heave_rate};
}

std::optional<double> VesselGeometry::row_x(int row) const {
  const int n = p_.vessel.rows;
  const double pitch = p_.vessel.row_pitch_m;
  if (row < 0) return std::nullopt;
  if (n % 2 == 1 && row == 0) return 0.0;
  if (row == 0) return std::nullopt;
  const int k = (row + 1) / 2;  // 1 for rows 01 and 02
  if (k > n / 2) return std::nullopt;
  const double offset = n % 2 == 0 ? (k - 0.5) * pitch : k * pitch;
  return row % 2 == 1 ? offset : -offset;
}

const VesselSettings::Bay* VesselGeometry::bay(int number) const {
  for (const VesselSettings::Bay& b : p_.vessel.bays)
    if (b.number == number) return &b;
  return nullptr;
}

std::optional<core::Vec3> VesselGeometry::slot_centre(const SlotAddress& slot, double height_m,
                                                      std::string& why) const {
  const VesselSettings& v = p_.vessel;
  const VesselSettings::Bay* b = bay(slot.bay);
  if (!b) {
    why = "the vessel has no 40 ft bay " + std::to_string(slot.bay);
    return std::nullopt;
  }
  const std::optional<double> x = row_x(slot.row);
  if (!x) {
    why = "the vessel has no row " + std::to_string(slot.row) + " (" + std::to_string(v.rows) + " rows)";
    return std::nullopt;
  }
  double bottom = 0.0;
  if (slot.tier % 2 == 0 && slot.tier >= 2 && slot.tier <= 2 * v.hold_tiers) {
    bottom = v.tank_top_m + (slot.tier / 2 - 1) * v.tier_height_m;
  } else if (slot.tier % 2 == 0 && slot.tier >= 82 && slot.tier < 82 + 2 * v.deck_tiers) {
    bottom = coaming_top_m() + v.hatch_cover_thickness_m + (slot.tier - 82) / 2 * v.tier_height_m;
  } else {
    why = "tier " + std::to_string(slot.tier) + " is neither a hold tier (02.." +
          std::to_string(2 * v.hold_tiers) + ") nor a deck tier (82.." +
          std::to_string(80 + 2 * v.deck_tiers) + ")";
    return std::nullopt;
  }
  return core::Vec3{*x, b->centre_m, bottom + height_m / 2.0};
}

std::vector<VesselGeometry::Opening> VesselGeometry::hatch_openings() const {
  const VesselSettings& v = p_.vessel;
  std::vector<Opening> openings;
  if (v.kind == VesselKind::kBulk) {
    for (const VesselSettings::Hold& h : v.holds)
      openings.push_back({h.centre_m, v.hatch_breadth_m / 2, h.opening_length_m / 2});
  } else {
    const double half_length = kIsoHalfLength40_m + v.cell_clearance_m + v.cell_guide_thickness_m + 0.1;
    for (const VesselSettings::Bay& b : v.bays)
      openings.push_back({b.centre_m, v.rows * v.row_pitch_m / 2.0, half_length});
  }
  std::sort(openings.begin(), openings.end(),
            [](const auto& a, const auto& b) { return a.centre_m < b.centre_m; });
  return openings;
}

const VesselSettings::Hold* VesselGeometry::hold(int number) const {
  for (const VesselSettings::Hold& h : p_.vessel.holds)
    if (h.number == number) return &h;
  return nullptr;
}

VesselGeometry::Floor VesselGeometry::hold_floor(const VesselSettings::Hold& hold) const {
  const VesselSettings& v = p_.vessel;
  const double half_breadth = v.beam_m / 2 - kShellPlate_m;
  const double half_length = hold.opening_length_m / 2 + kCoamingWall_m;
  return {{-half_breadth, hold.centre_m - half_length, v.tank_top_m}, 2 * half_breadth, 2 * half_length};
}

std::vector<VesselGeometry::Panel> VesselGeometry::hatch_panels() const {
  const VesselSettings& v = p_.vessel;
  std::vector<Panel> panels;
  if (v.kind == VesselKind::kBulk) return panels;  // discharging: the hatches are open
  const double half_opening = v.rows * v.row_pitch_m / 2.0;
  const double half_length = hatch_openings().front().half_length_m + kCoamingWall_m;
  const double z = coaming_top_m() + v.hatch_cover_thickness_m / 2.0;
  for (const VesselSettings::Bay& b : v.bays) {
    const std::string bay = std::to_string(b.number);
    if (v.hatch_panels == 1) {
      panels.push_back({"HATCH" + bay,
                        {0, b.centre_m, z},
                        {half_opening + kCoamingWall_m, half_length, v.hatch_cover_thickness_m / 2}});
    } else {
      const double half_width = (half_opening + kCoamingWall_m) / 2.0;
      panels.push_back({"HATCH" + bay + "P",
                        {-half_width, b.centre_m, z},
                        {half_width, half_length, v.hatch_cover_thickness_m / 2}});
      panels.push_back({"HATCH" + bay + "S",
                        {half_width, b.centre_m, z},
                        {half_width, half_length, v.hatch_cover_thickness_m / 2}});
    }
  }
  return panels;
}

Vessel::Vessel(physics::PhysicsWorld& world, const VesselPlacement& placement)
    : world_(world), geometry_(placement) {
  const VesselSettings& v = placement.vessel;
  frame_ = geometry_.pose_at(0.0);
  geometry_.velocities_at(0.0, velocity_, angular_velocity_);
  body_ = world.add_kinematic_body({frame_.rotation, waterline_centre()});  // the body's origin
  auto add = [&](const core::Vec3& lo, const core::Vec3& hi, int surface) {
    core::Vec3 half;
    core::Pose local = box_between(lo, hi, half);
    local.position = local.position - origin();
    world.add_box_shape(body_, half, local, surface);
    if (surface == scene::kSurfaceCellGuide) ++cell_guide_shapes_;
  };
  const double half_beam = v.beam_m / 2, half_length = v.length_m / 2;
  const std::vector<VesselGeometry::Opening> openings = geometry_.hatch_openings();
  const double half_opening = openings.front().half_breadth_m;  // every hatch has the same breadth
  const double top = geometry_.coaming_top_m(), deck = v.depth_m;

  // double bottom, side shells and the deck outboard of the hatch coamings
  add({-half_beam, -half_length, 0}, {half_beam, half_length, v.tank_top_m}, scene::kSurfaceHull);
  for (double side : {-1.0, 1.0}) {
    add({side > 0 ? half_beam - kShellPlate_m : -half_beam, -half_length, v.tank_top_m},
        {side > 0 ? half_beam : -half_beam + kShellPlate_m, half_length, deck}, scene::kSurfaceHull);
    const double inner = half_opening + kCoamingWall_m;
    add({side > 0 ? inner : -half_beam + kShellPlate_m, -half_length, deck - kDeckPlate_m},
        {side > 0 ? half_beam - kShellPlate_m : -inner, half_length, deck}, scene::kSurfaceHull);
  }
  // cross decks fore and aft of every hatch, from the vessel's ends between the hatches
  double aft_end = -half_length;
  for (const VesselGeometry::Opening& o : openings) {
    const double aft = o.centre_m - o.half_length_m - kCoamingWall_m;
    if (aft > aft_end)
      add({-half_opening - kCoamingWall_m, aft_end, v.tank_top_m}, {half_opening + kCoamingWall_m, aft, deck},
          scene::kSurfaceHull);
    aft_end = o.centre_m + o.half_length_m + kCoamingWall_m;
  }
  if (aft_end < half_length)
    add({-half_opening - kCoamingWall_m, aft_end, v.tank_top_m},
        {half_opening + kCoamingWall_m, half_length, deck}, scene::kSurfaceHull);

  const double c = v.cell_clearance_m, t = v.cell_guide_thickness_m, leg = v.cell_guide_leg_m;
  for (const VesselGeometry::Opening& o : openings) {
    const double y0 = o.centre_m, hl = o.half_length_m;
    // hatch coamings: port and starboard, fore and aft walls up to the covers
    for (double s : {-1.0, 1.0}) {
      add({s > 0 ? half_opening : -half_opening - kCoamingWall_m, y0 - hl - kCoamingWall_m,
           deck - kDeckPlate_m},
          {s > 0 ? half_opening + kCoamingWall_m : -half_opening, y0 + hl + kCoamingWall_m, top},
          scene::kSurfaceHull);
      add({-half_opening, s > 0 ? y0 + hl : y0 - hl - kCoamingWall_m, deck - kDeckPlate_m},
          {half_opening, s > 0 ? y0 + hl + kCoamingWall_m : y0 - hl, top}, scene::kSurfaceHull);
    }
    if (v.kind == VesselKind::kBulk) {
      const auto hold =
          std::find_if(v.holds.begin(), v.holds.end(), [&](const auto& h) { return h.centre_m == y0; });
      if (hold != v.holds.end() && !hold->open)
        add({-half_opening - kCoamingWall_m, y0 - hl - kCoamingWall_m, top},
            {half_opening + kCoamingWall_m, y0 + hl + kCoamingWall_m, top + kHatchLid_m},
            scene::kSurfaceHatchCover);
      continue;
    }
    if (v.hatch_panels == 2)
      add({-kHatchGirder_m, y0 - hl, top - 0.5}, {kHatchGirder_m, y0 + hl, top}, scene::kSurfaceHull);
    // cell guides: an angle bar at each corner of every cell, from the tank top to just under the hatch
    // covers (they do not carry them)
    const double guide_top = top - 0.05;
    for (int k = 0; k < v.rows; ++k) {
      const int row = v.rows % 2 == 1 ? (k == 0 ? 0 : k) : k + 1;
      const double x0 = *geometry_.row_x(row);
      for (double sx : {-1.0, 1.0}) {
        for (double sy : {-1.0, 1.0}) {
          auto span = [](double centre, double sign, double from, double to) {
            return sign > 0 ? std::pair{centre + from, centre + to} : std::pair{centre - to, centre - from};
          };
          const double hw = kIsoHalfWidth_m;
          // leg across the container's end face stops it along the vessel; leg along its side stops it across
          const auto [ax0, ax1] = span(x0, sx, hw + c, hw + c + t);
          const auto [ay0, ay1] = span(y0, sy, kIsoHalfLength40_m + c + t - leg, kIsoHalfLength40_m + c + t);
          add({ax0, ay0, v.tank_top_m}, {ax1, ay1, guide_top}, scene::kSurfaceCellGuide);
          const auto [bx0, bx1] = span(x0, sx, hw + c + t - leg, hw + c + t);
          const auto [by0, by1] = span(y0, sy, kIsoHalfLength40_m + c, kIsoHalfLength40_m + c + t);
          add({bx0, by0, v.tank_top_m}, {bx1, by1, guide_top}, scene::kSurfaceCellGuide);
        }
      }
    }
  }
}

void Vessel::move_to(double t_s) {
  frame_ = geometry_.pose_at(t_s);
  geometry_.velocities_at(t_s, velocity_, angular_velocity_);
  world_.set_kinematic_motion(body_, {frame_.rotation, waterline_centre()}, velocity_, angular_velocity_);
}

}  // namespace harbour::sim
