#include "harbour/machines/mhc/MobileHarbourCrane.h"

#include "harbour/machines/parts/DriveReadings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "harbour/core/Units.h"
#include "harbour/machines/parts/KineticDamping.h"

namespace harbour::sim {
namespace {

constexpr double kG = core::kStandardGravity;
constexpr double kRestingShare = 0.5;  // ropes carrying less of the grab than this: it rests on something
constexpr double kShutOpening = 0.05;  // shells this little open count as shut (their play on the ropes)
constexpr double kShareGain = 0.5;     // holding winch speed (share of full) per unit of excess load share
// reeving bodies, as the constructor maps them (kBlock: the grab's head, or the hook block)
constexpr int kHouse = 0, kBoom = 1, kBlock = 2, kGrabLower = 3;
constexpr int kSlingLegs = 4;          // drawn from the hook to a slung load's top corners
constexpr double kSlungResting = 0.5;  // a slung load the ropes carry less of than this rests (unslinging)

core::Mat3 yaw(double rad) {
  return core::Mat3::rotation({0, 0, 1}, rad);
}

// the boom's orientation: x from foot to head, raised `angle` above the house's horizontal x
core::Mat3 boom_rotation(double slew_rad, double angle_rad) {
  return yaw(slew_rad) * core::Mat3::rotation({0, 1, 0}, -angle_rad);
}

// segments joining a mount on body `from` to one on a body in `to`
std::vector<std::pair<int, int>> segments_between(const cable::ReevingSettings& reeving, int from,
                                                  std::initializer_list<int> to) {
  std::vector<std::pair<int, int>> found;
  const auto body = [&](int element) {
    return reeving.elements[static_cast<std::size_t>(element)].mount.body;
  };
  for (std::size_t r = 0; r < reeving.ropes.size(); ++r) {
    const std::vector<int>& path = reeving.ropes[r].path;
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
      const int a = body(path[k]), b = body(path[k + 1]);
      for (const int t : to)
        if ((a == from && b == t) || (b == from && a == t))
          found.emplace_back(static_cast<int>(r), static_cast<int>(k));
    }
  }
  return found;
}

const cable::ElementSettings& first_drum(const cable::ReevingSettings& reeving) {
  for (const cable::ElementSettings& e : reeving.elements)
    if (e.kind == cable::ElementKind::kDrum) return e;
  throw std::invalid_argument("reeving '" + reeving.name + "' has no drum");
}

constexpr const char* kMhcIndicators[] = {
    "slew_deg",        "boom_angle_deg",    "radius_m",     "load_t",   "capacity_t",
    "utilisation",     "limiter_stop",      "grab_opening", "pad_1_kn", "pad_2_kn",
    "pad_3_kn",        "pad_4_kn",          "horn",         "slung",    "lamp_brake_fault",
    "grab_material_t", "lamp_limiter_fault"};

}  // namespace

PadForces pad_forces(double down_n, const core::Vec3& moment_nm, double a_m, double b_m, double yaw_rad) {
  // pads push up F_i at p_i: sum F_i = down, sum F_i y_i = -M_x, sum F_i x_i = M_y; the plane share
  // F_i = down/4 + x_i M_y / (4 a^2) - y_i M_x / (4 b^2) in the pads' frame
  const core::Vec3 m = yaw(-yaw_rad) * moment_nm;
  const double sx[] = {1, -1, -1, 1}, sy[] = {1, 1, -1, -1};
  PadForces f{};
  for (std::size_t i = 0; i < 4; ++i) {
    const double x = sx[i] * a_m, y = sy[i] * b_m;
    f[i] = down_n / 4 + x * m.y / (4 * a_m * a_m) - y * m.x / (4 * b_m * b_m);
  }
  return f;
}

