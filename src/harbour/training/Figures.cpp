#include "harbour/training/Figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace harbour::training {

namespace {

constexpr double kToDegrees = 180.0 / std::numbers::pi;

FigureWords count(const char* name, const char* label, const char* about, bool higher_better = false) {
  return {name, label, "", 1.0, 3, higher_better, about};
}
FigureWords measured(const char* name, const char* label, const char* unit, double scale, const char* about,
                     bool higher_better = false) {
  return {name, label, unit, scale, 3, higher_better, about};
}

}  // namespace

const std::vector<FigureWords>& figure_table() {
  static const std::vector<FigureWords> table = {
      measured("score", "score", "", 1.0, "100 points less the deductions", true),
      measured("skill_safety", "safety", "", 1.0, "100 less the deductions against safety", true),
      measured("skill_precision", "precision", "", 1.0, "100 less the deductions against precision", true),
      measured("skill_productivity", "productivity", "", 1.0, "100 less the deductions against productivity",
               true),
      measured("time_s", "time", "s", 1.0, "simulated time from the start to the end of the attempt"),
      count("moves_completed", "moves completed", "goal moves set down within tolerance", true),
      measured("moves_per_hour", "moves per hour", "moves/h", 1.0, "moves completed per hour of the attempt",
               true),
      measured("delivered_t", "delivered", "t", 1.0, "bulk material landed in the hopper", true),
      measured("handled_t", "handled", "t", 1.0, "bulk material lifted by the grab", true),
      measured("tonnes_per_hour", "tonnes per hour", "t/h", 1.0, "delivered tonnes per hour", true),
      count("bites", "bites", "times the grab closed on material"),
      measured("mean_bite_fill", "mean bite fill", "%", 100.0, "the grab's mean fill at closing", true),
      count("poor_bites", "poor bites", "bites that filled the grab less than the rules ask"),
      measured("pile_top_m", "pile top", "m", 1.0, "the heap's highest point at the end (trimming)"),
      count("collisions", "collisions", "impacts of the load, the spreader or the machine"),
      measured("worst_collision_mps", "worst collision speed", "m/s", 1.0,
               "the fastest impact's closing speed"),
      measured("collision_impulse_ns", "collision impulse", "kN·s", 1e-3, "the impacts' summed impulse"),
      count("container_collisions", "box collisions", "impacts against boxes, hatch covers or stacks"),
      count("cell_guide_collisions", "cell guide collisions", "impacts against a hold's cell guides"),
      count("ship_collisions", "ship collisions", "impacts against the hull or the coamings"),
      count("vehicle_collisions", "vehicle collisions", "impacts against a truck, vehicle or trailer"),
      count("twistlock_misuse", "twistlock misuse", "locks worked out of turn, or a lift unlocked"),
      count("overloads", "rope overloads", "a hoist rope past its working load"),
      count("emergency_stops", "emergency stops", "the emergency stop pressed"),
      count("signals", "signals given", "the signaller's hand signals to the operator"),
      count("late_signals", "signals followed late",
            "signals not followed at the controls in time, or never"),
      count("late_stop_signals", "stop signals followed late", "stop signals not followed in time, or never"),
      measured("worst_signal_delay_s", "slowest signal to action", "s", 1.0,
               "the longest from a signal to the controls following it"),
      measured("mean_signal_delay_s", "mean signal to action", "s", 1.0,
               "the mean time from a signal to the controls following it"),
      count("unwarned_gantry_travel", "gantry travel without the horn", "gantry moves with no horn before"),
      count("load_drops", "loads dropped", "loads that fell"),
      count("lifts_under_fault", "lifts with the brake failed", "hoisting with the hoist brake failed"),
      count("stopped_after_fault", "stopped after the fault", "1 when the machine was taken out of service",
            true),
      measured("fault_set_down_s", "set down after the fault", "s", 1.0,
               "time from the fault to the load set down"),
      count("limiter_trips", "load-moment limiter trips", "the limiter stopped a motion"),
      count("pad_lift_offs", "outrigger pad lift-offs", "an outrigger pad left the ground"),
      count("jackknifes", "jack-knifes", "the trailer folded past the safe angle"),
      count("tip_overs", "tip-overs", "the vehicle or its load tipped"),
      count("overspeeds", "speeding", "the terminal's speed limit exceeded"),
      measured("worst_overspeed_kmh", "worst overspeed", "km/h", 1.0, "the most over the limit"),
      count("hard_landings", "hard landings", "set-downs faster than the rules allow"),
      measured("worst_landing_mps", "worst landing speed", "m/s", 1.0,
               "the fastest set-down's closing speed"),
      count("sway_landings", "landings while swaying", "landings with the load swinging past the limit"),
      count("swinging_releases", "discharges while swinging", "the grab opened while swinging"),
      measured("worst_release_swing_m", "worst swing at discharge", "m", 1.0,
               "the grab's swing when it opened"),
      measured("worst_placement_offset_m", "worst placement offset", "cm", 100.0,
               "the farthest a set-down box landed from its target"),
      measured("worst_placement_skew_deg", "worst placement skew", "°", 1.0, "a set-down box's largest skew"),
      count("limit_hits", "limit switch hits", "a motion driven into its end limit"),
      measured("spilled_t", "spilled", "t", 1.0, "material dropped outside the hopper"),
      measured("spilled_percent", "spilled share", "%", 1.0, "spilled of handled"),
      measured("hoist_energy_j", "hoist energy", "MJ", 1e-6, "work the hoist drum delivered"),
      measured("travel_energy_j", "travel energy", "MJ", 1e-6,
               "work the gantry and trolley drives delivered"),
      measured("*_rms_jerk_mps3", "{axis} jerk (RMS)", "m/s³", 1.0, "how smoothly the {axis} was driven"),
      count("*_harsh_moves", "{axis} harsh moves", "{axis} moves with a jerk past the rules' limit"),
      count("instructor_disruptions", "instructor disruptions", "faults and holds the instructor imposed"),
      count("team_near_misses", "near misses (team)", "members' machines closer than the safe distance"),
      count("team_contacts", "contacts (team)", "members' machines touching"),
      measured("team_closest_m", "closest approach (team)", "m", 1.0, "the nearest another member came"),
      count("team_hand_offs", "hand-offs (team)", "boxes handed to another member", true),
      measured("team_worst_hand_off_ms", "slowest hand-off (team)", "ms", 1.0,
               "from set-down to the other station taking the box"),
      measured("team_waited_s", "waited (team)", "s", 1.0, "time spent waiting for another member"),
  };
  return table;
}

