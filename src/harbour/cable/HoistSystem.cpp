#include "harbour/cable/HoistSystem.h"

#include <algorithm>
#include <cmath>

#include "harbour/core/Assert.h"

namespace harbour::cable {
namespace {

using core::Vec3;

constexpr double kBendingCreep_rad_s = 0.01;  // below this turning rate the bending loss falls linearly
// a working load exceeded this long is an overload: a load limiter's filtering (a slack rope snapping taut
// inside a grab reads hundreds of kN for a millisecond or two)
constexpr double kOverloadFilter_s = 0.01;
constexpr double kCourant = 0.5;              // sub-step: wave (plus transport) crosses half a node interval
constexpr double kSpringDecay_s = 0.05;       // a suspended oscillation's shape fades over this time
constexpr double kStretchStability = 1.0;     // sub-step times the stretch coupling's frequency (< 2)
constexpr double kMaxWave_hz = 20.0;          // a segment whose fundamental would be faster becomes a spring
constexpr double kBrakeSpeedFraction = 1e-3;  // brake engages below this share of full speed

Vec3 perpendicular(const Vec3& v, const Vec3& e) {
  return v - e * core::dot(v, e);
}

}  // namespace

HoistSystem::HoistSystem(const ReevingSettings& settings, const CableBodies& bodies, const Vec3& gravity)
    : settings_(settings), gravity_(gravity), elements_(settings.elements.size()) {
  events_.reserve(64);
  for (int e = 0; e < static_cast<int>(settings.elements.size()); ++e)
    if (settings.elements[e].kind == ElementKind::kDrum) drums_.push_back(e);
  for (int r = 0; r < static_cast<int>(settings.ropes.size()); ++r) {
    const RopeSettings& rope = settings.ropes[r];
    HARBOUR_ASSERT(rope.path.size() >= 2, "reeving must be validated by the loader");
    Rope state;
    state.stored_m = settings.elements[rope.path.front()].stored_rope_m;
    if (settings.elements[rope.path.back()].kind == ElementKind::kDrum)
      state.stored_m += settings.elements[rope.path.back()].stored_rope_m;
    for (std::size_t j = 0; j + 1 < rope.path.size(); ++j) {
      Segment s;
      s.rope = r;
      s.a = rope.path[j];
      s.b = rope.path[j + 1];
      const ElementSettings& ea = settings.elements[s.a];
      const ElementSettings& eb = settings.elements[s.b];
      s.end_a = bodies.point_position(ea.mount.body, ea.mount.local);
      s.end_b = bodies.point_position(eb.mount.body, eb.mount.local);
      s.velocity_a = bodies.point_velocity(ea.mount.body, ea.mount.local);
      s.velocity_b = bodies.point_velocity(eb.mount.body, eb.mount.local);
      s.rest_length = core::length(s.end_b - s.end_a);
      s.length = s.rest_length;
      s.chord_length = s.rest_length;
      s.w.assign(static_cast<std::size_t>(rope.nodes - 1), Vec3{});
      s.u.assign(static_cast<std::size_t>(rope.nodes - 1), Vec3{});
      state.segments.push_back(static_cast<int>(segments_.size()));
      segments_.push_back(std::move(s));
    }
    ropes_.push_back(std::move(state));
  }
}

void HoistSystem::pretension(double tension_n) {
  // each segment hangs in its static sag under that tension (the parabola of w_ss = -mu g_perp / T) and is
  // stretched along that curve: the load starts where it will rest and the spans do not drop into their sag
  // (on the chord's stretch, straight)
  for (Rope& rope : ropes_)
    for (const int index : rope.segments) {
      Segment& s = segments_[static_cast<std::size_t>(index)];
      const RopeSettings& settings = settings_.ropes[static_cast<std::size_t>(s.rope)];
      double length = s.chord_length;
      if (!settings_.stretch_along_chord) {
        const Vec3 e = (s.end_b - s.end_a) * (1.0 / std::max(s.chord_length, 1e-9));
        const Vec3 sag = perpendicular(gravity_, e) * (settings.mass_per_m_kg / (2.0 * tension_n));
        const double h = s.chord_length / settings.nodes;
        length = 0.0;
        Vec3 previous{};
        for (std::size_t k = 0; k <= s.w.size(); ++k) {
          const double along = static_cast<double>(k + 1) * h;
          const Vec3 w = k < s.w.size() ? sag * (along * (s.chord_length - along)) : Vec3{};
          if (k < s.w.size()) s.w[k] = w;
          length += std::sqrt(h * h + core::dot(w - previous, w - previous));
          previous = w;
        }
        s.length = length;
        s.sag_share = 1.0;
      }
      const double ea = settings.axial_stiffness_n;
      const double rest = length / (1.0 + tension_n / ea);  // T = EA (L - L0) / L0
      rope.stored_m += s.rest_length - rest;
      s.rest_length = rest;
      s.tension = tension_n;
      s.stiffness = ea / rest * length / rest;
    }
}

void HoistSystem::stop_transverse_motion() {
  if (settings_.stretch_along_chord) return;
  for (Segment& s : segments_)
    std::fill(s.u.begin(), s.u.end(), Vec3{});
}

double HoistSystem::rope_speed_into(const Segment& s, bool at_a) const {
  // speed at which rope material crosses an end of the segment, positive from the drum towards the dead end
  const int e = at_a ? s.a : s.b;
  const ElementSettings& el = settings_.elements[e];
  if (el.kind == ElementKind::kAnchor) return 0.0;
  const double v = el.radius_m * elements_[e].omega;
  // a drum at the far end pays out towards the drum at the near end: against the path direction
  const bool far_drum = !at_a && el.kind == ElementKind::kDrum;
  return far_drum ? -v : v;
}

void HoistSystem::integrate_wave(Segment& s, const RopeSettings& rope, double dt, int substeps, const Vec3& e,
                                 double h, double transport, const Vec3& accel_a, const Vec3& accel_b) {
  // axially moving string: w_tt = (T/mu - v^2) w_ss - 2 v w_st - d w_t + g_perp - a_chord(s)_perp
  // symplectic Euler for the wave; the transport (gyroscopic, skew) and damping terms implicitly (midpoint
  // and backward Euler: a tridiagonal solve), since forward Euler on a skew operator always amplifies
  const int n = rope.nodes;
  const double mu = rope.mass_per_m_kg;
  const Vec3 g_perp = perpendicular(gravity_, e);
  const double tension_term = std::max(s.tension / mu - transport * transport, 0.0) / (h * h);
  const int count = std::max(substeps, 1);
  const double ds = dt / count;
  const double skew = 0.5 * ds * transport / h;  // (ds / 2) * 2v / (2h)
  const double diag = 1.0 + ds * rope.transverse_damping_per_s;
  const std::size_t m = s.w.size();
  std::vector<Vec3>& w = s.w;
  std::vector<Vec3>& u = s.u;
  // Thomas factors of the tridiagonal (lower -skew, diagonal diag, upper +skew): the same every sub-step
  thomas_upper_.resize(m);
  thomas_pivot_.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    thomas_pivot_[k] = diag + (k > 0 ? skew * thomas_upper_[k - 1] : 0.0);
    thomas_upper_[k] = skew / thomas_pivot_[k];
  }
  thomas_rhs_.resize(m);
  // the damping is internal to the rope (the relative motion of its nodes across the chord): its reaction
  // goes to the ends, each node's to the two ends by its place along the chord, so it only dissipates
  s.damping_a = Vec3{};
  s.damping_b = Vec3{};
  const double node_damping = rope.transverse_damping_per_s * mu * s.rest_length / n / count;
  for (int sub = 0; sub < count; ++sub) {
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3 w_left = k > 0 ? w[k - 1] : Vec3{}, w_right = k + 1 < m ? w[k + 1] : Vec3{};
      const Vec3 u_left = k > 0 ? u[k - 1] : Vec3{}, u_right = k + 1 < m ? u[k + 1] : Vec3{};
      const double along = static_cast<double>(k + 1) / n;
      const Vec3 end_motion = perpendicular(accel_a * (1.0 - along) + accel_b * along, e);
      const Vec3 force = (w_right - w[k] * 2.0 + w_left) * tension_term + g_perp - end_motion;
      const Vec3 rhs = u[k] + force * ds - (u_right - u_left) * skew;
      thomas_rhs_[k] = (rhs + (k > 0 ? thomas_rhs_[k - 1] * skew : Vec3{})) * (1.0 / thomas_pivot_[k]);
    }
    for (std::size_t k = m; k-- > 0;) {
      u[k] = thomas_rhs_[k] - (k + 1 < m ? u[k + 1] * thomas_upper_[k] : Vec3{});
      const double along = static_cast<double>(k + 1) / n;
      s.damping_a += u[k] * (node_damping * (1.0 - along));
      s.damping_b += u[k] * (node_damping * along);
    }
    for (std::size_t k = 0; k < m; ++k)
      w[k] += u[k] * ds;
  }
}