MobileHarbourCrane::MobileHarbourCrane(physics::PhysicsWorld& world, const MhcSettings& settings,
                                       const MhcStart& start)
    : world_(world),
      settings_(settings),
      start_on_hook_(start.on_hook),
      slew_slot_(settings.controls.slot("slew", scene::ControlKind::kAxis)),
      luff_slot_(settings.controls.slot("luff", scene::ControlKind::kAxis)),
      hoist_slot_(settings.controls.slot("hoist", scene::ControlKind::kAxis)),
      grab_slot_(settings.controls.slot("grab", scene::ControlKind::kAxis)),
      sling_slot_(settings.controls.find("sling")),
      stop_slot_(settings.controls.slot("emergency_stop", scene::ControlKind::kButton)),
      horn_slot_(settings.controls.slot("horn", scene::ControlKind::kButton)),
      position_(start.position_m),
      slew_drive_(settings.slew_drive),
      luff_limits_(settings.boom_min_angle_rad, settings.boom_max_angle_rad),
      hoist_limits_(settings.hoist_lower_limit_m, settings.hoist_upper_limit_m),
      grab_limits_(0.0, 1.0),
      house_origin_in_body_m_(settings.house_com_m * -1.0),
      boom_head_in_body_m_{0.5 * settings.boom_length_m, 0.0, 0.0},
      slew_(start.slew_rad) {
  if (start.on_hook && !settings.hook) throw std::invalid_argument("this MHC has no hook block");
  if (start.on_hook && sling_slot_ < 0)
    throw std::invalid_argument("an MHC on its hook needs a 'sling' button");
  if (on_hook()) settings_.capacity_chart = settings.hook->capacity_chart;
  const cable::ReevingSettings& hoisting = on_hook() ? settings.hook->hoist : settings.hoist;
  grab_falls_ = segments_between(hoisting, kBoom, {kBlock, kGrabLower});
  for (const auto& [rope, segment] : segments_between(settings.luffing, kHouse, {kBoom})) {
    const std::vector<int>& path = settings.luffing.ropes[static_cast<std::size_t>(rope)].path;
    const int far = path[static_cast<std::size_t>(segment) + 1];
    luff_falls_.push_back(
        {rope, segment, settings.luffing.elements[static_cast<std::size_t>(far)].mount.body == kBoom});
  }
  const auto tackle =
      on_hook() ? std::vector<std::pair<int, int>>{} : segments_between(hoisting, kBlock, {kGrabLower});
  for (std::size_t r = 0; r < hoisting.ropes.size(); ++r)
    closing_rope_.push_back(std::any_of(tackle.begin(), tackle.end(),
                                        [&](const auto& f) { return f.first == static_cast<int>(r); }));
  const int closing_ropes = static_cast<int>(std::count(closing_rope_.begin(), closing_rope_.end(), true));
  tackle_falls_ = closing_ropes > 0 ? static_cast<int>(tackle.size()) / closing_ropes : 1;
  const auto holding_falls = std::count_if(grab_falls_.begin(), grab_falls_.end(), [&](const auto& f) {
    return !closing_rope_[static_cast<std::size_t>(f.first)];
  });
  const int holding_ropes = static_cast<int>(hoisting.ropes.size()) - closing_ropes;
  if (holding_falls > 0 && holding_ropes > 0)
    holding_falls_per_rope_ = static_cast<double>(holding_falls) / holding_ropes;
  const core::Mat3 house_rotation = yaw(start.slew_rad);
  physics::BoxSettings house;
  house.mass_kg = settings.house_mass_kg;
  house.half_extents_m = settings.house_half_extents_m;
  house.pose = {house_rotation, position_ + house_rotation * settings.house_com_m};
  house.collides = false;
  house_ = world.add_box(house);
  slew_hinge_ = world.add_hinge(physics::kWorld, house_, position_, {0, 0, 1});

  const core::Vec3 foot = position_ + house_rotation * settings.boom_foot_m;
  const core::Mat3 boom_rotation_now = boom_rotation(start.slew_rad, start.boom_rad);
  physics::BoxSettings boom;
  boom.mass_kg = settings.boom_mass_kg;
  boom.half_extents_m = {0.5 * settings.boom_length_m, settings.boom_half_width_m,
                         settings.boom_half_width_m};
  boom.pose = {boom_rotation_now, foot + boom_rotation_now * core::Vec3{0.5 * settings.boom_length_m, 0, 0}};
  boom.collides = false;
  boom_ = world.add_box(boom);
  boom_hinge_ = world.add_hinge(house_, boom_, foot, house_rotation * core::Vec3{0, 1, 0});

  // under the boom head: the grab's head and its lower block on the shells' linkage, or the hook block
  const core::Vec3 head = boom.pose.to_parent(boom_head_in_body_m_);
  physics::BoxSettings block;
  block.mass_kg = on_hook() ? settings.hook->block_mass_kg : settings.grab_head_mass_kg;
  block.half_extents_m = block_half_extents_m();
  block.pose = {house_rotation, {head.x, head.y, start.hanging_z_m}};
  block.collides = on_hook();  // the hook block lands on what it is lowered onto
  block_ = world.add_box(block);
  std::vector<physics::BodyId> hoisted{house_, boom_, block_};
  if (!on_hook()) {
    physics::BoxSettings grab_lower;
    grab_lower.mass_kg = settings.grab_lower_mass_kg;
    grab_lower.half_extents_m = settings.grab_lower_half_extents_m;
    grab_lower.pose = {house_rotation, {head.x, head.y, start.hanging_z_m - settings.grab_open_gap_m}};
    grab_lower_ = world.add_box(grab_lower);
    hoisted.push_back(grab_lower_);
    // the shells' linkage: the lower block slides up towards the head (shutting) between two stops
    grab_slider_ = world.add_slider(block_, grab_lower_, {0, 0, 1});
    world.set_slider_limits(grab_slider_, 0.0, settings.grab_open_gap_m - settings.grab_closed_gap_m);
  }

  luffing_bodies_ = std::make_unique<OdeCableBodies>(
      world, std::vector<physics::BodyId>{house_, boom_},
      std::vector<core::Vec3>{house_origin_in_body_m_, boom_head_in_body_m_});
  luffing_ = std::make_unique<cable::HoistSystem>(settings.luffing, *luffing_bodies_, core::Vec3{0, 0, -kG});
  std::vector<core::Vec3> origins{house_origin_in_body_m_, boom_head_in_body_m_};
  origins.resize(hoisted.size());
  hoist_bodies_ = std::make_unique<OdeCableBodies>(world, hoisted, origins);
  hoist_ = std::make_unique<cable::HoistSystem>(hoisting, *hoist_bodies_, core::Vec3{0, 0, -kG});
  wind_areas_.clear();
  wind_areas_.push_back({block_, block_half_extents_m(), true});
  if (!on_hook()) wind_areas_.push_back({grab_lower_, settings.grab_lower_half_extents_m, true});
  wind_areas_.push_back({house_, settings.house_half_extents_m});
  last_hinge_angle_ = world.hinge_angle(slew_hinge_);
  if (!on_hook()) {
    // the grab as a bulk tool: nine points over the shells' underside (moved with the jaws by update_tool),
    // the jaw tips at its centre; its bite closes in the time the closing ropes take to shut it resting on
    // material (the holding winch following)
    const core::Vec3& h = settings.grab_lower_half_extents_m;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        shell_points_[static_cast<std::size_t>(3 * a + b)] = {(a - 1) * h.x, (b - 1) * h.y, -h.z};
    tool_.body = grab_lower_;
    tool_.contact_points_m = shell_points_;
    tool_.grab = settings.grab;
    tool_.grab.closing_time_s = std::max(tackle_falls_ - 1, 1) *
                                (settings.grab_open_gap_m - settings.grab_closed_gap_m) /
                                first_drum(settings.hoist).max_rope_speed_mps;
  }
  settle();
  update_tool();
}

