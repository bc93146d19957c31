#include "harbour/io/ReevingFiles.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <numbers>

namespace harbour::io {
namespace {

// physical ranges (docs/reliability.md)
constexpr double kSteelModulus_pa = 2.1e11;  ///< [Pa] a rope is no stiffer than a steel bar of its diameter
constexpr double kSteelDensity_kg_m3 = 7850.0;  ///< [kg/m^3] ... nor heavier
constexpr double kMaxRopeStress_pa = 2.5e9;     ///< [Pa] ... nor stronger than 2500 MPa wire on all of it
// and no rope is softer, lighter or weaker than the softest, lightest, weakest fibre rope of its diameter
// (polyester and HMPE: E 2-100 GPa, 970-1380 kg/m^3, 0.5-3 GPa on their fibre, which fills about half of it)
constexpr double kMinRopeModulus_pa = 1e9;       ///< [Pa] on the rope's whole section
constexpr double kMinRopeDensity_kg_m3 = 300.0;  ///< [kg/m^3] on the rope's whole section
constexpr double kMinRopeStress_pa = 1e8;        ///< [Pa] its breaking force on the rope's whole section
constexpr double kMount_m = 500.0;               ///< [m] a sheave or anchor lies within this of its body
constexpr double kMaxTorque_n_m = 1e7;           ///< [N m] drum motors, brakes and bearing friction

std::string figure(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

double bar_area_m2(double diameter_m) {
  return std::numbers::pi / 4.0 * diameter_m * diameter_m;
}

std::string item(const std::string& list, std::size_t n) {
  return list + "[" + std::to_string(n) + "]";
}

}  // namespace

ReevingFile load_reeving(const YamlFile& f) {
  ReevingFile out;
  cable::ReevingSettings& r = out.reeving;
  const YAML::Node root = f.required_map(f.root(), "reeving", "");
  r.name = f.text(root, "name", "reeving");
  r.max_substeps = f.integer(root, "max_substeps", "reeving", 0, 1000);
  r.resume_fraction =
      f.number_or(root, "resume_fraction", "reeving", r.resume_fraction, 0.0, 1.0, true, true);

  // bodies by name; "world" is fixed
  const YAML::Node bodies = f.sequence(root, "bodies", "reeving", 16);
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    if (!bodies[n].IsScalar() || bodies[n].Scalar().empty() || bodies[n].Scalar() == "world")
      f.fail(bodies[n], item("reeving.bodies", n), "expected a body name other than 'world'");
    out.bodies.push_back(bodies[n].Scalar());
  }
  auto body_index = [&](const YAML::Node& node, const std::string& field) {
    const std::string name = node.IsScalar() ? node.Scalar() : "";
    if (name == "world") return -1;
    const auto at = std::find(out.bodies.begin(), out.bodies.end(), name);
    if (at == out.bodies.end()) f.fail(node, field, "unknown body '" + name + "' (not in reeving.bodies)");
    return static_cast<int>(at - out.bodies.begin());
  };

  // rope types
  std::map<std::string, cable::RopeSettings> types;
  const YAML::Node type_list = f.sequence(root, "rope_types", "reeving", 64);
  for (std::size_t n = 0; n < type_list.size(); ++n) {
    const YAML::Node t = type_list[n];
    const std::string at = item("reeving.rope_types", n);
    cable::RopeSettings rope;
    rope.name = f.text(t, "name", at);
    rope.diameter_m = f.number(t, "diameter_m", at, 0.003, 0.2);
    const double area = bar_area_m2(rope.diameter_m);
    // between the lightest, softest, weakest fibre rope and a steel bar of its diameter: outside, no rope
    const auto physical = [&](const char* key, double per_area, double steel_per_area, const char* quality) {
      const double value = f.number(t, key, at, 0.0, 1e300, true);
      const std::string diameter = figure(rope.diameter_m * 1e3) + " mm";
      if (value < per_area * area)
        f.fail(t[key], at + "." + key,
               figure(value) + " is below " + figure(per_area * area) + ": no " + diameter + " rope is " +
                   quality + " than that (the lightest, softest, weakest fibre rope)");
      if (value > steel_per_area * area)
        f.fail(t[key], at + "." + key,
               figure(value) + " is above " + figure(steel_per_area * area) + ", more than a steel bar of " +
                   diameter + " gives");
      return value;
    };
    rope.mass_per_m_kg = physical("mass_per_m_kg", kMinRopeDensity_kg_m3, kSteelDensity_kg_m3, "lighter");
    rope.axial_stiffness_n = physical("axial_stiffness_n", kMinRopeModulus_pa, kSteelModulus_pa, "softer");
    rope.min_breaking_force_n =
        physical("min_breaking_force_n", kMinRopeStress_pa, kMaxRopeStress_pa, "weaker");
    rope.safety_factor = f.number_or(t, "safety_factor", at, rope.safety_factor, 1.0, 100.0);
    rope.axial_damping_s = f.number_or(t, "axial_damping_s", at, rope.axial_damping_s, 0.0, 1.0);
    rope.transverse_damping_per_s =
        f.number_or(t, "transverse_damping_per_s", at, rope.transverse_damping_per_s, 0.0, 1000.0);
    rope.bending_loss = f.number_or(t, "bending_loss", at, rope.bending_loss, 0.0, 0.2);
    rope.nodes = static_cast<int>(f.number_or(t, "nodes", at, rope.nodes, 2, 200));
    if (types.count(rope.name)) f.fail(t["name"], at + ".name", "duplicate rope type '" + rope.name + "'");
    types[rope.name] = rope;
  }

