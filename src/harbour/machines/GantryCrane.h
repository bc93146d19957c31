#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "harbour/machines/parts/SpreaderHoist.h"
#include "harbour/scene/Controls.h"

namespace harbour::sim {

/// The levers and buttons a gantry crane's operator works, whichever crane it is: what a scripted operator
/// decides, the crane writing them into its own controls (those it lacks ignored).
struct GantryLevers {
  double gantry = 0.0;   ///< [-1, 1] +: along +y
  double trolley = 0.0;  ///< [-1, 1] +: waterside
  double hoist = 0.0;    ///< [-1, 1] +: raise
  double steer = 0.0;    ///< [-1, 1] +: turn left (a gantry on tyres)
  bool lock = false;
  bool unlock = false;
  bool emergency_stop = false;
  bool horn = false;
  std::uint8_t spreader_size_ft = 0;   ///< a size button held: 20, 40 or 45 (0: none)
  std::array<bool, 4> flipper_down{};  ///< flipper switches per twistlock corner (true: lowered)
  friend bool operator==(const GantryLevers&, const GantryLevers&) = default;
};

/// A portal crane whose trolley carries a spreader hoist across its gantry: the gantry travels along world
/// y, the trolley along world x (the STS; an RTG standing square to the world). What a scripted operator
/// needs to drive one by where its load hangs, whichever it is.
class GantryCrane {
 public:
  virtual ~GantryCrane() = default;
  /// The gantry's and the trolley's world positions [m] and the speeds their drives are asked [m/s].
  virtual double gantry_y_m() const = 0;
  virtual double trolley_x_m() const = 0;
  virtual double gantry_reference_mps() const = 0;
  virtual double trolley_reference_mps() const = 0;
  /// Their speeds at full lever now [m/s] (a gantry may travel slower laden).
  virtual double gantry_max_speed_mps() const = 0;
  virtual double trolley_max_speed_mps() const = 0;
  virtual const SpreaderHoist& spreader_hoist() const = 0;
  /// A gantry on tyres steers to hold its line along the block: how far its middle is off that line [m,
  /// along world x], its heading off it [rad, anticlockwise], and the steering lever that turns it at a yaw
  /// rate [rad/s] at its present speed (what a driver learns of the steering). A crane on rails holds its
  /// line: 0, 0, and no steering.
  virtual double lane_offset_m() const { return 0.0; }
  virtual double yaw_rad() const { return 0.0; }
  virtual double steer_lever(double /*yaw_rate_radps*/) const { return 0.0; }
  /// Its controls with these levers and buttons (those it lacks ignored, the others neutral).
  virtual scene::Controls crane_controls(const GantryLevers& levers) const = 0;
};

class Machine;

/// Brings a gantry crane to rest before the exercise starts: its own steps with every lever neutral (drives
/// and drum braked), its `bodies` (gantry, trolley, spreader) stopped at each peak of their kinetic energy
/// and the ropes' waves with them. Built, its gantry and trolley hang on their joints' compliance undeflected
/// and its spreader on ropes pretensioned straight down: the STS's load cell then swung +-24 % through the
/// first 2 s.
void settle_gantry_crane(Machine& crane, physics::PhysicsWorld& world,
                         std::span<const physics::BodyId> bodies, SpreaderHoist& rig);

}  // namespace harbour::sim
