#include "harbour/machines/parts/DriveReadings.h"

#include <algorithm>
#include <cmath>

namespace harbour::sim {

namespace {
double fraction(double value, double rating) {
  return rating > 0.0 ? value / rating : 0.0;
}
}  // namespace

scene::Snapshot::Drive drive_reading(const Drive& drive, double joint_force_n) {
  const double speed = fraction(drive.reference_mps(), drive.settings().max_speed_mps);
  const double load = speed == 0.0 ? 0.0 : fraction(std::abs(joint_force_n), drive.settings().max_force_n);
  return {std::clamp(speed, -1.0, 1.0), std::min(load, 1.0)};
}

scene::Snapshot::Drive drum_reading(const cable::HoistSystem& hoist, int drum) {
  const cable::ElementSettings& d = hoist.drum_settings(drum);
  const double speed = fraction(-hoist.drum_rope_speed(drum), d.max_rope_speed_mps);
  const double load = fraction(std::abs(hoist.drum_rope_torque(drum)), d.max_torque_n_m);
  return {std::clamp(speed, -1.0, 1.0), std::min(load, 1.0)};
}

scene::Snapshot::Drive generator_reading(std::span<const scene::Snapshot::Drive> drives,
                                         std::span<const double> rated_power_w) {
  double power = 0.0, largest = 0.0;
  for (std::size_t k = 0; k < drives.size() && k < rated_power_w.size(); ++k) {
    power += std::abs(drives[k].speed * drives[k].load) * rated_power_w[k];
    largest = std::max(largest, rated_power_w[k]);
  }
  const double load = std::min(fraction(power, largest), 1.0);
  return {load, load};
}

double rated_power_w(const DriveSettings& drive) {
  return drive.max_speed_mps * drive.max_force_n;
}

double rated_power_w(const cable::ElementSettings& drum) {
  return drum.radius_m > 0.0 ? drum.max_rope_speed_mps * drum.max_torque_n_m / drum.radius_m : 0.0;
}

void publish_drives(std::span<const scene::Snapshot::Drive> readings, scene::Snapshot& s) {
  s.drive_count = static_cast<int>(std::min<std::size_t>(readings.size(), scene::kMaxDrives));
  std::copy_n(readings.begin(), s.drive_count, s.drives.begin());
}

}  // namespace harbour::sim