  // elements
  std::map<std::string, int> element_index;
  const YAML::Node elements = f.sequence(root, "elements", "reeving", 512);
  for (std::size_t n = 0; n < elements.size(); ++n) {
    const YAML::Node e = elements[n];
    const std::string at = item("reeving.elements", n);
    cable::ElementSettings el;
    el.name = f.text(e, "name", at);
    if (element_index.count(el.name)) f.fail(e["name"], at + ".name", "duplicate element '" + el.name + "'");
    const std::string kind = f.text(e, "kind", at);
    if (kind == "drum")
      el.kind = cable::ElementKind::kDrum;
    else if (kind == "sheave")
      el.kind = cable::ElementKind::kSheave;
    else if (kind == "anchor")
      el.kind = cable::ElementKind::kAnchor;
    else
      f.fail(e["kind"], at + ".kind", "'" + kind + "' is not drum, sheave or anchor");
    el.mount.body = body_index(f.required(e, "body", at), at + ".body");
    el.mount.local = f.vector3(f.required(e, "at_m", at), at + ".at_m", kMount_m);
    if (el.kind != cable::ElementKind::kAnchor) {
      el.radius_m = f.number(e, "radius_m", at, 0.05, 5.0);
      el.inertia_kg_m2 = f.number(e, "inertia_kg_m2", at, 0.01, 1e6);
      el.friction_torque_n_m = f.number_or(e, "friction_torque_n_m", at, 0.0, 0.0, kMaxTorque_n_m);
    }
    if (el.kind == cable::ElementKind::kDrum) {
      el.max_rope_speed_mps = f.number(e, "max_rope_speed_mps", at, 0.0, 20.0, true);
      el.max_rope_acceleration_mps2 = f.number(e, "max_rope_acceleration_mps2", at, 0.0, 20.0, true);
      el.max_torque_n_m = f.number(e, "max_torque_n_m", at, 0.0, kMaxTorque_n_m, true);
      el.brake_torque_n_m = f.number(e, "brake_torque_n_m", at, 0.0, kMaxTorque_n_m);
      el.stored_rope_m = f.number(e, "stored_rope_m", at, 0.0, 5000.0);
    }
    element_index[el.name] = static_cast<int>(r.elements.size());
    r.elements.push_back(el);
  }

  // ropes: a drum, sheaves, then an anchor or a drum; each sheave carries one rope
  std::vector<int> sheave_owner(r.elements.size(), -1);
  const YAML::Node ropes = f.sequence(root, "ropes", "reeving", 64);
  for (std::size_t n = 0; n < ropes.size(); ++n) {
    const YAML::Node node = ropes[n];
    const std::string at = item("reeving.ropes", n);
    const std::string type = f.text(node, "type", at);
    if (!types.count(type)) f.fail(node["type"], at + ".type", "unknown rope type '" + type + "'");
    cable::RopeSettings rope = types[type];
    rope.name = f.text(node, "name", at);
    const YAML::Node path = f.sequence(node, "path", at, 64);
    if (path.size() < 2) f.fail(path, at + ".path", "a rope needs at least two elements");
    for (std::size_t j = 0; j < path.size(); ++j) {
      const std::string field = item(at + ".path", j);
      const std::string name = path[j].IsScalar() ? path[j].Scalar() : "";
      if (!element_index.count(name)) f.fail(path[j], field, "unknown element '" + name + "'");
      const int e = element_index[name];
      // a rope that meets an element twice (a drum to itself, a sheave passed twice) has a zero-length or
      // folded segment the wave model cannot carry
      if (std::find(rope.path.begin(), rope.path.end(), e) != rope.path.end())
        f.fail(path[j], field, "rope '" + rope.name + "' meets '" + name + "' twice");
      const cable::ElementKind kind = r.elements[e].kind;
      const bool first = j == 0, last = j + 1 == path.size();
      if (first && kind != cable::ElementKind::kDrum)
        f.fail(path[j], field, "rope '" + rope.name + "' must start at a drum, not at '" + name + "'");
      if (!first && !last && kind != cable::ElementKind::kSheave)
        f.fail(path[j], field, "only sheaves can sit between the ends of a rope; '" + name + "' is not one");
      if (last && kind == cable::ElementKind::kSheave)
        f.fail(path[j], field,
               "rope '" + rope.name + "' ends on sheave '" + name + "': end it at an anchor or drum");
      if (kind == cable::ElementKind::kSheave) {
        if (sheave_owner[e] >= 0 && sheave_owner[e] != static_cast<int>(n))
          f.fail(path[j], field, "sheave '" + name + "' already carries another rope");
        sheave_owner[e] = static_cast<int>(n);
      }
      rope.path.push_back(e);
    }
    r.ropes.push_back(rope);
  }
  if (r.ropes.empty()) f.fail(ropes, "reeving.ropes", "no rope defined");
  f.check_unknown_keys();
  return out;
}

ReevingFile load_reeving(const std::string& path) {
  return load_reeving(YamlFile::load(path));
}

}  // namespace harbour::io
