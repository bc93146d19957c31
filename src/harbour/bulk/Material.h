#pragma once

#include <string>

namespace harbour::bulk {

/// A granular bulk material (settings; immutable while simulating).
struct Material {
  std::string name;
  double bulk_density_kg_m3 = 0.0;   ///< [kg/m^3] loose bulk density
  double angle_of_repose_rad = 0.0;  ///< [rad] critical slope angle of a relaxed pile
  double flow_friction_rad = 0.0;  ///< [rad] Coulomb friction angle of flowing material, <= the repose angle
  double compression_gain = 1.0;   ///< [-] artificial height per metre of contact penetration (§3.1.2)
};

}  // namespace harbour::bulk