const core::Vec3& MobileHarbourCrane::block_half_extents_m() const {
  return on_hook() ? settings_.hook->block_half_extents_m : settings_.grab_head_half_extents_m;
}

void MobileHarbourCrane::update_tool() {
  if (on_hook()) return;
  const core::Pose lower = world_.pose(grab_lower_);
  tool_.jaws = {lower.rotation, lower.to_parent({0, 0, -settings_.grab_lower_half_extents_m.z})};
  tool_.jaws_velocity_mps =
      world_.point_velocity(grab_lower_, {0, 0, -settings_.grab_lower_half_extents_m.z});
  // shut within a centimetre is shut: the shells on their stop do not leak
  const double opening = grab_opening() * settings_.grab.max_opening_m;
  tool_.opening_m = opening < 0.01 ? 0.0 : opening;
  // the shells' underside follows the jaw tips: its outer points come in as the jaws close (onto the
  // material they are cutting away, so the grab sinks as it cuts), out to the block's sides when open
  const double half_span = std::min(0.5 * opening, settings_.grab_lower_half_extents_m.x);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      shell_points_[static_cast<std::size_t>(3 * a + b)].x = (a - 1) * half_span;
}

void MobileHarbourCrane::step_braked(double dt_s) {
  const std::array<cable::DrumCommand, 2> braked{};
  const cable::DrumCommand luff_braked{};
  world_.set_hinge_motor(slew_hinge_, 0.0, settings_.slew_drive.brake_force_n);
  luffing_->step(dt_s, {&luff_braked, 1}, *luffing_bodies_);
  hoist_->step(dt_s, braked, *hoist_bodies_);
  world_.step(dt_s);
}

std::vector<physics::BodyId> MobileHarbourCrane::settled_bodies() const {
  std::vector<physics::BodyId> bodies{house_, boom_, block_};
  if (!on_hook()) bodies.push_back(grab_lower_);
  return bodies;
}

void MobileHarbourCrane::stop_rope_waves() {
  luffing_->stop_transverse_motion();
  hoist_->stop_transverse_motion();
}

void MobileHarbourCrane::settle() {
  // at rest, drums braked: the ropes stretch to their static load in a few bounces instead of the grab and
  // boom dropping on unstretched ropes when the exercise starts
  const std::vector<physics::BodyId> bodies = settled_bodies();
  constexpr double kDt = 0.001;
  settle_by_kinetic_damping(
      world_, bodies, kSettleSteps, [&] { step_braked(kDt); }, [&] { stop_rope_waves(); });
  static_cast<void>(luffing_->take_events());  // the settling's rope events are not the exercise's
  static_cast<void>(hoist_->take_events());
  last_hinge_angle_ = world_.hinge_angle(slew_hinge_);
}

void MobileHarbourCrane::settle_at_rest() {
  // the load's pendulum swings down from where it was built; just past the peak of the swing's kinetic energy
  // it passes plumb: everything is stopped there (a quarter of the pendulum's period, 2.8 s on the hook),
  // twice (the second swing starts from what the first stop missed), and the bounce left is settled as before
  const std::vector<physics::BodyId> bodies = settled_bodies();
  const physics::BodyId hanging = on_hook() ? block_ : grab_lower_;
  constexpr double kDt = 0.001;
  for (int swing_down = 0; swing_down < 2; ++swing_down) {
    double highest = 0.0;
    for (int k = 0; k < kPlumbSteps; ++k) {
      step_braked(kDt);
      const core::Vec3 v = world_.linear_velocity(hanging);
      const double swing = world_.mass_kg(hanging) * (v.x * v.x + v.y * v.y);
      highest = std::max(highest, swing);
      if (swing < kPastPeak * highest) break;
    }
    for (const physics::BodyId b : bodies)
      world_.stop_body(b);
    stop_rope_waves();
  }
  settle();
}

