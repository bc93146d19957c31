#include "harbour/io/VesselFiles.h"

#include <cmath>

#include "harbour/core/Units.h"

namespace harbour::io {
namespace {

std::vector<sim::Harmonic> read_harmonics(const YamlFile& f, const YAML::Node& sea, const std::string& key,
                                          const std::string& at, bool angle) {
  std::vector<sim::Harmonic> out;
  if (!f.optional(sea, key, at)) return out;
  const YAML::Node list = f.sequence(sea, key, at);
  for (std::size_t n = 0; n < list.size(); ++n) {
    const std::string p = at + "." + key + "[" + std::to_string(n) + "]";
    sim::Harmonic h;
    const HarmonicRange& range = kHarmonicRange;
    h.amplitude = angle ? core::deg_to_rad(f.number(list[n], "amplitude_deg", p, 0.0, range.max_angle_deg))
                        : f.number(list[n], "amplitude_m", p, 0.0, range.max_heave_m);
    h.period_s = f.number(list[n], "period_s", p, range.min_period_s, range.max_period_s);
    h.phase_rad = core::deg_to_rad(f.number_or(list[n], "phase_deg", p, 0.0, -360.0, 360.0));
    out.push_back(h);
  }
  return out;
}

// a bulk carrier's open hatches: one breadth, each hold's opening length along the vessel
sim::VesselSettings load_bulk_holds(const YamlFile& f, const YAML::Node& v, const std::string& at,
                                    sim::VesselSettings s) {
  s.kind = sim::VesselKind::kBulk;
  s.hatch_breadth_m = f.number(v, "hatch_breadth_m", at, 2.0, s.beam_m - 2.0);
  const YAML::Node holds = f.sequence(v, "holds", at);
  for (std::size_t n = 0; n < holds.size(); ++n) {
    const std::string p = at + ".holds[" + std::to_string(n) + "]";
    sim::VesselSettings::Hold h;
    h.number = f.integer(holds[n], "hold", p, 1, 20);
    h.opening_length_m = f.number(holds[n], "opening_length_m", p, 2.0, 60.0);
    h.open = f.flag(holds[n], "open", p, true);
    const double half = h.opening_length_m / 2 + 1.0;  // with its coamings and a cross deck
    h.centre_m = f.number(holds[n], "centre_m", p, -s.length_m / 2 + half, s.length_m / 2 - half);
    for (const auto& other : s.holds) {
      if (other.number == h.number) f.fail(holds[n]["hold"], p + ".hold", "hold listed twice");
      if (std::abs(other.centre_m - h.centre_m) < half + other.opening_length_m / 2 + 1.0)
        f.fail(holds[n]["centre_m"], p + ".centre_m", "overlaps hold " + std::to_string(other.number));
    }
    s.holds.push_back(h);
  }
  if (s.holds.empty()) f.fail(holds, at + ".holds", "a bulk carrier needs at least one hold");
  f.check_unknown_keys();
  return s;
}

}  // namespace

sim::SeaState read_sea_state(const YamlFile& f, const YAML::Node& sea, const std::string& at) {
  sim::SeaState s;
  s.heave_m = read_harmonics(f, sea, "heave", at, false);
  s.roll_rad = read_harmonics(f, sea, "roll", at, true);
  s.pitch_rad = read_harmonics(f, sea, "pitch", at, true);
  return s;
}

sim::VesselSettings load_vessel(const YamlFile& f) {
  const YAML::Node v = f.required(f.root(), "vessel", "");
  const std::string at = "vessel";
  sim::VesselSettings s;
  s.name = f.text(v, "name", at);
  s.length_m = f.number(v, "length_m", at, 20.0, 500.0);
  s.beam_m = f.number(v, "beam_m", at, 5.0, 80.0);
  s.depth_m = f.number(v, "depth_m", at, 2.0, 50.0);
  s.draught_m = f.number(v, "draught_m", at, 0.5, s.depth_m, false, true);
  s.tank_top_m = f.number(v, "tank_top_m", at, 0.0, s.depth_m, false, true);
  s.coaming_height_m = f.number(v, "coaming_height_m", at, 0.0, 5.0);
  if (f.optional(v, "kind", at)) {
    const std::string kind = f.text(v, "kind", at);
    if (kind == "bulk") return load_bulk_holds(f, v, at, s);
    if (kind != "container") f.fail(v["kind"], at + ".kind", "'" + kind + "' is neither container nor bulk");
  }
  s.rows = f.integer(v, "rows", at, 1, 30);
  s.row_pitch_m = f.number(v, "row_pitch_m", at, 2.5, 3.0);  // a 2.438 m box plus its guides
  s.hold_tiers = f.integer(v, "hold_tiers", at, 0, 12);
  s.deck_tiers = f.integer(v, "deck_tiers", at, 0, 10);
  if (s.rows * s.row_pitch_m + 1.0 > s.beam_m)
    f.fail(v["rows"], at + ".rows", "rows * row_pitch_m does not fit in the beam");
  if (s.tank_top_m + s.hold_tiers * s.tier_height_m > s.depth_m + s.coaming_height_m)
    f.fail(v["hold_tiers"], at + ".hold_tiers", "the hold tiers do not fit under the hatch covers");
  const YAML::Node guides = f.required(v, "cell_guides", at);
  s.cell_clearance_m = f.number(guides, "clearance_m", at + ".cell_guides", 0.0, 0.1, true);
  s.cell_guide_thickness_m = f.number(guides, "thickness_m", at + ".cell_guides", 0.0, 0.05, true);
  s.cell_guide_leg_m = f.number(guides, "leg_m", at + ".cell_guides", s.cell_guide_thickness_m, 0.5);
  if (2 * (s.cell_clearance_m + s.cell_guide_thickness_m) > s.row_pitch_m - 2.438)
    f.fail(guides, at + ".cell_guides", "two guides and their clearances do not fit between rows");
  const YAML::Node covers = f.required(v, "hatch_covers", at);
  s.hatch_panels = f.integer(covers, "panels", at + ".hatch_covers", 1, 2);
  if (s.hatch_panels == 2 && s.rows % 2 == 1)
    f.fail(covers["panels"], at + ".hatch_covers.panels", "two panels need an even number of rows");
  s.hatch_cover_mass_kg = f.number(covers, "mass_kg", at + ".hatch_covers", 0.0, 1e5, true);
  s.hatch_cover_thickness_m = f.number(covers, "thickness_m", at + ".hatch_covers", 0.0, 3.0, true);
  const YAML::Node bays = f.sequence(v, "bays", at);
  for (std::size_t n = 0; n < bays.size(); ++n) {
    const std::string p = at + ".bays[" + std::to_string(n) + "]";
    sim::VesselSettings::Bay b;
    b.number = f.integer(bays[n], "bay", p, 2, 98);
    if (b.number % 2 != 0) f.fail(bays[n]["bay"], p + ".bay", "40 ft bays have even numbers");
    b.centre_m = f.number(bays[n], "centre_m", p, -s.length_m / 2 + 7.0, s.length_m / 2 - 7.0);
    for (const auto& other : s.bays) {
      if (other.number == b.number) f.fail(bays[n]["bay"], p + ".bay", "bay listed twice");
      if (std::abs(other.centre_m - b.centre_m) < 13.5)
        f.fail(bays[n]["centre_m"], p + ".centre_m", "overlaps bay " + std::to_string(other.number));
    }
    s.bays.push_back(b);
  }
  if (s.bays.empty()) f.fail(bays, at + ".bays", "a vessel needs at least one bay");
  f.check_unknown_keys();
  return s;
}

sim::VesselSettings load_vessel(const std::string& path) {
  return load_vessel(YamlFile::load(path));
}

}  // namespace harbour::io
