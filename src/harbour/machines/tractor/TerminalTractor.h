#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "harbour/machines/parts/DrivingCab.h"
#include "harbour/machines/parts/WheeledChassis.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/sim/Machine.h"
#include "harbour/sim/MachineSetup.h"

namespace harbour::sim {

const MachineType& tractor_machine_type();  ///< machines/tractor/Type.cpp

/// A trailer the tractor tows (settings, from a data/trailers file): a roll trailer (mafi) on the gooseneck
/// or a semi-trailer on the fifth wheel. Its front rests on the coupling's plate, or on its legs when
/// dropped; its rear on its own axles. Frame: its deck's centre, x forward.
struct TrailerSettings {
  std::string id = "trailer";                 ///< the exercise's name for it (goals name it)
  double mass_kg = 9000.0;                    ///< [kg] tare and payload
  double center_of_mass_x_m = 0.0;            ///< [m] tare and payload's centre of mass along the deck
  double max_payload_kg = 60000.0;            ///< [kg] its rating
  core::Vec3 half_extents_m{6.1, 1.25, 0.4};  ///< a 40 ft mafi's deck, about its centre of mass
  core::Vec3 kingpin_m{5.6, 0.0, 0.3};        ///< [m] the hitch on it (trailer frame)
  WheeledChassisSettings wheels;              ///< its axles (none steered or driven), tyres and brakes
  /// Its front supports (skids or landing legs) as one axle of feet that do not roll (none: it never stands
  /// uncoupled); the feet's tyre is their contact with the ground.
  std::optional<WheeledChassisSettings> legs;
  /// It takes a box handed over by a team's crane, of these half extents (none: it takes none).
  std::optional<core::Vec3> receives_half_extents_m;
  /// The box it carries from the start (its payload), of these half extents, on its deck (none: empty).
  std::optional<core::Vec3> payload_half_extents_m;
  std::string payload_id = "payload";  ///< the box's ISO code, painted on it
  std::string look = "trailer.mafi";   ///< its look (data/visuals): "trailer." and its kind
};

/// The coupling (settings): a hydraulic gooseneck or lifting fifth wheel whose jaw locks the trailer's
/// kingpin and whose plate lifts the trailer's front off its legs. The plate carries the kingpin from below
/// and the jaw holds it across, both as stiff spring-dampers.
struct FifthWheelSettings {
  double lift_m = 0.3;               ///< [m] the plate's travel from down to up (hitch_m is up)
  double lift_rate_mps = 0.1;        ///< [m/s]
  double capture_m = 0.3;            ///< [m] the kingpin this near the jaw (across) locks into it
  double capture_rate_mps = 0.2;     ///< [m/s] how fast the jaw draws a captured kingpin home
  double stiffness_n_per_m = 1.0e7;  ///< the jaw's and the plate's
  double damping_ns_per_m = 2.0e5;   ///< the jaw's and the plate's
  double standstill_mps = 0.3;       ///< [m/s] a trailer is dropped only slower than this
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
  scene::CabSight sight{0.0, -0.1, 0.75};
  core::Vec3 hitch_m{-1.45, 0.0, 0.7};  ///< [m] the coupling's plate, up (chassis frame)
  FifthWheelSettings fifth_wheel;
  double jackknife_angle_rad = 1.4;  ///< the hitch angle counted as a jack-knife
  scene::ControlTable controls;      ///< the cab's controls, by label (its machine file's)
};

/// Where the tractor stands.
struct TractorStart {
  core::Vec3 position_m;                   ///< [m] the point under its centre of mass on the ground
  double heading_rad = 0.0;                ///< its x from world x, about z
  std::optional<TrailerSettings> trailer;  ///< coupled and lifted at the start, in line behind it
};

/// A terminal tractor on the physics world: a chassis body carried by its tyres (the shared wheeled chassis:
/// Ackermann steering on the front axle, the drivetrain on the twin-tyred rear axle, brakes on every wheel)
/// over a flat ground at quay level, and its trailer. The `couple` button drops a coupled trailer at a
/// standstill (the plate lowers its front onto its legs, then the jaw opens) and couples one whose kingpin
/// is within reach (the jaw locks, the plate lifts it). Its held item is the trailer while coupled.
class TerminalTractor final : public Machine {
 public:
  TerminalTractor(physics::PhysicsWorld& world, const TractorSettings& settings, const TractorStart& start);