double MobileHarbourCrane::track_slew() {
  // the hinge reads (-pi, pi]: add the change since the last step, unwrapped
  const double angle = world_.hinge_angle(slew_hinge_);
  double change = angle - last_hinge_angle_;
  if (change > std::numbers::pi) change -= 2 * std::numbers::pi;
  if (change < -std::numbers::pi) change += 2 * std::numbers::pi;
  last_hinge_angle_ = angle;
  slew_ += change;
  return slew_;
}

double MobileHarbourCrane::boom_angle_rad() const {
  const core::Vec3 along = world_.pose(boom_).rotation.column(0);
  return std::atan2(along.z, std::hypot(along.x, along.y));
}

core::Vec3 MobileHarbourCrane::boom_head_m() const {
  return world_.pose(boom_).to_parent(boom_head_in_body_m_);
}

core::Vec3 MobileHarbourCrane::suspension_point_m() const {
  core::Vec3 sum;
  double top = -std::numeric_limits<double>::infinity();
  std::array<core::Vec3, 2> ends;
  for (const auto& [rope, segment] : grab_falls_) {
    hoist_->polyline(rope, segment, ends);
    const core::Vec3& upper = ends[0].z > ends[1].z ? ends[0] : ends[1];
    sum += upper;
    top = std::max(top, upper.z);
  }
  const double n = static_cast<double>(grab_falls_.size());
  return {sum.x / n, sum.y / n, top};
}

double MobileHarbourCrane::radius_m() const {
  const core::Vec3 head = boom_head_m();
  return std::hypot(head.x - position_.x, head.y - position_.y);
}

MobileHarbourCrane::FallPulls MobileHarbourCrane::fall_pulls() const {
  // the falls below the boom head, their vertical share; the holding ropes' part of it
  FallPulls pulls;
  std::array<core::Vec3, 2> ends;
  for (const auto& [rope, segment] : grab_falls_) {
    hoist_->polyline(rope, segment, ends);
    const core::Vec3 d = ends[1] - ends[0];
    const double length = std::sqrt(dot(d, d));
    const double up = hoist_->tension(rope, segment) * (length > 0 ? std::abs(d.z) / length : 1.0);
    pulls.total_n += up;
    if (!closing_rope_[static_cast<std::size_t>(rope)]) pulls.holding_n += up;
  }
  return pulls;
}

double MobileHarbourCrane::hoisted_load_n() const {
  return fall_pulls().total_n;
}

double MobileHarbourCrane::capacity_t() const {
  const std::vector<CapacityPoint>& chart = settings_.capacity_chart;
  const double r = radius_m();
  if (r <= chart.front().radius_m) return chart.front().capacity_t;
  for (std::size_t k = 1; k < chart.size(); ++k)
    if (r <= chart[k].radius_m) {
      const double s = (r - chart[k - 1].radius_m) / (chart[k].radius_m - chart[k - 1].radius_m);
      return chart[k - 1].capacity_t + s * (chart[k].capacity_t - chart[k - 1].capacity_t);
    }
  return 0.0;  // beyond the chart nothing may hang
}

double MobileHarbourCrane::utilisation() const {
  const double capacity = capacity_t();
  const double load_t = limiter_load_n_ / kG / 1000.0;
  return capacity > 0.0 ? load_t / capacity : (load_t > 0.0 ? 1e9 : 0.0);
}

double MobileHarbourCrane::grab_opening() const {
  if (on_hook()) return 0.0;
  const double travel = settings_.grab_open_gap_m - settings_.grab_closed_gap_m;
  return std::clamp(1.0 - world_.slider_position(grab_slider_) / travel, 0.0, 1.0);
}

PadForces MobileHarbourCrane::pad_forces_n() const {
  // the house's load through the slewing ring (the opposite of the hinge's push on it), plus the
  // undercarriage's own weight on the axis
  const physics::PhysicsWorld::Wrench on_house = world_.hinge_reaction(slew_hinge_, position_);
  return pad_forces(on_house.force.z + settings_.undercarriage_mass_kg * kG, on_house.moment * -1.0,
                    settings_.pad_half_spread_x_m, settings_.pad_half_spread_y_m, 0.0);
}

double MobileHarbourCrane::luffing_rope_per_rad() const {
  // each fall's length change as the boom turns about its foot (the raising axis), summed over the falls
  const core::Pose house = world_.pose(house_);
  const core::Vec3 foot = house.to_parent(house_origin_in_body_m_ + settings_.boom_foot_m);
  const core::Vec3 raise_axis = house.rotation * core::Vec3{0, -1, 0};
  double rope_per_rad = 0.0;
  std::array<core::Vec3, 2> ends;
  for (const LuffFall& fall : luff_falls_) {
    luffing_->polyline(fall.rope, fall.segment, ends);
    const core::Vec3 d = ends[1] - ends[0];
    const double length = std::sqrt(dot(d, d));
    const core::Vec3 on_boom = fall.end_on_boom ? ends[1] : ends[0];
    const core::Vec3 moves = cross(raise_axis, on_boom - foot);
    rope_per_rad += length > 0 ? dot(d, moves) / length * (fall.end_on_boom ? 1.0 : -1.0) : 0.0;
  }
  return rope_per_rad;
}

