#include "harbour/sim/Trucks.h"

#include <algorithm>
#include <cmath>

#include "harbour/scene/Surface.h"

namespace harbour::sim {
namespace {

constexpr double kChassisHalfLength_m = 6.2, kChassisHalfWidth_m = 1.25, kChassisDepth_m = 1.0;
constexpr double kCabLength_m = 3.0, kCabHeight_m = 3.2;

}  // namespace

TruckLane::TruckLane(physics::PhysicsWorld& world, const TruckLaneSettings& settings)
    : world_(world), settings_(settings) {
  if (settings.team) {
    // each a trailer's deck, x along it, parked out of the way until its station says where it is
    for (int k = 0; k < settings.trucks; ++k) {
      Truck t;
      core::Pose pose;
      pose.position = {settings.lane_x_m, settings.stop_y_m - 1000.0 - 30.0 * k, settings.chassis_top_m};
      t.body = world.add_kinematic_body(pose);
      world.add_box_shape(t.body, {kChassisHalfLength_m, kChassisHalfWidth_m, kChassisDepth_m / 2},
                          {core::Mat3::identity(), {0, 0, -kChassisDepth_m / 2}}, scene::kSurfaceTruck);
      trucks_.push_back(t);
    }
    team_.resize(trucks_.size());
    return;
  }
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
                        {core::Mat3::identity(), {0, 0, -kChassisDepth_m / 2}}, scene::kSurfaceTruck);
    const double cab_floor = 0.5 - settings.chassis_top_m;
    world.add_box_shape(t.body, {kChassisHalfWidth_m, kCabLength_m / 2, kCabHeight_m / 2},
                        {core::Mat3::identity(),
                         {0, kChassisHalfLength_m + 0.5 + kCabLength_m / 2, cab_floor + kCabHeight_m / 2}},
                        scene::kSurfaceTruck);
    trucks_.push_back(t);
  }
}

std::optional<core::Vec3> TruckLane::load_centre(double height_m) const {
  if (!settings_.team)
    return core::Vec3{settings_.lane_x_m, settings_.stop_y_m, settings_.chassis_top_m + height_m / 2};
  std::optional<core::Vec3> nearest;
  double nearest_m = kTeamStopReach_m;
  for (std::size_t k = 0; k < trucks_.size(); ++k) {
    if (team_[k].seated >= 0) continue;
    const core::Pose deck = world_.pose(trucks_[k].body);
    const double off = std::hypot(deck.position.x - settings_.lane_x_m, deck.position.y - settings_.stop_y_m);
    if (off < nearest_m && core::length(world_.linear_velocity(trucks_[k].body)) < kTeamStanding_mps) {
      nearest_m = off;
      nearest = deck.to_parent({0, 0, height_m / 2});
    }
  }
  return nearest;
}

void TruckLane::set_truck(int truck, const core::Pose& deck, const core::Vec3& velocity_mps,
                          const core::Vec3& angular_velocity_radps) {
  world_.set_kinematic_motion(trucks_[static_cast<std::size_t>(truck)].body, deck, velocity_mps,
                              angular_velocity_radps);
}

core::Pose TruckLane::truck_pose(int truck) const {
  return world_.pose(trucks_[static_cast<std::size_t>(truck)].body);
}

void TruckLane::step_team(std::span<const ContainerRef> boxes, std::optional<physics::BodyId> held,
                          double attachment_bottom_z_m) {
  // a box set down square on a deck, the locks open and the spreader risen clear: the cones hold it
  if (held) return;
  for (std::size_t k = 0; k < trucks_.size(); ++k) {
    if (team_[k].seated >= 0) continue;
    const core::Pose deck = world_.pose(trucks_[k].body);
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      const core::Pose box = world_.pose(boxes[b].body);
      const core::Vec3 on = deck.to_local(box.position);
      if (std::abs(on.x) >= kChassisHalfLength_m || std::abs(on.y) >= kChassisHalfWidth_m ||
          std::abs(on.z - boxes[b].half_extents_m.z) >= 0.05)
        continue;
      if (attachment_bottom_z_m <= box.position.z + boxes[b].half_extents_m.z + settings_.clearance_m)
        continue;
      trucks_[k].load_attachment = world_.attach(boxes[b].body, trucks_[k].body);
      team_[k].seated = static_cast<int>(b);
      break;
    }
  }
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
  if (settings_.team) {
    step_team(boxes, held, attachment_bottom_z_m);
    return;
  }
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

template <typename Self, typename Archive>
void TruckLane::archive(Self& self, Archive& ar) {
  ar.section(0x54524B32, "trucks");  // "TRK2": trucks with their load attachments
  ar.sized(self.trucks_);
  if (!self.settings_.team) return;
  ar.section(0x54524B54, "team trucks");  // "TRKT": a team lane's seated and taken-over boxes
  ar.sized(self.team_);
}

void TruckLane::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void TruckLane::restore_state(core::StateReader& in) {
  archive(*this, in);
}

}  // namespace harbour::sim