void HoistSystem::update_segment(Segment& s, const RopeSettings& rope, double dt, const CableBodies& bodies) {
  const ElementSettings& ea = settings_.elements[s.a];
  const ElementSettings& eb = settings_.elements[s.b];
  const Vec3 a = bodies.point_position(ea.mount.body, ea.mount.local);
  const Vec3 b = bodies.point_position(eb.mount.body, eb.mount.local);
  const Vec3 va = bodies.point_velocity(ea.mount.body, ea.mount.local);
  const Vec3 vb = bodies.point_velocity(eb.mount.body, eb.mount.local);
  const Vec3 chord = b - a;
  const double chord_length = std::max(core::length(chord), 1e-9);
  const Vec3 e = chord * (1.0 / chord_length);
  const int n = rope.nodes;
  const double h = chord_length / n;
  const double mu = rope.mass_per_m_kg;

  // keep the transverse field perpendicular to the (turning) chord
  for (std::size_t k = 0; k < s.w.size(); ++k) {
    s.w[k] = perpendicular(s.w[k], e);
    s.u[k] = perpendicular(s.u[k], e);
  }

  // oscillation, or the massless spring when the wave would need too many sub-steps (with hysteresis);
  // a slack segment carries no wave either (nothing restores it): it keeps the shape it had (a slack rope
  // does not lift its own sag) and its weight rests on its ends; a spring's shape fades
  const double transport = 0.5 * (rope_speed_into(s, true) + rope_speed_into(s, false));
  const double wave_speed = std::sqrt(s.tension / mu);
  // the stretch of the curved rope couples its nodes through the tension (a rank-one stiffness EA/L0 g g^T,
  // g the gradient of the curved length): its frequency bounds the sub-step too
  double gradient_squared = 0.0;
  if (s.oscillating && s.tension > 0.0 && !settings_.stretch_along_chord)
    for (std::size_t k = 0; k < s.w.size(); ++k) {
      const Vec3 left = k > 0 ? s.w[k - 1] : Vec3{}, right = k + 1 < s.w.size() ? s.w[k + 1] : Vec3{};
      const Vec3 in = s.w[k] - left, out = right - s.w[k];
      const Vec3 g = in * (1.0 / std::sqrt(h * h + core::dot(in, in))) -
                     out * (1.0 / std::sqrt(h * h + core::dot(out, out)));
      gradient_squared += core::dot(g, g);
    }
  const double stretch_rate = std::sqrt(rope.axial_stiffness_n / s.rest_length * gradient_squared / (mu * h));
  const int substeps = static_cast<int>(std::ceil(
      dt * std::max((wave_speed + std::abs(transport)) / (kCourant * h), stretch_rate / kStretchStability)));
  // a short, taut segment vibrates too fast to matter (its fundamental beyond kMaxWave_hz): a spring, whose
  // curved length would otherwise tie its tension to millimetres of transverse motion
  const bool too_fast = !settings_.stretch_along_chord && wave_speed > kMaxWave_hz * 2.0 * chord_length;
  if (s.oscillating && (substeps > settings_.max_substeps || too_fast)) {
    s.oscillating = false;
    s.switch_tension = s.tension;
  } else if (!s.oscillating && s.tension < settings_.resume_fraction * s.switch_tension) {
    s.oscillating = true;
  }

  // the share of the rope's cross-chord weight that travels through the sag: it builds as a wave segment sags
  // and fades with a spring's shape, so the end forces change smoothly across a switch
  const double fade = std::exp(-dt / kSpringDecay_s);
  const Vec3 accel_a = (va - s.velocity_a) * (1.0 / dt), accel_b = (vb - s.velocity_b) * (1.0 / dt);
  if (s.oscillating && s.tension > 0.0) {
    s.sag_share = 1.0 - (1.0 - s.sag_share) * fade;
    integrate_wave(s, rope, dt, substeps, e, h, transport, accel_a, accel_b);
  } else {
    s.damping_a = s.damping_b = Vec3{};
    s.sag_share *= fade;
    const bool fade_shape = !s.oscillating || settings_.slack_ropes_straighten;
    for (std::size_t k = 0; k < s.w.size(); ++k) {
      if (fade_shape) s.w[k] *= fade;
      s.u[k] = Vec3{};
    }
  }

  // the rope's mass across the chord, where no wave carries it (a spring, the share not yet in the sag): a
  // taut straight rope moving with its ends, its inertia on them by the consistent mass of a linear element
  // (m/3 at its own end, m/6 at the other), from their accelerations of the last step
  const double spring_mass =
      s.tension > 0.0 && !settings_.stretch_along_chord ? (1.0 - s.sag_share) * mu * s.rest_length : 0.0;
  const Vec3 across_a = perpendicular(accel_a, e), across_b = perpendicular(accel_b, e);
  s.inertia_a = (across_a * (1.0 / 3.0) + across_b * (1.0 / 6.0)) * -spring_mass;
  s.inertia_b = (across_a * (1.0 / 6.0) + across_b * (1.0 / 3.0)) * -spring_mass;

  // tension from the stretch of the curved rope (its sag takes up rope: what keeps the energy of the wave and
  // of the end bodies one account), with strain-rate damping; a rope never pushes
  double length = 0.0;
  for (int k = 0; k < n; ++k) {
    const Vec3 left = k > 0 ? s.w[k - 1] : Vec3{}, right = k + 1 < n ? s.w[k] : Vec3{};
    length += std::sqrt(h * h + core::dot(right - left, right - left));
  }
  const bool along_chord = settings_.stretch_along_chord;
  const double stretch = (along_chord ? chord_length : length) - s.rest_length;
  // the rope transferred over its ends since the last step takes part in its strain rate (runs recorded
  // before: the geometric length's rate alone)
  const double transferred =
      settings_.simple_sheaves ? 0.0 : rope_speed_into(s, true) - rope_speed_into(s, false);
  const double strain_rate =
      ((along_chord ? chord_length - s.chord_length : length - s.length) / dt - transferred) / s.rest_length;
  s.length = length;
  s.chord_length = chord_length;
  if (stretch > 0.0) {
    const double ea_over_l0 = rope.axial_stiffness_n / s.rest_length;
    s.tension =
        std::max(0.0, ea_over_l0 * stretch + rope.axial_stiffness_n * rope.axial_damping_s * strain_rate);
    s.stiffness = ea_over_l0 * length / s.rest_length;
  } else {
    s.tension = 0.0;
    s.stiffness = 0.0;
  }
  // a rope turning on a sheave or drum (the far end moving across the chord against the element's body) rolls
  // on or off it: a length r dphi bends or straightens and its hysteresis takes bending_loss T r dphi, a
  // moment between the rope and the element's body against the turn
  const bool bending = !settings_.sheaves_without_bending_loss && s.tension > 0.0;
  const double loss_moment = bending ? rope.bending_loss * s.tension : 0.0;
  s.bending_at_a = bending_force(ea, bodies, a, b, va, vb, loss_moment * ea.radius_m);
  s.bending_at_b = bending_force(eb, bodies, b, a, vb, va, loss_moment * eb.radius_m);
  s.end_a = a;
  s.end_b = b;
  s.velocity_a = va;
  s.velocity_b = vb;
}