double MobileHarbourCrane::luffing_radius_rate_mps() const {
  const double per_rad = std::max(std::abs(luffing_rope_per_rad()), 1.0);
  return settings_.boom_length_m * std::sin(boom_angle_rad()) *
         first_drum(settings_.luffing).max_rope_speed_mps / per_rad;
}

core::Vec3 MobileHarbourCrane::load_position_m() const {
  if (!on_hook()) return world_.pose(grab_lower_).position;
  return world_.pose(slung_ != physics::kWorld ? slung_ : block_).position;
}

std::optional<physics::BodyId> MobileHarbourCrane::held_item() const {
  if (slung_ == physics::kWorld) return std::nullopt;
  return slung_;
}

MachineTally MobileHarbourCrane::tally() const {
  const core::Vec3 head = suspension_point_m(), grab = load_position_m();
  // the speeds the operator drives the boom head at: the slewing drive's reference round the axis, the
  // luffing winch's along the radius (the boom's bounce on its ropes is the machine's, not the operator's)
  MachineTally t;
  t.limiter_trips = limiter_trips_;
  t.pad_lift_offs = pad_lift_offs_;
  t.limit_hits = luff_limits_.hits() + hoist_limits_.hits();
  t.swing_m = {grab.x - head.x, grab.y - head.y, 0.0};
  t.axes = {AxisSpeed{"slew", slew_drive_.reference_mps() * radius_m()}, AxisSpeed{"luff", luff_speed_mps_}};
  for (int drum = 0; drum < hoist_->drum_count(); ++drum)
    t.hoist_power_w += std::max(0.0, hoist_->drum_power_w(drum));
  return t;
}

Telemetry MobileHarbourCrane::telemetry() const {
  const MachineTally t = tally();
  return {core::length(t.swing_m), hoist_->highest_tension_n(), t.axes};
}

double MobileHarbourCrane::luffing_tension_n() const {
  return luffing_->tension(0, 1);
}

double MobileHarbourCrane::attachment_bottom_z_m() const {
  if (on_hook()) return world_.pose(block_).position.z - block_half_extents_m().z;
  return world_.pose(grab_lower_).position.z - settings_.grab_lower_half_extents_m.z;
}

double MobileHarbourCrane::pendulum_length_m() const {
  return suspension_point_m().z - world_.pose(block_).position.z;
}

double MobileHarbourCrane::lowering_speed_mps() const {
  // the holding drum (the first) pays out over its ropes' falls to the hook block or the grab
  return hoist_->drum_rope_speed(0) / holding_falls_per_rope_;
}

core::Vec3 MobileHarbourCrane::eye_on_cab_body_m() const {
  return house_origin_in_body_m_ + settings_.cab_position_m + settings_.eye_m;
}

core::Pose MobileHarbourCrane::cab_pose() const {
  const core::Pose house = world_.pose(house_);
  return {house.rotation, house.to_parent(house_origin_in_body_m_ + settings_.cab_position_m)};
}

