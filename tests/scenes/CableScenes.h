#pragma once

// Reevings built in code for tests and benchmarks (files: data/reeving/).

#include "harbour/cable/Reeving.h"

namespace harbour::scenes {

/// A 28 mm 6x7 FC rope (reference.md: 2.70 kg/m, MBF 461 kN; EA assumed 100 GPa on 0.4 d^2).
inline cable::RopeSettings rope_28mm(std::vector<int> path, int nodes = 12) {
  cable::RopeSettings r;
  r.name = "rope";
  r.diameter_m = 0.028;
  r.mass_per_m_kg = 2.70;
  r.axial_stiffness_n = 100e9 * 0.4 * 0.028 * 0.028;
  r.min_breaking_force_n = 461e3;
  r.nodes = nodes;
  r.path = std::move(path);
  return r;
}

inline cable::ElementSettings drum(cable::Mount m) {
  cable::ElementSettings e;
  e.name = "drum";
  e.kind = cable::ElementKind::kDrum;
  e.mount = m;
  e.radius_m = 0.5;
  e.inertia_kg_m2 = 500.0;
  e.max_rope_speed_mps = 1.0;
  e.max_rope_acceleration_mps2 = 0.5;
  e.max_torque_n_m = 2e5;
  e.brake_torque_n_m = 3e5;
  e.stored_rope_m = 200.0;
  return e;
}

inline cable::ElementSettings sheave(cable::Mount m, const char* name = "sheave") {
  cable::ElementSettings e;
  e.name = name;
  e.kind = cable::ElementKind::kSheave;
  e.mount = m;
  e.radius_m = 0.4;
  e.inertia_kg_m2 = 4.0;
  return e;
}

inline cable::ElementSettings anchor(cable::Mount m) {
  cable::ElementSettings e;
  e.name = "anchor";
  e.kind = cable::ElementKind::kAnchor;
  e.mount = m;
  return e;
}

/// A 4-fall hoist: drum and two trolley-side points fixed at z = 30 m, a block (body `block`) with two
/// sheaves hanging at z = 10 m (20 m falls): drum -> block sheave -> trolley sheave -> block sheave -> dead
/// end on the trolley.
inline cable::ReevingSettings four_fall(int block) {
  cable::ReevingSettings s;
  s.name = "four_fall";
  s.elements = {drum({-1, {-1.5, 0, 30}}), sheave({block, {-1.0, 0, 0}}), sheave({-1, {0.0, 0, 30}}),
                sheave({block, {1.0, 0, 0}}), anchor({-1, {1.5, 0, 30}})};
  s.ropes = {rope_28mm({0, 1, 2, 3, 4})};
  return s;
}

}  // namespace harbour::scenes