void HoistSystem::step_drums(double dt, std::span<const DrumCommand> commands) {
  // rope torque on each drum: tension at the rim pays rope out
  for (int d : drums_)
    elements_[d].rope_torque = 0.0;
  for (const Rope& rope : ropes_) {
    const Segment& first = segments_[rope.segments.front()];
    const Segment& last = segments_[rope.segments.back()];
    elements_[first.a].rope_torque += settings_.elements[first.a].radius_m * first.tension;
    if (settings_.elements[last.b].kind == ElementKind::kDrum)
      elements_[last.b].rope_torque += settings_.elements[last.b].radius_m * last.tension;
  }
  for (std::size_t n = 0; n < drums_.size(); ++n) {
    const ElementSettings& d = settings_.elements[drums_[n]];
    ElementState& st = elements_[drums_[n]];
    const DrumCommand command = n < commands.size() ? commands[n] : DrumCommand{};
    // ramped speed reference from the lever
    const double full = d.max_rope_speed_mps / d.radius_m;
    const double target = std::clamp(command.lever, -1.0, 1.0) * full;
    const double ramp = d.max_rope_acceleration_mps2 / d.radius_m * dt;
    st.reference += std::clamp(target - st.reference, -ramp, ramp);

    if (!command.motor_enabled) st.reference = 0.0;
    const bool at_rest = st.reference == 0.0 && std::abs(st.omega) <= kBrakeSpeedFraction * full;
    const bool brake = !command.brake_fault && (at_rest || !command.motor_enabled);
    if (brake) {
      // the holding brake alone; it slips if the rope torque beats it
      if (std::abs(st.rope_torque) <= d.brake_torque_n_m) {
        st.omega = 0.0;
      } else {
        st.omega +=
            dt * (st.rope_torque - std::copysign(d.brake_torque_n_m, st.rope_torque)) / d.inertia_kg_m2;
      }
      continue;
    }
    if (!command.motor_enabled) {  // no torque and no brake: the rope drives the drum
      st.omega += dt * st.rope_torque / d.inertia_kg_m2;
      continue;
    }
    // speed control within the motor's torque limit
    const double wanted = d.inertia_kg_m2 * (st.reference - st.omega) / dt - st.rope_torque;
    const double motor = std::clamp(wanted, -d.max_torque_n_m, d.max_torque_n_m);
    st.omega += dt * (motor + st.rope_torque) / d.inertia_kg_m2;
  }
}

