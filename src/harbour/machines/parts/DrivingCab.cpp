#include "harbour/machines/parts/DrivingCab.h"

#include <algorithm>
#include <cmath>

namespace harbour::sim {
namespace {

constexpr int kReverse = 0, kNeutral = 1;  // the direction selector's positions: reverse, neutral, forward

}  // namespace

DrivingCab::DrivingCab(const scene::ControlTable& table, double steer_rate_per_s)
    : steer_slot_(table.slot("steer", scene::ControlKind::kAxis)),
      throttle_slot_(table.slot("throttle", scene::ControlKind::kAxis)),
      brake_slot_(table.slot("brake", scene::ControlKind::kAxis)),
      direction_slot_(table.slot("direction", scene::ControlKind::kSwitch)),
      parking_slot_(table.slot("parking_brake", scene::ControlKind::kSwitch)),
      stop_slot_(table.slot("emergency_stop", scene::ControlKind::kButton)),
      horn_slot_(table.slot("horn", scene::ControlKind::kButton)),
      steer_rate_per_s_(steer_rate_per_s) {}

ChassisCommand DrivingCab::step(const scene::Controls& c, double dt_s) {
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  stop_ = at(stop_slot_) != 0.0;
  horn_ = at(horn_slot_) != 0.0;
  const double most = steer_rate_per_s_ * dt_s;
  steering_ += std::clamp(at(steer_slot_) - steering_, -most, most);
  const int direction = static_cast<int>(std::lround(at(direction_slot_)));
  direction_ = direction - kNeutral;
  ChassisCommand command;
  command.steer = steering_;
  command.throttle = stop_ || direction == kNeutral ? 0.0 : at(throttle_slot_);
  command.reverse = direction == kReverse;
  command.brake = stop_ ? 1.0 : at(brake_slot_);
  parking_ = std::lround(at(parking_slot_)) == 1;
  command.parking_brake = parking_;
  return command;
}

}  // namespace harbour::sim
