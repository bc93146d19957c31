#include "harbour/sim/Trucks.h"

#include <algorithm>
#include <cmath>

#include "harbour/sim/Vessel.h"

namespace harbour::sim {
namespace {

constexpr double kChassisHalfLength_m = 6.2, kChassisHalfWidth_m = 1.25, kChassisDepth_m = 1.0;
constexpr double kCabLength_m = 3.0, kCabHeight_m = 3.2;

}  // namespace

TruckLane::TruckLane(physics::PhysicsWorld& world, const TruckLaneSettings& settings)
    : world_(world), settings_(settings) {
  for (int k = 0; k < settings.trucks; ++k) {
    Truck t;
    t.state = k == 0 ? State::kWaiting : State::kQueued;
    t.y = k == 0 ? settings.stop_y_m
                 : settings.stop_y_m - settings.queue_start_m - (k - 1) * settings.queue_gap_m;
    core::Pose pose;
    pose.position = {settings.lane_x_m, t.y, settings.chassis_top_m};
    t.body = world.add_kinematic_body(pose);
    // chassis below the container floor, the tractor's cab ahead of it
    world.add_box_shape(t.body, {kChassisHalfWidth_m, kChassisHalfLength_m, kChassisDepth_m / 2},
                        {core::Mat3::identity(), {0, 0, -kChassisDepth_m / 2}}, kSurfaceTruck);
    const double cab_floor = 0.5 - settings.chassis_top_m;
    world.add_box_shape(t.body, {kChassisHalfWidth_m, kCabLength_m / 2, kCabHeight_m / 2},
                        {core::Mat3::identity(),
                         {0, kChassisHalfLength_m + 0.5 + kCabLength_m / 2, cab_floor + kCabHeight_m / 2}},
                        kSurfaceTruck);
    trucks_.push_back(t);
  }
}

core::Vec3 TruckLane::load_centre(double height_m) const {
  return {settings_.lane_x_m, settings_.stop_y_m, settings_.chassis_top_m + height_m / 2};
}

int TruckLane::departed() const {
  return static_cast<int>(std::count_if(trucks_.begin(), trucks_.end(), [](const Truck& t) {
    return t.state == State::kLeaving || t.state == State::kParked;
  }));
}

const ContainerRef* TruckLane::on_chassis(const Truck& truck, std::span<const ContainerRef> boxes) const {
  for (const ContainerRef& box : boxes) {
    const core::Vec3 p = world_.pose(box.body).position;
    if (std::abs(p.x - settings_.lane_x_m) < kChassisHalfWidth_m &&
        std::abs(p.y - truck.y) < kChassisHalfLength_m &&
        std::abs(p.z - box.half_extents_m.z - settings_.chassis_top_m) < 0.05)
      return &box;
  }
  return nullptr;
}

std::optional<physics::BodyId> TruckLane::load(const Truck& truck, std::span<const ContainerRef> boxes,
                                               std::optional<physics::BodyId> held,
                                               double attachment_bottom_z_m) const {
  if (held) return std::nullopt;
  const ContainerRef* box = on_chassis(truck, boxes);
  if (!box) return std::nullopt;
  const double top = world_.pose(box->body).position.z + box->half_extents_m.z;
  if (attachment_bottom_z_m > top + settings_.clearance_m) return box->body;
  return std::nullopt;
}

void TruckLane::place(const Truck& truck) {
  core::Pose pose;
  pose.position = {settings_.lane_x_m, truck.y, settings_.chassis_top_m};
  world_.set_kinematic_motion(truck.body, pose, {0, truck.speed, 0}, {});
}

void TruckLane::step(double dt_s, std::span<const ContainerRef> boxes, std::optional<physics::BodyId> held,
                     double attachment_bottom_z_m) {
  const double a = settings_.acceleration_mps2;
  for (std::size_t k = 0; k < trucks_.size(); ++k) {
    Truck& t = trucks_[k];
    switch (t.state) {
      case State::kQueued:
      case State::kParked:
        t.speed = 0.0;
        break;
      case State::kWaiting:
        t.speed = 0.0;
        if (settings_.delivering) {
          // its box lifted off and the spreader clear of the chassis: it leaves empty
          const bool clear = attachment_bottom_z_m > settings_.chassis_top_m + settings_.clearance_m;
          if (!on_chassis(t, boxes) && clear) {
            t.state = State::kLeaving;
            if (k + 1 < trucks_.size()) trucks_[k + 1].state = State::kArriving;
          }
        } else if (const auto box = load(t, boxes, held, attachment_bottom_z_m)) {
          t.load_attachment = world_.attach(*box, t.body);
          t.state = State::kLeaving;
          if (k + 1 < trucks_.size()) trucks_[k + 1].state = State::kArriving;
        }
        break;
      case State::kArriving: {
        // speed limit, and brake so as to stop at the stop line
        const double remaining = settings_.stop_y_m - t.y;
        t.speed =
            std::min({settings_.speed_mps, t.speed + a * dt_s, std::sqrt(2 * a * std::max(0.0, remaining))});
        if (remaining <= 1e-3 || t.speed <= 0.0) {
          t.y = settings_.stop_y_m;
          t.speed = 0.0;
          t.state = State::kWaiting;
        }
        break;
      }
      case State::kLeaving: {
        const double park =
            settings_.stop_y_m + settings_.queue_start_m + static_cast<double>(k) * settings_.queue_gap_m;
        const double remaining = park - t.y;
        t.speed =
            std::min({settings_.speed_mps, t.speed + a * dt_s, std::sqrt(2 * a * std::max(0.0, remaining))});
        if (remaining <= 1e-3) {
          t.speed = 0.0;
          t.state = State::kParked;
        }
        break;
      }
    }
    place(t);
    t.y += t.speed * dt_s;  // where the step leaves it
  }
}

void TruckLane::save_state(core::StateWriter& out) const {
  out.section(0x54524B32);  // "TRK2": trucks with their load attachments
  out.put(trucks_);
}

void TruckLane::restore_state(core::StateReader& in) {
  in.section(0x54524B32, "trucks");
  in.get(trucks_, static_cast<std::int64_t>(trucks_.size()));
}

}  // namespace harbour::sim