void HoistSystem::step_sheaves(const Rope& rope, double dt) {
  // linearly implicit in the sheave speeds: each sheave's speed depends on the rope it transfers to its
  // neighbours, a tridiagonal system along the rope (sheaves are light against stiff rope)
  const std::size_t m = rope.segments.size() + 1;  // path elements
  if (m < 3) return;
  std::vector<double>& lower = sheave_lower_;  // scratch reused every step
  std::vector<double>& diag = sheave_diag_;
  std::vector<double>& upper = sheave_upper_;
  std::vector<double>& rhs = sheave_rhs_;
  lower.assign(m, 0.0);
  diag.assign(m, 1.0);
  upper.assign(m, 0.0);
  rhs.assign(m, 0.0);
  auto element = [&](std::size_t j) {
    return j == 0 ? segments_[rope.segments[0]].a : segments_[rope.segments[j - 1]].b;
  };
  const bool by_increment = !settings_.simple_sheaves;
  // a segment's tension change per metre per second of rope transferred over the step, implicitly: its
  // stiffness over the step and its strain-rate damping
  auto coupling = [&](const Segment& s) {
    const RopeSettings& rs = settings_.ropes[s.rope];
    return s.stiffness > 0.0 ? dt * s.stiffness + rs.axial_stiffness_n * rs.axial_damping_s / s.rest_length
                             : 0.0;
  };
  auto speed = [&](std::size_t j) { return elements_[element(j)].omega; };
  for (std::size_t j = 1; j + 1 < m; ++j) {
    const int e = element(j);
    const ElementSettings& el = settings_.elements[e];
    const Segment& before = segments_[rope.segments[j - 1]];
    const Segment& after = segments_[rope.segments[j]];
    const double r = el.radius_m;
    // neighbours: sheaves are unknowns; the ends (drum or anchor) have known rope speeds
    const bool left_sheave = j - 1 >= 1, right_sheave = j + 1 <= m - 2;
    if (by_increment) {
      // the transfer acts on the speeds' change over the step, A (w' - w) = r (T_next - T_prev): in steady
      // running the tensions balance across the sheave, and the stiffness part is a symplectic Euler step of
      // the sheaves with their inertia raised by dt^2 r^2 k (stable for any sheave; the ends' change is left
      // to the next step)
      const double c_before = coupling(before), c_after = coupling(after);
      diag[j] = el.inertia_kg_m2 / dt + r * r * (c_before + c_after);
      lower[j] = left_sheave ? -r * c_before * settings_.elements[element(j - 1)].radius_m : 0.0;
      upper[j] = right_sheave ? -r * c_after * settings_.elements[element(j + 1)].radius_m : 0.0;
      rhs[j] = diag[j] * speed(j) + (left_sheave ? lower[j] * speed(j - 1) : 0.0) +
               (right_sheave ? upper[j] * speed(j + 1) : 0.0) + r * (after.tension - before.tension);
      continue;
    }
    // runs recorded before: the tensions balanced after the step's transfer, T' = T - k dL0
    diag[j] = el.inertia_kg_m2 / dt + dt * r * r * (before.stiffness + after.stiffness);
    rhs[j] = el.inertia_kg_m2 * elements_[e].omega / dt + r * (after.tension - before.tension);
    const double left_speed = rope_speed_into(before, true), right_speed = rope_speed_into(after, false);
    if (left_sheave)
      lower[j] = -dt * r * before.stiffness * settings_.elements[element(j - 1)].radius_m;
    else
      rhs[j] += dt * r * before.stiffness * left_speed;
    if (right_sheave)
      upper[j] = -dt * r * after.stiffness * settings_.elements[element(j + 1)].radius_m;
    else
      rhs[j] += dt * r * after.stiffness * right_speed;
  }
  // Thomas algorithm over j = 1 .. m-2
  for (std::size_t j = 2; j + 1 < m; ++j) {
    const double f = lower[j] / diag[j - 1];
    diag[j] -= f * upper[j - 1];
    rhs[j] -= f * rhs[j - 1];
  }
  for (std::size_t j = m - 2; j >= 1; --j) {
    const double next = j + 1 <= m - 2 ? elements_[element(j + 1)].omega : 0.0;
    double omega = (rhs[j] - upper[j] * next) / diag[j];
    // bearing friction and the rope's bending on and off the sheave as it runs over it (bending_loss c at
    // each tangent: c r (T_prev + T_next)) oppose the motion and cannot reverse it; they act on the sheave
    // with the rope it moves (the coupling the solve gave it), as in the solve; runs recorded before: bearing
    // friction alone, on the sheave alone
    const ElementSettings& el = settings_.elements[element(j)];
    const Segment& before = segments_[rope.segments[j - 1]];
    const Segment& after = segments_[rope.segments[j]];
    const double r = el.radius_m;
    const bool running_loss = by_increment && !settings_.sheaves_without_bending_loss;
    const double friction =
        el.friction_torque_n_m +
        (running_loss ? settings_.ropes[before.rope].bending_loss * r * (before.tension + after.tension)
                      : 0.0);
    if (friction > 0.0) {
      const double rope_inertia = dt * r * r * (coupling(before) + coupling(after));
      const double loss = friction * dt / (el.inertia_kg_m2 + (by_increment ? rope_inertia : 0.0));
      omega = std::abs(omega) <= loss ? 0.0 : omega - std::copysign(loss, omega);
    }
    elements_[element(j)].omega = omega;
    if (j == 1) break;
  }
}