namespace {

struct SuffixUnit {
  const char* suffix;
  const char* unit;
  double scale;
};
// a name the table does not know: its unit from its suffix (the simulator's SI as stored)
constexpr SuffixUnit kSuffixUnits[] = {
    {"_mps3", "m/s³", 1.0}, {"_mps2", "m/s²", 1.0}, {"_mps", "m/s", 1.0}, {"_kmh", "km/h", 1.0},
    {"_ns", "N·s", 1.0},    {"_kn", "kN", 1.0},     {"_ms", "ms", 1.0},   {"_n", "N", 1.0},
    {"_j", "kJ", 1e-3},     {"_kg", "kg", 1.0},     {"_deg", "°", 1.0},   {"_rad", "°", kToDegrees},
    {"_m3", "m³", 1.0},     {"_s", "s", 1.0},       {"_m", "m", 1.0},     {"_t", "t", 1.0}};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string spaced(std::string s) {
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

std::string with_axis(std::string text, const std::string& axis) {
  for (std::size_t at = text.find("{axis}"); at != std::string::npos; at = text.find("{axis}"))
    text.replace(at, 6, axis);
  return text;
}

}  // namespace

std::size_t figure_order(const std::string& name) {
  const std::vector<FigureWords>& table = figure_table();
  for (std::size_t n = 0; n < table.size(); ++n) {
    const std::string& row = table[n].name;
    if (row == name || (row.front() == '*' && name.size() > row.size() - 1 && ends_with(name, row.substr(1))))
      return n;
  }
  return table.size();
}

FigureWords figure_words(const std::string& name) {
  const std::vector<FigureWords>& table = figure_table();
  if (const std::size_t n = figure_order(name); n < table.size()) {
    FigureWords row = table[n];
    if (row.name == name) return row;
    // a per-axis row ("*_harsh_moves"): the axis is the name before the row's tail
    const std::string axis = spaced(name.substr(0, name.size() - (row.name.size() - 1)));
    row.name = name;
    row.label = with_axis(row.label, axis);
    row.about = with_axis(row.about, axis);
    return row;
  }
  FigureWords made{name, spaced(name), "", 1.0, 3, false, ""};
  for (const SuffixUnit& u : kSuffixUnits)
    if (name.size() > std::string(u.suffix).size() && ends_with(name, u.suffix)) {
      made.label = spaced(name.substr(0, name.size() - std::string(u.suffix).size()));
      made.unit = u.unit;
      made.scale = u.scale;
      break;
    }
  return made;
}

std::string figure_text(const FigureWords& words, double stored) {
  const double shown = stored * words.scale;
  char text[64];
  if (!std::isfinite(shown)) {
    std::snprintf(text, sizeof text, "–");
    return text;
  }
  // the figure's significant digits, nothing below a thousandth, no trailing zeros
  const double magnitude = shown == 0.0 ? 0.0 : std::floor(std::log10(std::abs(shown)));
  const int decimals = std::clamp(words.digits - 1 - static_cast<int>(magnitude), 0, 3);
  std::snprintf(text, sizeof text, "%.*f", decimals, shown);
  std::string out = text;
  if (out.find('.') != std::string::npos) {
    while (out.back() == '0')
      out.pop_back();
    if (out.back() == '.') out.pop_back();
  }
  if (out == "-0") out = "0";
  return words.unit.empty() ? out : out + (words.unit == "°" || words.unit == "%" ? "" : " ") + words.unit;
}

namespace {
struct EventWords {
  const char* kind;
  const char* label;
  const char* value_words;  ///< "at", "by"; nullptr: the event carries no value worth saying
  const char* unit;
};
constexpr EventWords kEventWords[] = {
    {"collision", "collision", "at", "m/s"},
    {"hard_landing", "hard landing", "at", "m/s"},
    {"sway_landing", "landing while swaying", nullptr, ""},
    {"twistlock_misuse", "twistlock misuse", nullptr, ""},
    {"rope_overload", "rope overload", nullptr, ""},
    {"limit_switch_hit", "limit switch hit", nullptr, ""},
    {"emergency_stop", "emergency stop", nullptr, ""},
    {"gantry_travel_without_horn", "gantry travel without the horn", nullptr, ""},
    {"limiter_trip", "load-moment limiter trip", nullptr, ""},
    {"pad_lift_off", "outrigger pad lift-off", nullptr, ""},
    {"poor_bite", "poor bite", nullptr, ""},
    {"swinging_release", "discharge while swinging", nullptr, ""},
    {"jackknife", "jack-knife", nullptr, ""},
    {"tip_over", "tip-over", nullptr, ""},
    {"speeding", "speeding", "worst so far", "km/h over"},
    {"load_drop", "load dropped", nullptr, ""},
    {"lift_under_fault", "lift with the hoist brake failed", nullptr, ""},
    {"late_stop_signal", "stop signal followed late", nullptr, ""},
    {"device_connected", "control device connected", nullptr, ""},
    {"device_lost", "control device lost", nullptr, ""},
};
}  // namespace

std::string event_text(const std::string& kind, double value, const std::string& text) {
  const auto words = [](std::string s) {
    std::replace(s.begin(), s.end(), '-', ' ');
    std::replace(s.begin(), s.end(), '_', ' ');
    return s;
  };
  static const std::string kInstructor = "instructor ";
  if (kind.rfind(kInstructor, 0) == 0)  // a command the instructor gave, by its command-line name
    return "instructor: " + words(kind.substr(kInstructor.size()));
  if (kind == "instructor") return "instructor: " + words(text);  // a station's: "hoist-brake-fault by ines"
  if (kind == "move_done") return "move " + figure_text("moves_completed", value) + " done";
  if (kind == "attempt_end") {  // its text the attempt's status, its value the score
    const std::string how = text == "finished"              ? "finished"
                            : text == "ended_by_instructor" ? "ended by the instructor"
                                                            : words(text);
    return "attempt " + how + ", score " + figure_text("score", value);
  }
  if (kind == "start_failed") return "could not start: " + text;
  for (const EventWords& e : kEventWords)
    if (kind == e.kind) {
      const std::string said = text.empty() ? "" : ": " + text;
      if (!e.value_words || value == 0.0) return e.label + said;
      const FigureWords shown{kind, e.label, e.unit, 1.0, 3, false, ""};
      return std::string(e.label) + " " + e.value_words + " " + figure_text(shown, value) + said;
    }
  return spaced(kind) + (text.empty() ? "" : ": " + text);
}

std::string figure_text(const std::string& name, double stored) {
  return figure_text(figure_words(name), stored);
}

}  // namespace harbour::training
