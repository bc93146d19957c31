#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "harbour/machines/Machine.h"
#include "harbour/machines/parts/WheeledChassis.h"
#include "harbour/physics/PhysicsWorld.h"

namespace harbour::sim {

/// The terminal tractor's controls as shipped (data/machines/tractor.yaml declares the same): steering wheel,
/// accelerator and brake pedals, the direction selector, horn and emergency stop.
ControlTable tractor_control_table();

/// A trailer the tractor tows (settings): a roll trailer (mafi) on its gooseneck or a semi-trailer on the
/// fifth wheel; its front rests on the hitch, its rear on its own axles. Frame: its centre of mass, x
/// forward.
struct TrailerSettings {
  double mass_kg = 9000.0;                    ///< [kg] tare and payload
  core::Vec3 half_extents_m{6.1, 1.25, 0.4};  ///< a 40 ft mafi's deck, about its centre of mass
  core::Vec3 kingpin_m{5.6, 0.0, 0.3};        ///< [m] the hitch on it (trailer frame)
  WheeledChassisSettings wheels;              ///< its axles (none steered or driven), tyres and brakes
};

/// A terminal (ro-ro) tractor (settings, from data/machines/tractor.yaml): a chassis body on its wheels.
/// Frame: the chassis body's centre is its centre of mass; x forward, z up; axles and the cab given in it.
struct TractorSettings {
  double mass_kg = 8000.0;
  core::Vec3 half_extents_m{2.6, 1.25, 0.6};  ///< the chassis as a box about its centre of mass
  WheeledChassisSettings chassis;
  double steer_rate_per_s = 1.0;  ///< steering command travel per second (lock to lock in 2 s at 1)
  core::Vec3 cab_position_m{1.4, 0.4, 1.3};
  core::Vec3 eye_m{0.0, 0.0, 0.5};
  double sight_pitch_rad = -0.1;
  core::Vec3 hitch_m{-1.45, 0.0, 0.7};  ///< [m] the fifth wheel / gooseneck coupling point (chassis frame)
  double jackknife_angle_rad = 1.4;     ///< the hitch angle counted as a jack-knife
  ControlTable controls = tractor_control_table();
};

/// Where the tractor stands.
struct TractorStart {
  core::Vec3 position_m;                   ///< [m] the point under its centre of mass on the ground
  double heading_rad = 0.0;                ///< its x from world x, about z
  std::optional<TrailerSettings> trailer;  ///< coupled at the start, in line behind it
};

/// A terminal tractor on the physics world: a chassis body carried by its tyres (the shared wheeled chassis:
/// Ackermann steering on the front axle, the drivetrain on the twin-tyred rear axle, brakes on every wheel)
/// over a flat ground at quay level.
class TerminalTractor final : public Machine {
 public:
  TerminalTractor(physics::PhysicsWorld& world, const TractorSettings& settings, const TractorStart& start);

  // Machine
  const char* kind() const override { return "tractor"; }
  const ControlTable& control_table() const override { return settings_.controls; }
  void step(const Controls& controls, std::span<const ContainerRef> liftables, double dt_s) override;
  std::optional<physics::BodyId> held_item() const override { return std::nullopt; }
  double attachment_bottom_z_m() const override;
  double pendulum_length_m() const override { return 0.0; }
  std::span<const WindArea> wind_areas() const override {
    return {wind_areas_.data(), trailer_body_ == physics::kWorld ? 1u : 2u};
  }
  physics::BodyId cab_body() const override { return body_; }
  core::Vec3 eye_on_cab_body_m() const override { return settings_.cab_position_m + settings_.eye_m; }
  core::Pose cab_pose() const override;
  core::Vec3 eye_m() const override { return settings_.eye_m; }
  double sight_pitch_rad() const override { return settings_.sight_pitch_rad; }
  void describe(SceneDescription& scene) const override;
  int publish(Snapshot& snapshot, int entities) const override;
  MachineTally tally() const override;
  void drain_events(StepEvents&) override {}
  bool has_fault(MachineFault) const override { return false; }
  void inject_fault(MachineFault, int) override {}
  void clear_faults() override {}
  void hash_into(core::StateHash& hash) const override;
  void save_state(core::StateWriter& out) const override;
  void restore_state(core::StateReader& in) override;

  physics::BodyId body() const { return body_; }
  /// Speed along its heading [m/s] (+ forward).
  double forward_mps() const;
  /// The steering as it stands now [-1, 1] (it follows the wheel at the steering's rate).
  double steering() const { return steering_; }
  /// The coupled trailer's body (kWorld: none).
  physics::BodyId trailer_body() const { return trailer_body_; }
  /// The hitch angle [rad]: the trailer's heading from the tractor's (+ the trailer swung to the tractor's
  /// left); 0 without a trailer.
  double hitch_angle_rad() const;
  std::uint32_t jackknifes() const { return jackknifes_; }
  const TractorSettings& settings() const { return settings_; }

 private:
  physics::PhysicsWorld& world_;
  TractorSettings settings_;
  int steer_slot_, throttle_slot_, brake_slot_, direction_slot_, stop_slot_, horn_slot_;
  physics::BodyId body_;
  WheeledChassis chassis_;
  std::array<WindArea, 2> wind_areas_;
  physics::BodyId trailer_body_ = physics::kWorld;
  std::optional<WheeledChassis> trailer_wheels_;
  core::Vec3 trailer_half_extents_m_;
  double steering_ = 0.0;
  bool horn_ = false, jackknifed_ = false;
  std::uint32_t jackknifes_ = 0;
};

}  // namespace harbour::sim