  // Machine
  const MachineType& type() const override { return tractor_machine_type(); }
  const scene::ControlTable& control_table() const override { return settings_.controls; }
  void step(const scene::Controls& controls, std::span<const ContainerRef> liftables, double dt_s) override;
  std::optional<physics::BodyId> held_item() const override;
  std::vector<std::pair<std::string, physics::BodyId>> own_items() const override;
  void stand_on(const Ground& ground) override { ground_ = &ground; }
  double attachment_bottom_z_m() const override;
  double pendulum_length_m() const override { return 0.0; }
  double lowering_speed_mps() const override { return 0.0; }  // it lifts nothing
  std::span<const WindArea> wind_areas() const override {
    return {wind_areas_.data(), trailer_body_ == physics::kWorld ? 1u : 2u};
  }
  physics::BodyId cab_body() const override { return body_; }
  core::Vec3 eye_on_cab_body_m() const override { return settings_.cab_position_m + settings_.eye_m; }
  core::Pose cab_pose() const override;
  core::Vec3 eye_m() const override { return settings_.eye_m; }
  scene::CabSight cab_sight() const override { return settings_.sight; }
  void describe(scene::SceneDescription& scene) const override;
  int publish(scene::Snapshot& snapshot, int entities) const override;
  MachineTally tally() const override;
  std::string why_no_load() const override;
  void take_load(const core::Pose& on_trailer, double mass_kg) override;
  std::optional<physics::BodyId> load() const override;
  void drain_events(StepEvents&) override {}
  void inject_fault(MachineFault, int) override {}
  void clear_faults() override {}
  bool fault_active(MachineFault) const override { return false; }
  void hash_into(core::StateHash& hash) const override;
  void save_state(core::StateWriter& out) const override;
  void restore_state(core::StateReader& in) override;

  physics::BodyId body() const { return body_; }
  /// Its wheels: their steering geometry (the turn's reference point, the steering base).
  const WheeledChassis& chassis() const { return chassis_; }
  /// Speed along its heading [m/s] (+ forward).
  double forward_mps() const;
  /// The steering as it stands now [-1, 1] (it follows the wheel at the steering's rate).
  double steering() const { return cab_.steering(); }
  /// The coupled trailer's body (kWorld: none).
  physics::BodyId trailer_body() const { return trailer_body_; }
  /// The hitch angle [rad]: the trailer's heading from the tractor's (+ the trailer swung to the tractor's
  /// left); 0 without a trailer.
  double hitch_angle_rad() const;
  std::uint32_t jackknifes() const { return jackknifes_; }
  /// The jaw locked on the trailer's kingpin.
  bool coupled() const { return coupled_; }
  /// The plate's height [0 down, 1 up].
  double lift() const { return lift_; }
  /// The trailer's kingpin and the coupling's jaw now (world) [m].
  core::Vec3 kingpin_m() const;
  core::Vec3 jaw_m() const;
  const TractorSettings& settings() const { return settings_; }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  physics::PhysicsWorld& world_;
  TractorSettings settings_;
  FlatGround quay_;
  const Ground* ground_ = &quay_;
  struct StartPoses {
    core::Pose tractor, trailer;
  };
  TerminalTractor(physics::PhysicsWorld& world, const TractorSettings& settings, const TractorStart& start,
                  const StartPoses& poses);
  static StartPoses start_poses(const TractorSettings& settings, const TractorStart& start);
  void step_coupling(bool couple_pressed, double dt_s);
  void push_coupling();

  DrivingCab cab_;
  int couple_slot_;
  physics::BodyId body_;
  WheeledChassis chassis_;
  std::array<WindArea, 2> wind_areas_;
  physics::BodyId trailer_body_ = physics::kWorld;
  std::optional<WheeledChassis> trailer_wheels_, trailer_legs_;
  std::string trailer_id_;
  core::Vec3 trailer_half_extents_m_, trailer_kingpin_m_;
  std::string trailer_look_;
  std::optional<core::Vec3> payload_half_extents_m_;  // drawn on the deck (its mass is the trailer's)
  std::string payload_id_;
  // a box handed over onto the trailer: built parked and still, it joins the trailer when handed over
  physics::BodyId load_body_ = physics::kWorld;
  core::Vec3 load_half_extents_m_;
  bool loaded_ = false;
  double load_mass_kg_ = 0.0;
  bool jackknifed_ = false;
  bool coupled_ = false, couple_was_pressed_ = false;
  double lift_ = 0.0, lift_target_ = 0.0;
  core::Vec3 capture_offset_m_;  ///< the captured kingpin's offset from the jaw, drawn home (world, across)
  std::uint32_t jackknifes_ = 0;
};

/// A terminal tractor and where it stands (settings).
struct TractorSetup {
  TractorSettings vehicle;
  TractorStart start;

  static const MachineType& type() { return tractor_machine_type(); }
  const scene::ControlTable& controls() const { return vehicle.controls; }
  std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const;
  std::vector<cable::ReevingSettings*> reevings() { return {}; }
  std::optional<BroughtTrailer> trailer() const {
    if (!start.trailer) return std::nullopt;
    return BroughtTrailer{start.trailer->id, start.trailer->half_extents_m,
                          start.trailer->receives_half_extents_m.has_value()};
  }
};

}  // namespace harbour::sim