void MobileHarbourCrane::step(const scene::Controls& raw, std::span<const ContainerRef> liftables,
                              double dt_s) {
  const scene::Controls c = settings_.controls.in_range(raw);
  const auto at = [&](int slot) { return c.value[static_cast<std::size_t>(slot)]; };
  const bool stop = at(stop_slot_) != 0.0;
  horn_ = at(horn_slot_) != 0.0;

  // slewing: a speed-controlled drive on the slewing ring's hinge
  const DriveOutput slew = slew_drive_.step(at(slew_slot_), track_slew(), dt_s, stop);
  world_.set_hinge_motor(slew_hinge_, slew.velocity_mps, slew.max_force_n);

  // load-moment limiter on the low-passed load (the ropes' bounce filtered out): moves that raise the moment
  // (luffing out, hoisting) slow above the chart's slow-down share and stop at the chart; a trip counts once
  // until the moment is back below the slow-down share
  const FallPulls pulls = fall_pulls();
  limiter_load_n_ += (pulls.total_n - limiter_load_n_) * std::min(1.0, dt_s / settings_.limiter_filter_s);
  const double u = utilisation();
  const double allowed = std::clamp((1.0 - u) / (1.0 - settings_.limiter_slow_from), 0.0, 1.0);
  double luff = at(luff_slot_), hoist = at(hoist_slot_);
  const bool raising_moment = luff < 0.0 || hoist > 0.0;
  // once stopped, the cut-off holds until the operator lets the lever back or the moment falls below the
  // slow-down share (the load's bounce does not let the boom creep out)
  limiter_stopping_ =
      raising_moment && (allowed == 0.0 || (limiter_stopping_ && u >= settings_.limiter_slow_from));
  if (limiter_stopping_) {
    if (limiter_armed_) ++limiter_trips_;
    limiter_armed_ = false;
  }
  if (u < settings_.limiter_slow_from) limiter_armed_ = true;
  // failed, it still counts and warns (the stop lamp and alarm) but lets every motion run at full speed
  const double share = limiter_fault_ ? 1.0 : limiter_stopping_ ? 0.0 : allowed;
  if (luff < 0.0) luff *= share;
  if (hoist > 0.0) hoist *= share;

  // luffing: rope speed to boom rate from the geometry (d rope length / d angle over the falls), the limit
  // switches on the boom angle
  const double rope_per_rad = luffing_rope_per_rad();
  const cable::ElementSettings& luff_drum = first_drum(settings_.luffing);
  const double per_rad = std::max(std::abs(rope_per_rad), 1.0);
  luff = luff_limits_.limit(luff, boom_angle_rad(), luff_drum.max_rope_speed_mps / per_rad,
                            luff_drum.max_rope_acceleration_mps2 / per_rad, dt_s);
  luff_speed_mps_ = stop ? 0.0 : -luff * luffing_radius_rate_mps();  // + raises: the radius shrinks
  const cable::DrumCommand luff_command{stop ? 0.0 : -luff, false, !stop};
  luffing_->step(dt_s, {&luff_command, 1}, *luffing_bodies_);

  // hoist: both winches together; on the grab the closing winch alone shuts (reels in) and opens the shells
  const cable::ElementSettings& hoist_drum = first_drum(hoisting());
  hoist = hoist_limits_.limit(hoist, world_.pose(block_).position.z, hoist_drum.max_rope_speed_mps,
                              hoist_drum.max_rope_acceleration_mps2, dt_s);
  std::array<cable::DrumCommand, 2> hoist_commands{cable::DrumCommand{0.0, hoist_brake_fault_, !stop},
                                                   cable::DrumCommand{0.0, hoist_brake_fault_, !stop}};
  if (on_hook()) {
    const bool pressed = at(sling_slot_) != 0.0;
    if (pressed && !sling_pressed_) sling(liftables);
    sling_pressed_ = pressed;
    for (cable::DrumCommand& drum : hoist_commands)
      drum.lever = stop ? 0.0 : -hoist;
    if (slung_ != physics::kWorld) {
      // tag lines: a torque against the load's rocking relative to the hook (about horizontal axes)
      const core::Vec3 w = world_.angular_velocity(slung_) - world_.angular_velocity(block_);
      const core::Vec3 torque{-rocking_damping_nms_ * w.x, -rocking_damping_nms_ * w.y, 0.0};
      world_.add_torque(slung_, torque);
      world_.add_torque(block_, torque * -1.0);
    }
  } else {
    // the shells' end switches: the closing winch stops on its own when they are shut or fully open
    const double travel = settings_.grab_open_gap_m - settings_.grab_closed_gap_m;
    const double shut_rate = hoist_drum.max_rope_speed_mps / (tackle_falls_ * travel);
    const double grab =
        grab_limits_.limit(at(grab_slot_), 1.0 - grab_opening(), shut_rate,
                           hoist_drum.max_rope_acceleration_mps2 / (tackle_falls_ * travel), dt_s);
    // the closing winch runs at hoist + grab; beyond its full speed both winches give up the excess, so the
    // grab lever keeps its difference while hoisting
    const double wanted_close = hoist + grab;
    const double excess = wanted_close - std::clamp(wanted_close, -1.0, 1.0);
    const double close = wanted_close - excess;
    // closing on material the holding winch follows (slack-rope control): it pays out what keeps the lower
    // block where it rests, so the head comes down to it and the jaws cut in under the grab's weight
    const double grab_kg = settings_.grab_head_mass_kg + settings_.grab_lower_mass_kg + carried_kg_;
    const bool resting = limiter_load_n_ < kRestingShare * grab_kg * kG;  // filtered: not a bounce's dip
    const double follow = resting && grab > 0.0 ? grab / std::max(tackle_falls_ - 1, 1) : 0.0;
    // a shut grab hanging on its ropes: the holding winch shares the load evenly with the closing winch
    // (load equalisation), so the closing ropes hold the shells shut and neither pair carries it all
    holding_share_ +=
        (pulls.holding_share() - holding_share_) * std::min(1.0, dt_s / settings_.limiter_filter_s);
    const bool sharing = !resting && grab >= 0.0 && grab_opening() < kShutOpening;
    const double equalise = sharing ? kShareGain * (holding_share_ - 0.5) : 0.0;
    hoist_commands[0].lever = stop ? 0.0 : std::clamp(follow - hoist + excess + equalise, -1.0, 1.0);
    hoist_commands[1].lever = stop ? 0.0 : -close;
  }
  hoist_->step(dt_s, hoist_commands, *hoist_bodies_);

  // the material in the grab hangs on its lower block
  if (carried_kg_ > 0.0)
    world_.add_force_at(grab_lower_, world_.pose(grab_lower_).position, {0, 0, -carried_kg_ * kG});
  update_tool();

  // outrigger pads: a pad whose share goes below zero lifts off
  const PadForces pads = pad_forces_n();
  const bool lifted = *std::min_element(pads.begin(), pads.end()) < 0.0;
  if (lifted && !pad_lifted_) ++pad_lift_offs_;
  pad_lifted_ = lifted;
}

