#pragma once

#include <span>

#include "harbour/cable/HoistSystem.h"
#include "harbour/machines/parts/Drive.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::sim {

/// What a machine's drives publish for their sound (Snapshot::Drive): each reading's speed and load are
/// fractions of the drive's ratings, so one sound's data fits any machine's drive of its kind.

/// A speed-controlled drive: its speed reference over its rated speed, and the force (or torque) its joint
/// gave in the last step over its motor's limit; a drive at rest on its brake gives no load.
scene::Snapshot::Drive drive_reading(const Drive& drive, double joint_force_n);
/// A hoist drum: its rope speed over its rated rope speed (+ reeling in: hoisting), and the torque the ropes
/// put on it over its motor's torque limit.
scene::Snapshot::Drive drum_reading(const cable::HoistSystem& hoist, int drum);
/// The diesel generator set that powers electric drives (a variable-speed set: its speed follows its load):
/// the drives' power (speed times load, each at its rated power) over the largest drive's rated power.
scene::Snapshot::Drive generator_reading(std::span<const scene::Snapshot::Drive> drives,
                                         std::span<const double> rated_power_w);
/// A drive's rated power [W]: its rated speed times its force limit.
double rated_power_w(const DriveSettings& drive);
double rated_power_w(const cable::ElementSettings& drum);
/// Writes `readings` as the snapshot's drives (in describe()'s order; what does not fit is left out).
void publish_drives(std::span<const scene::Snapshot::Drive> readings, scene::Snapshot& snapshot);

}  // namespace harbour::sim
