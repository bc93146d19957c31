#include "BulkDemo.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/bulk/PileMeasure.h"
#include "harbour/core/FixedStepClock.h"
#include "harbour/core/Units.h"
#include "harbour/io/BulkFiles.h"
#include "harbour/io/ReliefImage.h"

namespace harbour::apps {
namespace {

using core::Vec3;

constexpr double kStep_s = 0.001;         // physics step: 1 kHz
constexpr double kHoistSpeed_mps = 1.5;   // 90 m/min, typical grab crane hoist (assumed)
constexpr double kTravelSpeed_mps = 2.0;  // horizontal jib-tip speed while slewing (assumed)
constexpr double kTravelHeight_m = 10.0;  // world z of the grab when travelling
constexpr double kDropClearance_m = 2.5;  // opening height above the hold's material
constexpr double kProgressEvery_s = 15.0;

enum class Phase { kHoist, kToPile, kLower, kClose, kHoistLoaded, kToHold, kLowerToDrop, kOpen };

// moves `position` toward `target` at no more than `speed`; returns true when there
bool move_toward(Vec3& position, const Vec3& target, double speed, double dt) {
  const Vec3 d = target - position;
  const double distance = core::length(d);
  if (distance <= speed * dt) {
    position = target;
    return true;
  }
  position += d * (speed * dt / distance);
  return false;
}

// the yard's highest point (coarse search), where an operator bites next
Vec3 dig_target(const bulk::HeightGrid& yard) {
  const bulk::CellIndex top = bulk::highest_cell(yard);
  return yard.pose().to_parent(yard.cell_centre(top.i, top.j));
}

}  // namespace

int run_bulk_demo(const BulkDemoOptions& options) {
  const auto materials = io::load_materials(options.data_dir + "/materials.yaml");
  const auto scenario = io::load_bulk_scenario(options.data_dir + "/scenarios/bulk_demo.yaml", materials);

  const std::unique_ptr<bulk::BulkWorld> built = bulk::build_bulk_world(scenario);
  bulk::BulkWorld& world = *built;
  const int grab = world.add_grab(scenario.grab);
  const int yard = 0, hold = scenario.grids.size() > 1 ? 1 : 0;

  std::printf("harboursim bulk demo: %s, %zu grids, %.0f t in heaps, %d grab cycles\n",
              scenario.material.name.c_str(), scenario.grids.size(),
              core::kg_to_t(world.mass_kg(world.balance().added_m3)), options.cycles);

  // a scripted operator: bite at the top of the yard heap, drop at stations along the hold
  const std::vector<double> drop_stations_x = {4.0, 10.0, 16.0, 7.0, 13.0};
  core::FixedStepClock clock(kStep_s);
  bulk::GrabCommand command;
  command.pose.position = {5.0, 5.0, kTravelHeight_m};
  Phase phase = Phase::kHoist;
  Vec3 target;
  int cycle = 0;
  const auto wall_start = std::chrono::steady_clock::now();
  double next_progress_s = kProgressEvery_s;

  while (cycle < options.cycles) {
    bulk::move_grids(world, scenario, clock.time_s());
    const Vec3 before = command.pose.position;
    const bulk::GrabState& state = world.grab(grab);
    command.close_rate = 0.0;
    switch (phase) {
      case Phase::kHoist:
        if (move_toward(command.pose.position, {before.x, before.y, kTravelHeight_m}, kHoistSpeed_mps,
                        kStep_s)) {
          target = dig_target(world.grid(yard));
          phase = Phase::kToPile;
        }
        break;
      case Phase::kToPile:
        command.close_rate = -1.0;  // open on the way
        if (move_toward(command.pose.position, {target.x, target.y, kTravelHeight_m}, kTravelSpeed_mps,
                        kStep_s))
          phase = Phase::kLower;
        break;
      case Phase::kLower: {
        const bulk::HeightGrid& g = world.grid(yard);
        const Vec3 local = g.pose().to_local(command.pose.position);
        const double clearance = local.z - g.surface_height(local.x, local.y);
        const double speed = clearance > 1.0 ? kHoistSpeed_mps : 0.3;
        if (clearance <= 0.01)
          phase = Phase::kClose;
        else
          command.pose.position.z -= std::min(speed * kStep_s, clearance);
        break;
      }
      case Phase::kClose:
        command.close_rate = 1.0;
        if (state.digging) command.pose.position.z -= scenario.grab.sinking_speed_mps * kStep_s;
        if (state.opening_m <= 0.0) phase = Phase::kHoistLoaded;
        break;
      case Phase::kHoistLoaded:
        if (move_toward(command.pose.position, {before.x, before.y, kTravelHeight_m}, kHoistSpeed_mps,
                        kStep_s)) {
          const auto& g = world.grid(hold);
          const double station = drop_stations_x[static_cast<std::size_t>(cycle) % drop_stations_x.size()];
          target = g.pose().to_parent({station, 0.5 * g.cells_y() * g.cell_size_m(), 0.0});
          phase = Phase::kToHold;
        }
        break;
      case Phase::kToHold:
        if (move_toward(command.pose.position, {target.x, target.y, kTravelHeight_m}, kTravelSpeed_mps,
                        kStep_s))
          phase = Phase::kLowerToDrop;
        break;
      case Phase::kLowerToDrop: {
        const bulk::HeightGrid& g = world.grid(hold);
        const Vec3 local = g.pose().to_local(command.pose.position);
        const double drop_z =
            g.pose().to_parent({local.x, local.y, g.surface_height(local.x, local.y)}).z + kDropClearance_m;
        if (move_toward(command.pose.position, {before.x, before.y, std::min(drop_z, kTravelHeight_m)},
                        kHoistSpeed_mps, kStep_s))
          phase = Phase::kOpen;
        break;
      }
      case Phase::kOpen:
        command.close_rate = -1.0;
        if (state.load_m3 <= 0.0 && state.opening_m >= scenario.grab.max_opening_m) {
          ++cycle;
          phase = Phase::kHoist;
        }
        break;
    }
    command.velocity = (command.pose.position - before) * (1.0 / kStep_s);
    world.step(kStep_s, {&command, 1});
    clock.advance();

    if (clock.time_s() >= next_progress_s) {
      next_progress_s += kProgressEvery_s;
      const auto b = world.balance();
      std::printf("  t=%6.1f s  cycle %d/%d  in hold %6.1f t  in grab %5.1f t  spilled %5.2f t\n",
                  clock.time_s(), std::min(cycle + 1, options.cycles), options.cycles,
                  core::kg_to_t(world.mass_kg(world.grid(hold).total_volume_m3())),
                  core::kg_to_t(world.mass_kg(b.in_grabs_m3)), core::kg_to_t(world.mass_kg(b.spilled_m3)));
      std::fflush(stdout);
    }
  }

  // let the last drop land and the piles settle
  for (int n = 0; n < 3000 || !world.parcels().empty(); ++n) {
    bulk::move_grids(world, scenario, clock.time_s());
    command.velocity = {};
    command.close_rate = 0.0;
    world.step(kStep_s, {&command, 1});
    clock.advance();
  }

  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const auto b = world.balance();
  std::printf("\nsimulated %.1f s in %.2f s of wall time (%.1fx real time)\n", clock.time_s(), wall_s,
              clock.time_s() / wall_s);
  std::printf("moved into the hold : %8.2f t in %d cycles (%.1f t per bite)\n",
              core::kg_to_t(world.mass_kg(world.grid(hold).total_volume_m3())), options.cycles,
              core::kg_to_t(world.mass_kg(world.loaded_m3())) / options.cycles);
  std::printf("spilled             : %8.3f t\n", core::kg_to_t(world.mass_kg(b.spilled_m3)));
  std::printf("mass balance        : %.3e t discrepancy over %.1f t\n",
              core::kg_to_t(world.mass_kg(b.discrepancy_m3())), core::kg_to_t(world.mass_kg(b.added_m3)));
  const double flank_min = core::deg_to_rad(10.0);
  for (int g = 0; g < world.grid_count(); ++g)
    std::printf("angle of repose     : %-5s %5.1f deg (median flank slope; material %.1f deg)\n",
                scenario.grids[static_cast<std::size_t>(g)].name.c_str(),
                core::rad_to_deg(bulk::median_flank_angle(world.grid(g), flank_min)),
                core::rad_to_deg(scenario.material.angle_of_repose_rad));
  std::vector<const bulk::HeightGrid*> grids;
  for (int g = 0; g < world.grid_count(); ++g)
    grids.push_back(&world.grid(g));
  const std::string png = options.out_dir + "/bulk_demo.png";
  io::write_relief_png(png, grids);
  std::printf("relief image        : %s\n", png.c_str());
  if (world.warnings().total() > 0) {
    std::printf("physics warnings    : %u\n", world.warnings().total());
    return 1;
  }
  return 0;
}

}  // namespace harbour::apps
