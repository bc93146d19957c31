#include "harbour/sim/StsCrane.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harbour/sim/Vessel.h"

#include "harbour/core/Braking.h"

namespace harbour::sim {
namespace {

// the headblock's rope segments under the trolley in each rope of the 4-rope reeving (path: drum, backreach,
// trolley, headblock, trolley, boom tip): segments 2 and 3
constexpr int kFallSegments[] = {2, 3};

}  // namespace

StsCrane::StsCrane(physics::PhysicsWorld& world, const StsCraneSettings& settings, double gantry_y_m,
                   double trolley_x_m, double spreader_z_m)
    : world_(world),
      settings_(settings),
      gantry_start_y_(gantry_y_m),
      trolley_start_x_(trolley_x_m),
      gantry_(settings.gantry_drive),
      trolley_(settings.trolley_drive) {
  // gantry: the crane's base frame, on the quay rails
  physics::BoxSettings gantry;
  gantry.mass_kg = settings.gantry_mass_kg;
  gantry.half_extents_m = {15, 10, 25};
  gantry.pose.position = {0, gantry_y_m, 0};
  gantry.collides = false;
  gantry_body_ = world.add_box(gantry);
  gantry_slider_ = world.add_slider(physics::kWorld, gantry_body_, {0, 1, 0});

  physics::BoxSettings trolley;
  trolley.mass_kg = settings.trolley_mass_kg;
  trolley.half_extents_m = {3, 4, 1};
  trolley.pose.position = {trolley_x_m, gantry_y_m, settings.trolley_rail_height_m};
  trolley.collides = false;
  trolley_body_ = world.add_box(trolley);
  trolley_slider_ = world.add_slider(gantry_body_, trolley_body_, {1, 0, 0});

  physics::BoxSettings spreader;
  spreader.mass_kg = settings.spreader_mass_kg;
  spreader.half_extents_m = settings.spreader_half_extents_m;
  spreader.surface = kSurfaceSpreader;
  spreader.pose.position = {trolley_x_m, gantry_y_m, spreader_z_m};
  spreader_ = world.add_box(spreader);

  cable_bodies_ = std::make_unique<OdeCableBodies>(
      world, std::vector<physics::BodyId>{gantry_body_, trolley_body_, spreader_});
  hoist_ = std::make_unique<cable::HoistSystem>(settings.hoist, *cable_bodies_, core::Vec3{0, 0, -9.80665});
}

double StsCrane::hoisted_load_n() const {
  double total = 0.0;
  for (int r = 0; r < hoist_->rope_count(); ++r)
    for (int s : kFallSegments)
      total += hoist_->tension(r, s);
  return total;
}

void StsCrane::step(const StsControls& c, std::span<const ContainerRef> containers, double dt_s) {
  // travel drives onto the slider motors
  const DriveOutput g = gantry_.step(c.gantry, gantry_position_m(), dt_s, c.emergency_stop);
  world_.set_slider_motor(gantry_slider_, g.velocity_mps, g.max_force_n);
  const DriveOutput t = trolley_.step(c.trolley, trolley_position_m(), dt_s, c.emergency_stop);
  world_.set_slider_motor(trolley_slider_, t.velocity_mps, t.max_force_n);

  // hoist limit switches: slow down ahead of them so the spreader stops on them (the spreader moves at half
  // the rope speed on the 2-fall ropes), and count a push into one
  const cable::ElementSettings& drum_settings =
      settings_.hoist.elements[static_cast<std::size_t>(settings_.hoist.ropes[0].path[0])];
  const double spreader_z = world_.pose(spreader_).position.z;
  const double full_speed = 0.5 * drum_settings.max_rope_speed_mps;
  const double deceleration = 0.5 * drum_settings.max_rope_acceleration_mps2;
  double lever = std::clamp(c.hoist, -1.0, 1.0);
  const double room_up = std::max(0.0, settings_.hoist_upper_limit_m - spreader_z);
  const double room_down = std::max(0.0, spreader_z - settings_.hoist_lower_limit_m);
  lever = std::min(lever, core::discrete_braking_speed(room_up, deceleration, dt_s) / full_speed);
  lever = std::max(lever, -core::discrete_braking_speed(room_down, deceleration, dt_s) / full_speed);
  const bool pushing = (c.hoist > 0.0 && room_up <= 0.01) || (c.hoist < 0.0 && room_down <= 0.01);
  if (pushing && !hoist_at_limit_) ++hoist_limit_hits_;
  hoist_at_limit_ = pushing;

  // hoist: raising reels rope in (negative pay-out); the e-stop cuts the motor and sets the brake
  const cable::DrumCommand drum{c.emergency_stop ? 0.0 : -lever, hoist_brake_fault_, !c.emergency_stop};
  hoist_->step(dt_s, {&drum, 1}, *cable_bodies_);

  // twistlocks against the container under the spreader, if any
  const core::Pose spreader = world_.pose(spreader_);
  // twistlock frame: on the underside, x along the spreader's length (the quay's y)
  core::Pose underside = spreader;
  underside.position = spreader.to_parent({0, 0, -settings_.spreader_half_extents_m.z});
  underside.rotation = spreader.rotation * core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 2);
  std::array<bool, 4> landed{};
  std::optional<physics::BodyId> landed_on;
  for (const ContainerRef& box : containers) {
    core::Pose top = world_.pose(box.body);
    top.position = top.to_parent({0, 0, box.half_extents_m.z});
    auto corners = landed_corners(underside, top, box.pocket_half_length_m, box.pocket_half_width_m,
                                  settings_.twistlocks);
    if (landed_sensor_fault_ >= 0) corners[static_cast<std::size_t>(landed_sensor_fault_)] = false;
    if (corners[0] && corners[1] && corners[2] && corners[3]) {
      landed = corners;
      landed_on = box.body;
      break;
    }
  }
  // the load hangs when the ropes carry clearly more than the empty spreader (landing pins stay pressed while
  // a locked container hangs, so "landed" alone cannot tell)
  const bool load_suspended = hoisted_load_n() > 1.3 * settings_.spreader_mass_kg * 9.80665;
  const bool was_locked = twistlocks_.locked();
  twistlocks_.update(landed, c.lock, c.unlock, load_suspended);
  if (!was_locked && twistlocks_.locked() && landed_on) {
    attachment_ = world_.attach(spreader_, *landed_on);
    locked_container_ = landed_on;
  } else if (was_locked && !twistlocks_.locked() && attachment_ >= 0) {
    world_.detach(attachment_);
    attachment_ = -1;
    locked_container_.reset();
  }
}

void StsCrane::save_state(core::StateWriter& out) const {
  out.section(0x53545343);  // "STSC"
  gantry_.save_state(out);
  trolley_.save_state(out);
  twistlocks_.save_state(out);
  hoist_->save_state(out);
  out.put(locked_container_.value_or(physics::kWorld));
  out.put(attachment_);
  out.put(hoist_brake_fault_);
  out.put(hoist_at_limit_);
  out.put(hoist_limit_hits_);
  out.put(landed_sensor_fault_);
}

void StsCrane::restore_state(core::StateReader& in) {
  in.section(0x53545343, "crane");
  gantry_.restore_state(in);
  trolley_.restore_state(in);
  twistlocks_.restore_state(in);
  hoist_->restore_state(in);
  const auto locked = in.get<physics::BodyId>();
  locked_container_ = locked == physics::kWorld ? std::nullopt : std::optional<physics::BodyId>(locked);
  in.get(attachment_);
  in.get(hoist_brake_fault_);
  in.get(hoist_at_limit_);
  in.get(hoist_limit_hits_);
  in.get(landed_sensor_fault_);
}

}  // namespace harbour::sim
