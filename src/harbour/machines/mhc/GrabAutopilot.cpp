#include "harbour/machines/mhc/GrabAutopilot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "harbour/core/Units.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"

namespace harbour::sim {
namespace {

constexpr double kG = core::kStandardGravity;
constexpr double kCoamingClearance_m = 2.5;  // grab bottom over the coaming top while it slews
constexpr double kDischargeHeight_m = 4.0;   // grab bottom over the floor it drops onto when it opens (at 3 m
                                             // the shells sat in the heap they built under them)
constexpr double kSpotMargin_m = 1.0;        // dig spots inside the coamings by the grab's half size and this
constexpr double kSpotTie_m = 0.05;          // dig spots whose material stands within this count as level
constexpr double kLattice_m = 0.5;           // trimming: the spots it looks at over the pile
constexpr double kDumpApart_m = 10.0;        // trimming: the drop spot at least this far from the dig spot
constexpr double kBesideHopper_m = 8.0;      // after a hoist brake fault: the grab set down this far out of
                                             // the hopper's centre

// the material's surface height over `point` (the point's own height where no grid lies under it)
double surface_z(const bulk::BulkWorld& bulk, const core::Vec3& point) {
  double surface = point.z;
  for (int g = 0; g < bulk.grid_count(); ++g) {
    const core::Vec3 local = bulk.grid(g).pose().to_local(point);
    if (bulk.grid(g).contains(local.x, local.y))
      surface =
          bulk.grid(g).pose().to_parent({local.x, local.y, bulk.grid(g).surface_height(local.x, local.y)}).z;
  }
  return surface;
}

double wrap(double a) {
  return std::remainder(a, 2.0 * std::numbers::pi);
}

const VesselSettings::Hold* open_hold(const VesselSettings& vessel) {
  for (const VesselSettings::Hold& h : vessel.holds)
    if (h.open) return &h;
  return nullptr;
}

}  // namespace

std::string GrabAutopilot::why_cannot_drive(const ExerciseSettings& exercise) {
  if (!exercise.scenario.machine.get_if<MhcSetup>())
    return "the grab autopilot drives the mobile harbour crane";
  if (exercise.scenario.machine.as<MhcSetup>().start.on_hook) return "the crane works on its hook";
  if (exercise.trim) return "";
  if (!exercise.deliver) return "the exercise has no delivery or trim goal (exercise.deliver, exercise.trim)";
  const auto& vessel = exercise.scenario.vessel;
  if (!vessel || vessel->vessel.kind != VesselKind::kBulk || !open_hold(vessel->vessel))
    return "the grab autopilot digs from a bulk carrier's open hold";
  return "";
}

GrabAutopilot::GrabAutopilot(const ExerciseSettings& exercise, GrabOperatorDefects defects)
    : exercise_(exercise), defects_(defects) {
  if (const std::string why = why_cannot_drive(exercise); !why.empty()) throw std::invalid_argument(why);
  if (exercise.trim) return;  // it digs where the pile stands highest and drops where it lies lowest
  vessel_.emplace(*exercise.scenario.vessel);
  // a 3 x 3 pattern over the open hatch, centre first, then its sides, then its corners
  const VesselGeometry& geometry = *vessel_;
  const VesselSettings::Hold& hold = *open_hold(exercise.scenario.vessel->vessel);
  const MhcSettings& crane = exercise.scenario.machine.as<MhcSetup>().crane;
  const double reach_x =
      geometry.placement().vessel.hatch_breadth_m / 2 - crane.grab_lower_half_extents_m.x - kSpotMargin_m;
  const double reach_y = hold.opening_length_m / 2 - crane.grab_lower_half_extents_m.x - kSpotMargin_m;
  const double top = geometry.placement().vessel.tank_top_m;
  for (const auto& [fx, fy] :
       {std::pair{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, 1}, {-1, 1}, {1, -1}})
    spots_.push_back({0.6 * fx * reach_x, hold.centre_m + 0.6 * fy * reach_y, top});
}

const char* GrabAutopilot::activity() const {
  switch (phase_) {
    case Phase::kToDig:
      return "to dig";
    case Phase::kLower:
      return "lower";
    case Phase::kShut:
      return "shut";
    case Phase::kHoist:
      return "hoist";
    case Phase::kToDrop:
      return "to drop";
    case Phase::kDischarge:
      return "discharge";
    case Phase::kOpenAfterFault:
      return "open after fault";
    case Phase::kFaultStop:
      return "fault stop";
    case Phase::kDone:
      return "done";
  }
  return "";
}

void GrabAutopilot::resume(const Simulation& simulation, int /*moves_done*/, const scene::Controls& levers) {
  phase_ = simulation.carrying() ? Phase::kHoist : Phase::kToDig;
  phase_start_s_ = simulation.time_s();
  take_levers(levers);  // its filters start again from what it sees
}

core::Vec3 GrabAutopilot::dig_spot(const Simulation& simulation) const {
  if (exercise_.trim) return pile_dig_m_;
  return vessel_->pose_at(simulation.time_s()).to_parent(spots_[spot_]);
}

void GrabAutopilot::choose_trim_spots(const Simulation& simulation, const MobileHarbourCrane& crane) {
  // over a 0.5 m lattice on the pile, inside its edges by the grab's half size and a margin: dig where it
  // stands highest, drop where it lies lowest at least kDumpApart_m from there and within the chart's reach
  const bulk::BulkWorld& bulk = *simulation.bulk();
  const bulk::HeightGrid& grid = bulk.grid(exercise_.trim->grid_index);
  const int step = std::max(1, static_cast<int>(std::lround(kLattice_m / grid.cell_size_m())));
  const int inset = static_cast<int>(
      std::ceil((crane.settings().grab_lower_half_extents_m.x + kSpotMargin_m) / grid.cell_size_m()));
  const auto world = [&](int i, int j) {
    const core::Vec3 c = grid.cell_centre(i, j);
    return grid.pose().to_parent({c.x, c.y, grid.height(i, j)});
  };
  double highest = -std::numeric_limits<double>::infinity();
  for (int j = inset; j < grid.cells_y() - inset; j += step)
    for (int i = inset; i < grid.cells_x() - inset; i += step)
      if (const core::Vec3 p = world(i, j); p.z > highest + kSpotTie_m) highest = p.z, pile_dig_m_ = p;
  const double reach = crane.settings().capacity_chart.back().radius_m - kSpotMargin_m;
  double lowest = std::numeric_limits<double>::infinity();
  for (int j = inset; j < grid.cells_y() - inset; j += step)
    for (int i = inset; i < grid.cells_x() - inset; i += step) {
      const core::Vec3 p = world(i, j);
      const bool apart = std::hypot(p.x - pile_dig_m_.x, p.y - pile_dig_m_.y) >= kDumpApart_m;
      const core::Vec3 from_axis = p - crane.position_m();
      if (apart && std::hypot(from_axis.x, from_axis.y) < reach && p.z < lowest - kSpotTie_m)
        lowest = p.z, dump_m_ = p;
    }
  travel_z_m_ = pile_top_m(bulk, exercise_.trim->grid_index) + kCoamingClearance_m;
}

void GrabAutopilot::choose_dig_spot(const Simulation& simulation) {
  // where the material stands highest (the first of the pattern among equals)
  const core::Pose vessel = vessel_->pose_at(simulation.time_s());
  double highest = -std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < spots_.size(); ++n) {
    const double z = surface_z(*simulation.bulk(), vessel.to_parent(spots_[n]));
    if (z > highest + kSpotTie_m) highest = z, spot_ = n;
  }
}