void MobileHarbourCrane::sling(std::span<const ContainerRef> liftables) {
  if (slung_ != physics::kWorld) {
    // off: only once the load rests (the ropes carry little more than the hook block)
    const double slung_kg = world_.mass_kg(slung_);
    if (hoisted_load_n() > (settings_.hook->block_mass_kg + kSlungResting * slung_kg) * kG) {
      ++slings_refused_;
      return;
    }
    world_.detach(sling_attachment_);
    slung_ = physics::kWorld;
    sling_attachment_ = {};
    rocking_damping_nms_ = 0.0;
    return;
  }
  // on: the hook within the slinger's reach of plumb over a load's centre and no higher over its top than
  // the slings reach; the slings hang from the hook's bottom
  const core::Pose hook = world_.pose(block_);
  const core::Vec3 eye = hook.to_parent({0, 0, -block_half_extents_m().z});
  for (const ContainerRef& item : liftables) {
    const core::Pose load = world_.pose(item.body);
    const double top = load.position.z + item.half_extents_m.z;
    const double above = eye.z - top;
    if (std::hypot(eye.x - load.position.x, eye.y - load.position.y) <= settings_.hook->slinger_reach_m &&
        above > 0.0 && above <= settings_.hook->sling_length_m) {
      slung_ = item.body;
      slung_half_extents_m_ = item.half_extents_m;
      sling_attachment_ = world_.attach_pivot(block_, item.body, eye);
      // the rocking mode about the hook: a box's moment of inertia about a horizontal axis through its centre
      // (the larger of the two), carried to the hook; ω² = m g d / I
      const core::Vec3& h = item.half_extents_m;
      const double m = world_.mass_kg(item.body), d = eye.z - load.position.z;
      const double inertia = m / 3.0 * (std::max(h.x, h.y) * std::max(h.x, h.y) + h.z * h.z) + m * d * d;
      rocking_damping_nms_ =
          2.0 * settings_.hook->tag_line_damping_ratio * inertia * std::sqrt(m * kG * d / inertia);
      return;
    }
  }
  ++slings_refused_;
}

void MobileHarbourCrane::describe(scene::SceneDescription& d) const {
  d.machine = kind();
  d.entities.push_back({"undercarriage",
                        "mhc.undercarriage",
                        {settings_.pad_half_spread_x_m, settings_.pad_half_spread_y_m, 2.0}});
  d.entities.push_back({"house", "mhc.house", settings_.house_half_extents_m});
  d.entities.push_back(
      {"boom",
       "mhc.boom",
       {0.5 * settings_.boom_length_m, settings_.boom_half_width_m, settings_.boom_half_width_m}});
  if (on_hook()) {
    d.entities.push_back({"hook", "mhc.hook", block_half_extents_m()});
  } else {
    d.entities.push_back({"grab head", "mhc.grab_head", settings_.grab_head_half_extents_m});
    d.entities.push_back({"grab", "mhc.grab", settings_.grab_lower_half_extents_m});
  }
  d.indicators.assign(std::begin(kMhcIndicators), std::end(kMhcIndicators));
  d.drives = {"slew", "luff", "hoist", "closing", "engine"};
  d.rope_count = std::min(luffing_->rope_count() + hoist_->rope_count() + (on_hook() ? kSlingLegs : 0),
                          scene::kMaxRopes);
}

