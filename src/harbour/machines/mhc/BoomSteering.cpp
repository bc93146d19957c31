#include "harbour/machines/mhc/BoomSteering.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harbour/core/Units.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"

namespace harbour::sim {
namespace {

constexpr double kCreepGain_per_s = 0.25;   // head speed towards the target per metre off it
constexpr double kSwingGain_per_s = 0.6;    // head speed towards the load per metre of swing
constexpr double kLevelOff_s = 0.3;         // the slewing speed held this long before it is eased back
constexpr double kCalm_m = 0.35;            // swing at which the load counts as calm
constexpr double kSwingFilter_s = 0.3;      // time constant of the swing and height the levers follow
constexpr double kHeightBand_m = 0.3;       // height error the hoist leaves alone
constexpr double kHeightGain_per_m = 0.25;  // hoist lever per metre beyond it
constexpr double kLeverTravel_s = 1.0;      // a lever from neutral to full
constexpr double kLeverEase_s = 0.2;        // a lever eases into its position over about this time
constexpr double kLeverSpeedUp_s = 0.2;     // a lever's speed builds up (or reverses) over about this time
constexpr double kLeverResolution = 1e-3;   // ... and then steps the rest
// setting an empty attachment down after a fault: the hoist lever at most, as it touches, and per metre over
// what it rests on in between
constexpr double kRestLowering = 0.5, kRestTouch = 0.02, kRestEase_per_m = 0.15;

double wrap(double a) {
  return std::remainder(a, 2.0 * std::numbers::pi);
}

}  // namespace

BoomSteering::Target BoomSteering::target_of(const MobileHarbourCrane& crane, const core::Vec3& point) {
  const core::Vec3 d = point - crane.position_m();
  return {std::atan2(d.y, d.x), std::hypot(d.x, d.y)};
}

void BoomSteering::observe(const MobileHarbourCrane& crane, double decision_s, bool restart) {
  const core::Vec3 head = crane.suspension_point_m(), load = crane.load_position_m();
  const core::Vec3 swing{load.x - head.x, load.y - head.y, 0.0};
  const double smoothing = restart ? 1.0 : decision_s / (kSwingFilter_s + decision_s);
  swing_m_ += (swing - swing_m_) * smoothing;
  held_bottom_m_ += (crane.attachment_bottom_z_m() - held_bottom_m_) * smoothing;
  const double reference = crane.slew_drive().reference_mps();
  // the drive speeding up or slowing down (one way: a reversal is neither)
  const bool same_way = !restart && reference * slew_reference_ > 0.0;
  const double faster = std::abs(reference) - std::abs(slew_reference_);
  if (same_way && faster != 0.0) {
    slew_speeding_ = faster > 0.0 ? 1 : -1;
    slew_speeding_ago_s_ = 0.0;
  } else {
    slew_speeding_ago_s_ += decision_s;
  }
  slew_reference_ = reference;
}

bool BoomSteering::steer(const MobileHarbourCrane& crane, const Target& target, double tolerance_m,
                         double& slew, double& luff) const {
  // the load hangs plumb under the falls at rest: that point is steered over the target
  const core::Vec3 head = crane.suspension_point_m(), p = crane.position_m();
  const double r = std::hypot(head.x - p.x, head.y - p.y);
  const core::Vec3 radial = core::Vec3{head.x - p.x, head.y - p.y, 0.0} * (1.0 / std::max(r, 1.0));
  const core::Vec3 tangential{-radial.y, radial.x, 0.0};  // + slew: anticlockwise seen from above
  const MhcSettings& s = crane.settings();
  const double e_t = wrap(target.slew_rad - crane.slew_rad()) * r, e_r = target.radius_m - r;
  const double s_t = dot(swing_m_, tangential), s_r = dot(swing_m_, radial);
  const double v_t_max = s.slew_drive.max_speed_mps * r, v_r_max = crane.luffing_radius_rate_mps();
  const double v_t = std::clamp(kCreepGain_per_s * e_t, -v_t_max, v_t_max) + kSwingGain_per_s * s_t;
  const double v_r = std::clamp(kCreepGain_per_s * e_r, -v_r_max, v_r_max) + kSwingGain_per_s * s_r;
  slew = std::clamp(v_t / v_t_max, -1.0, 1.0);
  // while the drive speeds up, and a moment after, the lever is not brought back under its speed, and while
  // it slows down not pushed past it: the ramp would turn from full acceleration to full deceleration (or
  // back) at once (a harsh move); it levels off at the speed reached, then goes the other way
  const double reached = slew_reference_ / s.slew_drive.max_speed_mps;
  if (slew_speeding_ago_s_ < kLevelOff_s && slew * reached >= 0.0 &&
      (slew_speeding_ > 0 ? std::abs(slew) < std::abs(reached) : std::abs(slew) > std::abs(reached)))
    slew = reached;
  luff = std::clamp(-v_r / v_r_max, -1.0, 1.0);  // + raises the boom: less radius
  const double off = std::hypot(e_t + s_t, e_r + s_r);
  return off < tolerance_m && std::hypot(s_t, s_r) < kCalm_m;
}

double BoomSteering::hold_height(double z_m) const {
  const double error = z_m - held_bottom_m_;
  return std::clamp(kHeightGain_per_m * std::copysign(std::max(0.0, std::abs(error) - kHeightBand_m), error),
                    -1.0, 1.0);
}

scene::Controls stop_after_hoist_fault(const scene::ControlTable& table, const MobileHarbourCrane& crane,
                                       const scene::Controls& last, const scene::Controls& before_last,
                                       double decision_s, double empty_kg, double rest_on_z_m, double slew,
                                       double luff) {
  const bool resting = crane.limiter_load_n() < 0.5 * empty_kg * core::kStandardGravity;
  const double lowering =
      std::clamp(kRestTouch + kRestEase_per_m * (crane.attachment_bottom_z_m() - rest_on_z_m), kRestTouch,
                 kRestLowering);
  scene::Controls out = resting ? hand_levers(table, last, before_last, decision_s, {{"hoist", 0.0}})
                                : hand_levers(table, last, before_last, decision_s,
                                              {{"slew", slew}, {"luff", luff}, {"hoist", -lowering}});
  if (const int stop = table.find("emergency_stop"); stop >= 0 && resting)
    out.value[static_cast<std::size_t>(stop)] = 1.0;
  return out;
}

scene::Controls hand_levers(const scene::ControlTable& table, const scene::Controls& last,
                            const scene::Controls& before_last, double decision_s,
                            std::initializer_list<std::pair<const char*, double>> wanted) {
  scene::Controls out = table.neutral();
  // at most full travel in kLeverTravel_s, easing into the wanted position over its last kLeverEase_s, and
  // its speed changing over kLeverSpeedUp_s (a lever stopped dead, started or turned back at full speed is a
  // jerk the drive passes on: a harsh move)
  for (const auto& [label, value] : wanted)
    if (const int slot = table.find(label); slot >= 0) {
      const auto at = static_cast<std::size_t>(slot);
      out.value[at] = hand_lever(last.value[at], before_last.value[at], value, decision_s);
    }
  return out;
}

double hand_lever(double last, double before_last, double wanted, double decision_s) {
  const double step = decision_s / kLeverTravel_s;
  const double speed_change = step * decision_s / kLeverSpeedUp_s;
  const double moved = last - before_last;
  const double eased = std::abs(wanted - last) * decision_s / kLeverEase_s;
  const double most = std::min(step, std::max(eased, kLeverResolution));
  const double move =
      std::clamp(std::clamp(wanted - last, -most, most), moved - speed_change, moved + speed_change);
  return std::clamp(last + move, -1.0, 1.0);
}

}  // namespace harbour::sim