scene::Controls GrabAutopilot::decide(const Simulation& simulation, const MobileHarbourCrane& crane) {
  double slew = 0.0, luff = 0.0, hoist = 0.0, grab = 0.0;
  const double now = simulation.time_s();
  const auto choose = [&] {
    if (exercise_.trim)
      choose_trim_spots(simulation, crane);
    else
      choose_dig_spot(simulation);
  };
  auto enter = [&](Phase p) {
    phase_ = p;
    phase_start_s_ = now;
    if (p == Phase::kToDig) choose();
  };
  if (first_decision()) choose();
  const double decision_s = kDecisionSteps * Simulation::kStep_s;
  steering_.observe(crane, decision_s, first_decision());
  const bulk::BulkWorld& bulk = *simulation.bulk();
  const double load_m3 = bulk.grab(simulation.bulk_grab()).load_m3;
  const double bottom = crane.attachment_bottom_z_m();
  // the height it travels at (over the coaming, over the pile), where it drops the bite (over the hopper's
  // floor, over the pile's lowest spot) and whether the goal is met with what is on its way
  double travel_z = travel_z_m_;
  core::Vec3 drop = dump_m_;
  bool delivered = false;
  if (exercise_.trim) {
    drop.z = surface_z(bulk, dump_m_);
    delivered = pile_top_m(bulk, exercise_.trim->grid_index) <= exercise_.trim->top_m;
  } else {
    const VesselGeometry& geometry = *vessel_;
    const double coaming_top = geometry.pose_at(now).to_parent({0, 0, geometry.coaming_top_m()}).z;
    travel_z = defects_.travel_below_the_coaming ? coaming_top - 1.0 : coaming_top + kCoamingClearance_m;
    const bulk::GridPlacement& hopper =
        exercise_.scenario.bulk->grids[static_cast<std::size_t>(exercise_.deliver->grid_index)];
    const double hopper_half = 0.5 * hopper.settings.cell_size_m;
    drop = {hopper.origin_x_m + hopper_half * hopper.settings.cells_x,
            hopper.origin_y_m + hopper_half * hopper.settings.cells_y, hopper.origin_z_m};
    const double t_per_m3 = bulk.material().bulk_density_kg_m3 / 1000.0;
    double in_flight_m3 = 0.0;
    for (const bulk::Parcel& p : bulk.parcels())
      in_flight_m3 += p.volume_m3;
    delivered = (bulk.landed_m3(exercise_.deliver->grid_index) + in_flight_m3) * t_per_m3 >=
                exercise_.deliver->tonnes;
  }
  const double empty_kg = crane.settings().grab_head_mass_kg + crane.settings().grab_lower_mass_kg;
  // the hoist brake has failed: no bite more; one being taken is let go where it lies
  const bool fault = crane.fault_active(MachineFault::kHoistBrake);
  if (phase_ != Phase::kFaultStop) {  // the grab set down where it is, unless told otherwise below
    rest_spot_m_ = crane.load_position_m();
    rest_spot_m_.z = 0.0;  // the quay, outside every grid
  }
  if (fault && (phase_ == Phase::kToDig || phase_ == Phase::kLower)) enter(Phase::kFaultStop);
  if (fault && phase_ == Phase::kShut) enter(Phase::kOpenAfterFault);
  const auto hold_height = [&](double z) { return steering_.hold_height(z); };
  const auto steer = [&](const BoomSteering::Target& target, double tolerance_m, double& slew_lever,
                         double& luff_lever) {
    return steering_.steer(crane, target, tolerance_m, slew_lever, luff_lever);
  };
  const auto target_of = [&](const core::Vec3& point) { return BoomSteering::target_of(crane, point); };

  switch (phase_) {
    case Phase::kToDig: {
      grab = -1.0;  // open on the way
      hoist = hold_height(travel_z + 0.5);
      if (bottom > travel_z - 0.5 && steer(target_of(dig_spot(simulation)), 0.4, slew, luff) &&
          crane.grab_opening() > 0.95)
        enter(Phase::kLower);
      break;
    }
    case Phase::kLower: {
      const core::Vec3 spot = dig_spot(simulation);
      const double surface = surface_z(bulk, spot);
      steer(target_of(spot), 0.4, slew, luff);
      hoist = bottom - surface > 3.0 ? -1.0 : -0.3;
      // resting on the material: the ropes' filtered load below half the grab's weight, near the surface
      if (bottom - surface < 1.0 && crane.limiter_load_n() < 0.5 * empty_kg * kG) enter(Phase::kShut);
      break;
    }
    case Phase::kShut:
      grab = 1.0;
      if (crane.grab_opening() < 0.001 || now - phase_start_s_ > 8.0) {
        ++bites_;
        enter(Phase::kHoist);
      }
      break;
    case Phase::kHoist:
      grab = 1.0;  // the closing winch keeps the shells shut while the load comes onto the ropes
      hoist = now - phase_start_s_ < 3.0 ? 0.3 : 1.0;
      if (bottom > travel_z) enter(Phase::kToDrop);
      break;
    case Phase::kToDrop: {
      grab = 1.0;
      hoist = hold_height(std::max(travel_z, drop.z + kDischargeHeight_m));
      const BoomSteering::Target target = target_of(drop);
      const bool over = steer(target, 0.5, slew, luff);
      // the bad operator opens half way, over the gap between quay and ship
      if (defects_.open_over_the_quay_edge && std::abs(wrap(target.slew_rad - crane.slew_rad())) < 0.6 &&
          std::abs(wrap(target.slew_rad - crane.slew_rad())) > 0.4)
        grab = -1.0;
      if (over) enter(Phase::kDischarge);
      break;
    }
    case Phase::kDischarge:
      grab = -1.0;
      hoist = hold_height(drop.z + kDischargeHeight_m);
      steer(target_of(drop), 0.5, slew, luff);
      if (load_m3 <= 0.0 && crane.grab_opening() > 0.95) {
        enter(fault ? Phase::kFaultStop : delivered ? Phase::kDone : Phase::kToDig);
        // not in the hopper, which drains under it: beside it on the quay, away from the crane
        if (fault && exercise_.deliver) {
          const core::Vec3 out = drop - crane.position_m();
          rest_spot_m_ = drop + out * (kBesideHopper_m / std::max(std::hypot(out.x, out.y), 1.0));
          rest_spot_m_.z = 0.0;
        }
      }
      break;
    case Phase::kOpenAfterFault:
      grab = -1.0;
      if (load_m3 <= 0.0 && crane.grab_opening() > 0.95) enter(Phase::kFaultStop);
      break;
    case Phase::kFaultStop: {
      // the empty grab carried to its spot (beside the hopper, or where it is) and set down there, calm
      const bool over = steer(target_of(rest_spot_m_), 0.5, slew, luff);
      reached_rest_spot_ = reached_rest_spot_ || over;
      if (!reached_rest_spot_)
        return hand_levers(simulation.control_table(), last_decision(), decision_before_last(), decision_s,
                           {{"slew", slew}, {"luff", luff}, {"hoist", hold_height(travel_z)}});
      return stop_after_hoist_fault(simulation.control_table(), crane, last_decision(),
                                    decision_before_last(), decision_s, empty_kg,
                                    surface_z(bulk, rest_spot_m_), slew, luff);
    }
    case Phase::kDone:
      hoist = hold_height(travel_z);
      break;
  }
  return hand_levers(simulation.control_table(), last_decision(), decision_before_last(), decision_s,
                     {{"slew", slew}, {"luff", luff}, {"hoist", hoist}, {"grab", grab}});
}

}  // namespace harbour::sim