int MobileHarbourCrane::publish(scene::Snapshot& s, int first) const {
  int n = first;
  const core::Pose undercarriage{core::Mat3::identity(), position_ + core::Vec3{0, 0, 2.0}};
  const int bodies = on_hook() ? 4 : 5;
  const core::Pose poses[] = {undercarriage, world_.pose(house_), world_.pose(boom_), world_.pose(block_),
                              on_hook() ? core::Pose{} : world_.pose(grab_lower_)};
  for (const core::Pose& pose : std::span(poses, static_cast<std::size_t>(bodies)))
    if (n < scene::kMaxEntities) {
      s.entities[static_cast<std::size_t>(n)] = {static_cast<std::uint32_t>(n), 0, pose};
      ++n;
    }
  publish_ropes(*luffing_, s);
  publish_ropes(*hoist_, s);
  if (on_hook())
    for (int leg = 0; leg < kSlingLegs; ++leg) {
      // four legs from the hook to the slung load's top corners (a little in from its edges)
      std::array<core::Vec3, 2> line;
      if (slung_ != physics::kWorld) {
        const core::Vec3 h = slung_half_extents_m_;
        const double sx = leg == 0 || leg == 3 ? 1.0 : -1.0, sy = leg < 2 ? 1.0 : -1.0;
        line = {world_.pose(block_).to_parent({0, 0, -block_half_extents_m().z}),
                world_.pose(slung_).to_parent(
                    {sx * std::max(h.x - 0.2, 0.0), sy * std::max(h.y - 0.2, 0.0), h.z})};
      }
      publish_polyline(std::span(line.data(), slung_ != physics::kWorld ? line.size() : 0), s);
    }
  const PadForces pads = pad_forces_n();
  const double values[] = {slew_ * 180.0 / std::numbers::pi,
                           boom_angle_rad() * 180.0 / std::numbers::pi,
                           radius_m(),
                           hoisted_load_n() / kG / 1000.0,
                           capacity_t(),
                           utilisation(),
                           limiter_stopping_ ? 1.0 : 0.0,
                           grab_opening(),
                           pads[0] / 1000.0,
                           pads[1] / 1000.0,
                           pads[2] / 1000.0,
                           pads[3] / 1000.0,
                           horn_ ? 1.0 : 0.0,
                           slung_ != physics::kWorld ? 1.0 : 0.0,
                           hoist_brake_fault_ ? 1.0 : 0.0,
                           carried_kg_ / 1000.0,
                           limiter_fault_ ? 1.0 : 0.0};
  static_assert(std::size(values) == std::size(kMhcIndicators));
  s.indicator_count = static_cast<int>(std::size(values));
  std::copy(std::begin(values), std::end(values), s.indicators.begin());
  // its drives (the grab's closing drum, where it has one) and the diesel generator set that powers them
  const bool closing = hoist_->drum_count() > 1;
  const scene::Snapshot::Drive motors[] = {drive_reading(slew_drive_, world_.hinge_torque(slew_hinge_)),
                                           drum_reading(*luffing_, 0), drum_reading(*hoist_, 0),
                                           closing ? drum_reading(*hoist_, 1) : scene::Snapshot::Drive{}};
  const double rated[] = {rated_power_w(settings_.slew_drive), rated_power_w(luffing_->drum_settings(0)),
                          rated_power_w(hoist_->drum_settings(0)),
                          closing ? rated_power_w(hoist_->drum_settings(1)) : 0.0};
  const scene::Snapshot::Drive drives[] = {motors[0], motors[1], motors[2], motors[3],
                                           generator_reading(motors, rated)};
  publish_drives(drives, s);
  return n - first;
}

void MobileHarbourCrane::drain_events(StepEvents& events) {
  luffing_->drain_events(events.ropes);
  hoist_->drain_events(events.ropes);
}

void MobileHarbourCrane::inject_fault(MachineFault fault, int) {
  if (fault == MachineFault::kHoistBrake) hoist_brake_fault_ = true;
  if (fault == MachineFault::kLoadMomentLimiter) limiter_fault_ = true;
}

void MobileHarbourCrane::hash_into(core::StateHash& hash) const {
  luffing_->hash_into(hash);
  hoist_->hash_into(hash);
  hash.add(slew_drive_.reference_mps());
  hash.add(slew_);
  hash.add(limiter_trips_);
  hash.add(limiter_load_n_);
  hash.add(carried_kg_);
  hash.add(pad_lift_offs_);
  hash.add(holding_share_);
  hash.add(luff_speed_mps_);
  hash.add(slung_);
  hash.add(rocking_damping_nms_);
  hash.add(slings_refused_);
}

// its faults as one byte where the hoist brake's flag was before the limiter could fail (a bool's byte: 0 or
// 1), so keyframes saved then restore as they were
std::uint8_t MobileHarbourCrane::fault_mask() const {
  return static_cast<std::uint8_t>((hoist_brake_fault_ ? kHoistBrakeFaultBit : 0) |
                                   (limiter_fault_ ? kLimiterFaultBit : 0));
}

template <typename Self, typename Archive>
void MobileHarbourCrane::archive(Self& self, Archive& ar) {
  ar.section(0x4D484331, "mobile harbour crane");  // "MHC1"
  ar.part(self.slew_drive_);
  ar.part(self.luff_limits_);
  ar.part(self.hoist_limits_);
  ar.part(self.grab_limits_);
  ar.part(*self.luffing_);
  ar.part(*self.hoist_);
  std::uint8_t faults = self.fault_mask();
  ar(self.slew_, self.last_hinge_angle_, self.horn_, faults);
  if constexpr (Archive::kRestoring) {
    if (faults > (kHoistBrakeFaultBit | kLimiterFaultBit))
      throw core::StateError("saved state holds a fault this mobile harbour crane does not have");
    self.hoist_brake_fault_ = (faults & kHoistBrakeFaultBit) != 0;
    self.limiter_fault_ = (faults & kLimiterFaultBit) != 0;
  }
  ar(self.limiter_stopping_, self.limiter_armed_, self.limiter_load_n_, self.pad_lifted_, self.limiter_trips_,
     self.pad_lift_offs_, self.carried_kg_, self.holding_share_, self.luff_speed_mps_, self.slung_,
     self.sling_attachment_, self.rocking_damping_nms_, self.slung_half_extents_m_, self.sling_pressed_,
     self.slings_refused_);
}

void MobileHarbourCrane::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void MobileHarbourCrane::restore_state(core::StateReader& in) {
  archive(*this, in);
  if ((slung_ != physics::kWorld) != sling_attachment_.valid() ||
      sling_attachment_.index >= world_.attachments_made())
    throw core::StateError("saved state slings a load this mobile harbour crane cannot have");
  update_tool();
}

}  // namespace harbour::sim
