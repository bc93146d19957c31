#pragma once

#include <string>

namespace harbour::bulk {

/// A granular bulk material (settings; immutable while simulating).
struct Material {
  std::string name;
  double bulk_density_kg_m3 = 0.0;   ///< [kg/m^3] loose bulk density
  double angle_of_repose_rad = 0.0;  ///< [rad] critical slope angle of a relaxed pile
  double flow_fraction =
      0.5;  ///< [-] the paper's c: share of a slope excess moved per relaxation step, (0, 1)
  double compression_gain = 1.0;  ///< [-] artificial height per metre of contact penetration (§3.1.2)
};

}  // namespace harbour::bulk
