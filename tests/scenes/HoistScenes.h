#pragma once

// The shipped STS hoist and MHC grab reevings on point masses: shared by the cable tests and benchmark.

#include <memory>
#include <string>
#include <vector>

#include "harbour/cable/HoistSystem.h"
#include "harbour/io/ReevingFiles.h"
#include "scenes/PointMassBodies.h"

namespace harbour::scenes {

struct HoistScene {
  PointMassBodies bodies;
  std::unique_ptr<cable::HoistSystem> hoist;
  std::vector<cable::DrumCommand> commands;
  core::Vec3 gravity{0, 0, -9.80665};
  int nodes = 0;  ///< interior wave nodes over all segments

  void build(cable::ReevingSettings reeving, int max_substeps) {
    reeving.max_substeps = max_substeps;
    hoist = std::make_unique<cable::HoistSystem>(reeving, bodies, gravity);
    int drums = 0;
    for (const auto& e : reeving.elements)
      drums += e.kind == cable::ElementKind::kDrum;
    commands.assign(static_cast<std::size_t>(drums), {});
    for (const auto& r : reeving.ropes)
      nodes += static_cast<int>(r.path.size() - 1) * (r.nodes - 1);
  }
  void step() {
    hoist->step(0.001, commands, bodies);
    bodies.step(0.001, gravity);
  }
};

/// STS hoist: trolley fixed over the vessel at x = 20 m, headblock + spreader + 65 t (80 t) hanging at z = 20
/// m.
inline void build_sts(HoistScene& s, const std::string& data_dir, int max_substeps = 8) {
  const io::ReevingFile f = io::load_reeving(data_dir + "/reeving/sts_hoist.yaml");
  s.bodies.add({0, 0, 0}, 1e6, true);      // gantry (its frame is the crane's base centre)
  s.bodies.add({20, 0, 49}, 30000, true);  // trolley
  s.bodies.add({20, 0, 20}, 80000);        // headblock, spreader and container
  s.build(f.reeving, max_substeps);
}

/// MHC grab: boom head fixed at (30, 0, 35); grab head (18 t) and lower block with a full bite (13.5 t).
inline void build_mhc(HoistScene& s, const std::string& data_dir, int max_substeps = 8) {
  const io::ReevingFile f = io::load_reeving(data_dir + "/reeving/mhc_grab.yaml");
  s.bodies.add({0, 0, 0}, 190000, true);   // house (its frame: the slewing ring)
  s.bodies.add({30, 0, 35}, 60000, true);  // boom head
  s.bodies.add({30, 0, 15}, 18000);        // grab head
  s.bodies.add({30, 0, 13.5}, 13500);      // lower block with the load
  s.build(f.reeving, max_substeps);
}

}  // namespace harbour::scenes