Vec3 HoistSystem::bending_force(const ElementSettings& element, const CableBodies& bodies, const Vec3& here,
                                const Vec3& there, const Vec3& velocity_here, const Vec3& velocity_there,
                                double loss_moment_n_m) const {
  if (loss_moment_n_m <= 0.0) return {};
  const Vec3 chord = there - here;
  const double chord_length = std::max(core::length(chord), 1e-9);
  const Vec3 e = chord * (1.0 / chord_length);
  // the far end's motion across the chord seen from the element's body (its point there)
  const Vec3 carried = velocity_here + core::cross(bodies.angular_velocity(element.mount.body), chord);
  const Vec3 across = perpendicular(velocity_there - carried, e);
  // Coulomb in the turning rate, linear below kBendingCreep (micro-slip between the wires)
  const double speed = std::max(core::length(across), kBendingCreep_rad_s * chord_length);
  return across * (-loss_moment_n_m / (chord_length * speed));
}

void HoistSystem::apply_forces(const Segment& s, const RopeSettings& rope, CableBodies& bodies) const {
  // the rope pulls each end towards its first interior point; its weight goes half to each end (the part
  // across the chord travels through the sag while it oscillates)
  const Vec3 chord = s.end_b - s.end_a;
  const double chord_length = std::max(core::length(chord), 1e-9);
  const Vec3 e = chord * (1.0 / chord_length);
  const double h = chord_length / rope.nodes;
  const Vec3 first = e * h + (s.w.empty() ? Vec3{} : s.w.front());
  const Vec3 last = -e * h + (s.w.empty() ? Vec3{} : s.w.back());
  const Vec3 weight = gravity_ * (0.5 * rope.mass_per_m_kg * s.rest_length);
  const Vec3 along = e * core::dot(weight, e);
  const Vec3 carried = along + (weight - along) * (1.0 - s.sag_share);
  const bool internal_damping = !settings_.damping_against_ground;
  const ElementSettings& ea = settings_.elements[s.a];
  const ElementSettings& eb = settings_.elements[s.b];
  if (ea.mount.body >= 0)
    bodies.add_force(ea.mount.body, s.end_a,
                     first * (s.tension / core::length(first)) + carried + s.inertia_a +
                         (internal_damping ? s.damping_a : Vec3{}) + s.bending_at_b);
  if (eb.mount.body >= 0)
    bodies.add_force(eb.mount.body, s.end_b,
                     last * (s.tension / core::length(last)) + carried + s.inertia_b +
                         (internal_damping ? s.damping_b : Vec3{}) + s.bending_at_a);
  // each bending force's reaction on the turning element's body, on the same line of action (no couple)
  if (ea.mount.body >= 0 && s.bending_at_a != Vec3{})
    bodies.add_force(ea.mount.body, s.end_b, -s.bending_at_a);
  if (eb.mount.body >= 0 && s.bending_at_b != Vec3{})
    bodies.add_force(eb.mount.body, s.end_a, -s.bending_at_b);
}

