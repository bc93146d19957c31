#pragma once

#include <optional>
#include <span>
#include <vector>

#include "harbour/core/StateArchive.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/sim/Machine.h"

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
  /// The trucks are a team session's trailers, each towed by a tractor that another station simulates: they
  /// move only as their stations report (set_truck), are drawn from those stations' states rather than here,
  /// and a box seated on one (locks open, spreader clear) is handed over to that station.
  bool team = false;
};

/// The trucks as kinematic bodies (chassis and cab).
class TruckLane {
 public:
  TruckLane(physics::PhysicsWorld& world, const TruckLaneSettings& settings);

  /// Moves the trucks through the step that starts now.
  void step(double dt_s, std::span<const ContainerRef> boxes, std::optional<physics::BodyId> held,
            double attachment_bottom_z_m);
  /// The centre of a container of height `height_m` seated on the truck waiting under the crane (a team lane:
  /// the empty team truck nearest the stop, where it stands; nullopt while none stands within
  /// kTeamStopReach_m of the stop, still).
  std::optional<core::Vec3> load_centre(double height_m) const;
  static constexpr double kTeamStopReach_m = 5.0;
  static constexpr double kTeamStanding_mps = 0.05;

  // A team lane
  /// Team truck `truck`'s deck (its top centre, x along its length) where its station has it, moving so.
  void set_truck(int truck, const core::Pose& deck, const core::Vec3& velocity_mps,
                 const core::Vec3& angular_velocity_radps);
  core::Pose truck_pose(int truck) const;
  /// The box (index into the boxes stepped with) seated on team truck `truck` and held by its cones (-1:
  /// none): offered to the truck's station from then on.
  int seated_box(int truck) const { return team_[static_cast<std::size_t>(truck)].seated; }
  /// That box was taken over by the truck's station (TeamInput::kTakenOver): not drawn here.
  void taken_over(int truck) { team_[static_cast<std::size_t>(truck)].taken_over = true; }
  bool is_taken_over(int truck) const { return team_[static_cast<std::size_t>(truck)].taken_over; }
  int trucks() const { return static_cast<int>(trucks_.size()); }
  bool team() const { return settings_.team; }
  /// Trucks that left loaded.
  int departed() const;
  double truck_y(int truck) const { return trucks_[static_cast<std::size_t>(truck)].y; }
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  enum class State : std::uint8_t { kQueued, kArriving, kWaiting, kLeaving, kParked };
  struct Truck {
    physics::BodyId body = physics::kWorld;
    double y = 0.0, speed = 0.0;
    State state = State::kQueued;
    physics::AttachmentId load_attachment;  // the box held by the chassis cones
  };
  /// The box seated on the truck once the spreader is clear of it.
  /// A box stands on the truck's chassis (none: nullopt).
  const ContainerRef* on_chassis(const Truck& truck, std::span<const ContainerRef> boxes) const;
  std::optional<physics::BodyId> load(const Truck& truck, std::span<const ContainerRef> boxes,
                                      std::optional<physics::BodyId> held,
                                      double attachment_bottom_z_m) const;
  void place(const Truck& truck);
  void step_team(std::span<const ContainerRef> boxes, std::optional<physics::BodyId> held,
                 double attachment_bottom_z_m);
  struct TeamTruck {
    int seated = -1;  // the box its cones hold
    bool taken_over = false;
  };
  std::vector<TeamTruck> team_;  // a team lane's trucks (kept beside trucks_, whose saved layout is fixed)

  physics::PhysicsWorld& world_;
  TruckLaneSettings settings_;
  std::vector<Truck> trucks_;
};

}  // namespace harbour::sim
