#pragma once

#include <optional>
#include <span>
#include <vector>

#include "harbour/core/StateArchive.h"
#include "harbour/machines/Machine.h"
#include "harbour/physics/PhysicsWorld.h"

namespace harbour::sim {

/// Terminal trucks serving the crane in one lane under it (settings): one waits under the crane; once a box
/// sits on its chassis, the locks are open and the spreader has risen clear, the chassis' locating cones hold
/// the box (a fixed joint: it no longer rides on friction), the truck drives off along +y and the next truck
/// of the queue drives in. Delivering trucks bring a box instead (the exercise seats it on the waiting one):
/// each drives off once its chassis is empty and the spreader clear.
struct TruckLaneSettings {
  int trucks = 0;
  double lane_x_m = 8.0;       ///< [m] chassis centre line across the quay
  double stop_y_m = 0.0;       ///< [m] chassis centre where a truck waits under the crane
  double chassis_top_m = 1.5;  ///< [m] container floor above the quay (assumed)
  double speed_mps = 5.0;      ///< [m/s] in the lane (assumed terminal speed limit)
  double acceleration_mps2 = 0.5;
  double queue_start_m = 60.0;  ///< [m] first queued truck this far behind the stop
  double queue_gap_m = 25.0;    ///< [m] truck to truck in the queue and where loaded trucks park
  double clearance_m = 1.0;     ///< [m] spreader underside above the box before the truck leaves
  bool delivering = false;      ///< the trucks bring boxes to the crane rather than take them away
};

/// The trucks as kinematic bodies (chassis and cab).
class TruckLane {
 public:
  TruckLane(physics::PhysicsWorld& world, const TruckLaneSettings& settings);

  /// Moves the trucks through the step that starts now.
  void step(double dt_s, std::span<const ContainerRef> boxes, std::optional<physics::BodyId> held,
            double attachment_bottom_z_m);
  /// The centre of a container of height `height_m` seated on the truck waiting under the crane.
  core::Vec3 load_centre(double height_m) const;
  /// Trucks that left loaded.
  int departed() const;
  double truck_y(int truck) const { return trucks_[static_cast<std::size_t>(truck)].y; }
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  enum class State : std::uint8_t { kQueued, kArriving, kWaiting, kLeaving, kParked };
  struct Truck {
    physics::BodyId body = physics::kWorld;
    double y = 0.0, speed = 0.0;
    State state = State::kQueued;
    int load_attachment = -1;  // the box held by the chassis cones
  };
  /// The box seated on the truck once the spreader is clear of it.
  /// A box stands on the truck's chassis (none: nullopt).
  const ContainerRef* on_chassis(const Truck& truck, std::span<const ContainerRef> boxes) const;
  std::optional<physics::BodyId> load(const Truck& truck, std::span<const ContainerRef> boxes,
                                      std::optional<physics::BodyId> held,
                                      double attachment_bottom_z_m) const;
  void place(const Truck& truck);

  physics::PhysicsWorld& world_;
  TruckLaneSettings settings_;
  std::vector<Truck> trucks_;
};

}  // namespace harbour::sim