void HoistSystem::check_events(Segment& s, const RopeSettings& rope, int rope_index, int segment_index,
                               double dt) {
  const bool slack = s.tension <= 0.0;
  const bool over = s.tension > rope.min_breaking_force_n / rope.safety_factor;
  s.over_s = over ? s.over_s + dt : 0.0;
  const bool overloaded = settings_.simple_sheaves ? over : s.over_s >= kOverloadFilter_s - 0.5 * dt;
  const bool breaking = s.tension > rope.min_breaking_force_n;
  if (slack && !s.slack) events_.push_back({CableEventKind::kSlack, rope_index, segment_index, s.tension});
  if (overloaded && !s.overloaded)
    events_.push_back({CableEventKind::kOverload, rope_index, segment_index, s.tension});
  if (breaking && !s.breaking)
    events_.push_back({CableEventKind::kBreakingForce, rope_index, segment_index, s.tension});
  s.slack = slack;
  s.overloaded = overloaded;
  s.breaking = breaking;
}

void HoistSystem::step(double dt_s, std::span<const DrumCommand> drum_commands, CableBodies& bodies) {
  // segments (tension from the bodies' positions), then drums, then sheaves, then rope transfer and forces
  for (Segment& s : segments_)
    update_segment(s, settings_.ropes[s.rope], dt_s, bodies);
  step_drums(dt_s, drum_commands);
  for (const Rope& rope : ropes_)
    step_sheaves(rope, dt_s);
  for (std::size_t r = 0; r < ropes_.size(); ++r) {
    Rope& rope = ropes_[r];
    const RopeSettings& settings = settings_.ropes[r];
    for (std::size_t n = 0; n < rope.segments.size(); ++n) {
      Segment& s = segments_[rope.segments[n]];
      s.rest_length += (rope_speed_into(s, true) - rope_speed_into(s, false)) * dt_s;
      s.rest_length = std::max(s.rest_length, 1e-3);
      apply_forces(s, settings, bodies);
      check_events(s, settings, static_cast<int>(r), static_cast<int>(n), dt_s);
    }
    rope.stored_m -= rope_speed_into(segments_[rope.segments.front()], true) * dt_s;
    if (settings_.elements[segments_[rope.segments.back()].b].kind == ElementKind::kDrum)
      rope.stored_m += rope_speed_into(segments_[rope.segments.back()], false) * dt_s;
  }
}

double HoistSystem::rope_length(int rope) const {
  double total = ropes_[rope].stored_m;
  for (int s : ropes_[rope].segments)
    total += segments_[s].rest_length;
  return total;
}

core::Vec3 HoistSystem::midspan_displacement(int rope, int segment) const {
  const Segment& s = segment_at(rope, segment);
  return s.w.empty() ? Vec3{} : s.w[s.w.size() / 2];
}

double HoistSystem::drum_rope_speed(int drum) const {
  return settings_.elements[drums_[drum]].radius_m * elements_[drums_[drum]].omega;
}

double HoistSystem::drum_rope_torque(int drum) const {
  return elements_[drums_[drum]].rope_torque;
}

double HoistSystem::drum_power_w(int drum) const {
  return -drum_rope_torque(drum) * drum_rope_speed(drum) / drum_settings(drum).radius_m;
}

const ElementSettings& HoistSystem::drum_settings(int drum) const {
  return settings_.elements[static_cast<std::size_t>(drums_[static_cast<std::size_t>(drum)])];
}

double HoistSystem::energy() const {
  double total = 0.0;
  for (const Segment& s : segments_) {
    const RopeSettings& rope = settings_.ropes[s.rope];
    const double stretch = std::max(0.0, s.length - s.rest_length);
    total += 0.5 * rope.axial_stiffness_n / s.rest_length * stretch * stretch;
    const double node_mass = rope.mass_per_m_kg * s.rest_length / rope.nodes;
    for (const Vec3& u : s.u)
      total += 0.5 * node_mass * core::dot(u, u);
  }
  for (std::size_t e = 0; e < elements_.size(); ++e)
    total += 0.5 * settings_.elements[e].inertia_kg_m2 * elements_[e].omega * elements_[e].omega;
  return total;
}

std::vector<CableEvent> HoistSystem::take_events() {
  std::vector<CableEvent> out;
  drain_events(out);
  return out;
}

void HoistSystem::drain_events(std::vector<CableEvent>& into) {
  into.insert(into.end(), events_.begin(), events_.end());
  events_.clear();
}

int HoistSystem::polyline(int rope, int segment, std::span<core::Vec3> out) const {
  const Segment& s = segment_at(rope, segment);
  if (out.size() < 2) return 0;
  const std::size_t interior = s.w.size(), room = out.size() - 2;
  const std::size_t stride = room == 0 ? interior + 1 : interior > room ? (interior + room - 1) / room : 1;
  std::size_t n = 0;
  out[n++] = s.end_a;
  for (std::size_t i = stride - 1; room > 0 && i < interior && n + 1 < out.size(); i += stride) {
    const double f = static_cast<double>(i + 1) / static_cast<double>(interior + 1);
    out[n++] = s.end_a + (s.end_b - s.end_a) * f + s.w[i];
  }
  out[n++] = s.end_b;
  return static_cast<int>(n);
}

template <typename Self, typename Archive>
void HoistSystem::archive(Self& self, Archive& ar) {
  ar.section(self.state_section(), "hoist");
  for (auto& s : self.segments_) {
    ar(s.rest_length, s.length, s.chord_length, s.tension, s.stiffness, s.switch_tension, s.oscillating,
       s.sag_share, s.slack, s.overloaded, s.breaking);
    ar.sized(s.w);
    ar.sized(s.u);
    ar(s.end_a, s.end_b, s.velocity_a, s.velocity_b);
    if (!self.settings_.simple_sheaves) ar(s.over_s);
  }
  for (auto& r : self.ropes_)
    ar(r.stored_m);
  ar.sized(self.elements_);
}

void HoistSystem::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void HoistSystem::restore_state(core::StateReader& in) {
  archive(*this, in);
  events_.clear();
}

void HoistSystem::hash_into(core::StateHash& hash) const {
  for (const Segment& s : segments_) {
    hash.add(s.rest_length);
    hash.add(s.tension);
    hash.add(s.oscillating);
    hash.add(std::span<const Vec3>(s.w));
    hash.add(std::span<const Vec3>(s.u));
    if (!settings_.simple_sheaves) hash.add(s.over_s);
  }
  for (const ElementState& e : elements_)
    hash.add(e);
  for (const Rope& r : ropes_)
    hash.add(r.stored_m);
}

std::uint32_t HoistSystem::state_section() const {
  return settings_.simple_sheaves ? 0x484F4953 /* "HOIS" */
                                  : 0x484F4932 /* "HOI2": with the overload timers */;
}

double HoistSystem::highest_tension_n() const {
  double highest = 0.0;
  for (int r = 0; r < rope_count(); ++r)
    for (int k = 0; k < segment_count(r); ++k)
      highest = std::max(highest, tension(r, k));
  return highest;
}

}  // namespace harbour::cable
