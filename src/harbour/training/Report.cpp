#include "harbour/training/Report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "harbour/training/Figures.h"

namespace harbour::training {

namespace {

std::string number(double value, const char* format = "%.1f") {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string figure(const std::optional<double>& value, const char* format = "%.1f") {
  return value ? number(*value, format) : "–";
}

const char* const kStyle = R"(
@page { size: A4; margin: 14mm 12mm; }
body { font-family: "DejaVu Sans", sans-serif; font-size: 9.5pt; color: #1b1f24; }
h1 { font-size: 17pt; margin: 0 0 2pt; }
h2 { font-size: 12pt; margin: 14pt 0 4pt; border-bottom: 1px solid #9aa4ae; }
h3 { font-size: 10pt; margin: 8pt 0 3pt; }
.sub { color: #56606b; margin: 0 0 8pt; }
table { border-collapse: collapse; width: 100%; margin-bottom: 4pt; }
th, td { border-bottom: 1px solid #d5dae0; padding: 2pt 4pt; text-align: left; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }
tr { page-break-inside: avoid; }
.passed { color: #1c7c3c; } .blocked { color: #b3261e; } .open { color: #1f5fa8; } .locked { color: #6b7580; }
svg { display: block; margin: 2pt 0 6pt; }
)";

std::string head(const std::string& title) {
  return "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + escape_html(title) +
         "</title><style>" + kStyle + "</style></head><body>\n";
}

// a table's row; a header row (`th`) is the table's head, which a printed table repeats on every page
std::string row(const std::vector<std::string>& cells, const std::vector<bool>& numeric,
                const char* tag = "td") {
  const bool head = std::string_view(tag) == "th";
  std::string out = head ? "<thead><tr>" : "<tr>";
  for (std::size_t i = 0; i < cells.size(); ++i)
    out += std::string("<") + tag + (i < numeric.size() && numeric[i] ? " class=\"n\">" : ">") + cells[i] +
           "</" + tag + ">";
  return out + (head ? "</tr></thead>\n" : "</tr>\n");
}

std::string routes_section(const std::vector<RouteStanding>& routes) {
  std::string out;
  for (const RouteStanding& r : routes) {
    out += "<h3>" + escape_html(r.route.name) + " (" + escape_html(r.route.id) + "): " +
           (r.progress.complete ? std::string("complete")
            : r.progress.next   ? "next stage " + escape_html(*r.progress.next)
                                : std::string("waiting for an instructor")) +
           "</h3>\n<table>\n";
    const std::vector<bool> numeric = {false, false, false, true, true, true};
    out += row({"Stage", "Goal", "State", "Attempts", "Passes", "Best score"}, numeric, "th");
    for (std::size_t i = 0; i < r.progress.stages.size() && i < r.route.stages.size(); ++i) {
      const StageProgress& s = r.progress.stages[i];
      const std::string state = state_name(s.state);
      out +=
          row({escape_html(s.stage), escape_html(r.route.stages[i].goal),
               "<span class=\"" + state + "\">" + state + (s.signed_off ? " (signed off)" : "") + "</span>",
               std::to_string(s.attempts) + " / " + std::to_string(s.attempts_allowed),
               std::to_string(s.passes) + " / " + std::to_string(r.route.stages[i].repetitions),
               figure(s.best_score)},
              numeric);
    }
    out += "</table>\n";
  }
  return out.empty() ? "<p>Not enrolled in a route.</p>\n" : out;
}

}  // namespace

std::string escape_html(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string svg_plot(const std::vector<Series>& series, double y_min, double y_max,
                     const std::string& title) {
  constexpr double kWidth = 640, kHeight = 200, kLeft = 40, kRight = 130, kTop = 18, kBottom = 26;
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  std::size_t n = 0;
  for (const Series& s : series)
    n = std::max(n, s.values.size());
  const auto x_of = [&](std::size_t i) {
    return n <= 1 ? kLeft + plot_w / 2 : kLeft + plot_w * static_cast<double>(i) / static_cast<double>(n - 1);
  };
  const auto y_of = [&](double v) {
    const double t = (std::clamp(v, y_min, y_max) - y_min) / (y_max - y_min);
    return kTop + plot_h * (1.0 - t);
  };
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + number(kWidth, "%.0f") +
                    "\" height=\"" + number(kHeight, "%.0f") + "\" viewBox=\"0 0 " + number(kWidth, "%.0f") +
                    " " + number(kHeight, "%.0f") + "\" font-size=\"10\" font-family=\"DejaVu Sans\">";
  out += "<text x=\"" + number(kLeft, "%.0f") + "\" y=\"12\" font-weight=\"bold\">" + escape_html(title) +
         "</text>";
  for (int tick = 0; tick <= 4; ++tick) {
    const double v = y_min + (y_max - y_min) * tick / 4.0, y = y_of(v);
    out += "<line x1=\"" + number(kLeft) + "\" x2=\"" + number(kLeft + plot_w) + "\" y1=\"" + number(y) +
           "\" y2=\"" + number(y) + "\" stroke=\"#d5dae0\"/>";
    out += "<text x=\"" + number(kLeft - 4) + "\" y=\"" + number(y + 3) + "\" text-anchor=\"end\">" +
           number(v, "%g") + "</text>";
  }
  const std::size_t label_every = std::max<std::size_t>(1, (n + 9) / 10);
  for (std::size_t i = 0; i < n; i += label_every)
    out += "<text x=\"" + number(x_of(i)) + "\" y=\"" + number(kTop + plot_h + 12) +
           "\" text-anchor=\"middle\">" + std::to_string(i + 1) + "</text>";
  out += "<text x=\"" + number(kLeft + plot_w / 2) + "\" y=\"" + number(kHeight - 2) +
         "\" text-anchor=\"middle\" fill=\"#56606b\">attempt</text>";
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    std::string points;
    for (std::size_t i = 0; i < s.values.size(); ++i)
      points += (i ? " " : "") + number(x_of(i)) + "," + number(y_of(s.values[i]));
    const std::string colour = escape_html(s.colour);
    // the first series widest, so that a later one on the same values still shows the earlier beneath
    const double width = 2.0 + 1.5 * static_cast<double>(series.size() - 1 - k);
    out += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"" + number(width) +
           "\" points=\"" + points + "\"/>";
    for (std::size_t i = 0; i < s.values.size(); ++i)
      out += "<circle cx=\"" + number(x_of(i)) + "\" cy=\"" + number(y_of(s.values[i])) +
             "\" r=\"3\" fill=\"" + colour + "\"/>";
    const double ly = kTop + 10 + 16 * static_cast<double>(k);
    out += "<rect x=\"" + number(kWidth - kRight + 12) + "\" y=\"" + number(ly - 8) +
           "\" width=\"14\" height=\"8\" fill=\"" + colour + "\"/><text x=\"" + number(kWidth - kRight + 30) +
           "\" y=\"" + number(ly) + "\">" + escape_html(s.name) + "</text>";
  }
  return out + "</svg>";
}

std::string trainee_report_html(const TraineeReportData& d) {
  std::vector<const AttemptFigures*> finished;
  for (const AttemptFigures& a : d.attempts)
    if (a.status == "finished" && a.score) finished.push_back(&a);
  const TraineeSummary summary = class_overview(d.attempts, {d.trainee}).front();

  std::string out = head("Trainee report: " + d.name);
  out += "<h1>Trainee report: " + escape_html(d.name) + "</h1>\n<p class=\"sub\">Trainee " +
         escape_html(d.trainee) + " · generated " + escape_html(d.generated_at) + " · harboursim</p>\n";
  out += "<table>\n";
  const std::vector<bool> numeric(6, true);
  out += row(
      {"Attempts", "Finished", "Passed", "Best score", "Mean of the last 3", "Trend (points per attempt)"},
      numeric, "th");
  out +=
      row({std::to_string(summary.attempts), std::to_string(summary.finished), std::to_string(summary.passed),
           figure(summary.best_score), figure(summary.recent_score), figure(summary.trend, "%+.1f")},
          numeric);
  out += "</table>\n";

  out += "<h2>Evolution</h2>\n";
  if (finished.empty()) {
    out += "<p>No finished attempt yet.</p>\n";
  } else {
    Series score{"score", "#1f77b4", {}};
    Series skills[3] = {
        {"safety", "#d62728", {}}, {"precision", "#2ca02c", {}}, {"productivity", "#ff7f0e", {}}};
    static const char* const names[3] = {"skill_safety", "skill_precision", "skill_productivity"};
    for (const AttemptFigures* a : finished) {
      score.values.push_back(*a->score);
      for (int k = 0; k < 3; ++k) {
        const auto found = a->metrics.find(names[k]);
        skills[k].values.push_back(found == a->metrics.end() ? 0.0 : found->second);
      }
    }
    out += svg_plot({score}, 0, 100, "Score over finished attempts") + "\n";
    out += svg_plot({skills[0], skills[1], skills[2]}, 0, 100, "Skills over finished attempts") + "\n";
  }

  out += "<h2>Training routes</h2>\n" + routes_section(d.routes);

  out += "<h2>Attempts</h2>\n<table>\n";
  const std::vector<bool> attempt_numeric = {true, false, false, false, false, true, false, true, true};
  out += row({"#", "Exercise", "Version", "Stage", "Status", "Score", "Passed", "Time [s]", "Collisions"},
             attempt_numeric, "th");
  for (const AttemptFigures& a : d.attempts) {
    const auto metric = [&](const char* name) {
      const auto found = a.metrics.find(name);
      return found == a.metrics.end() ? std::string("–") : number(found->second, "%.0f");
    };
    out += row({std::to_string(a.id), escape_html(a.exercise), escape_html(a.exercise_version.substr(0, 8)),
                escape_html(a.route.empty() ? "" : a.route + "/" + a.stage), escape_html(a.status),
                figure(a.score), a.passed ? "yes" : "no", metric("time_s"), metric("collisions")},
               attempt_numeric);
  }
  out += "</table>\n";

  out +=
      "<h2>Standing in the cohort</h2>\n<p class=\"sub\">The trainee's best on each figure of each exercise "
      "version, and its place among every trainee's best there.</p>\n<table>\n";
  const std::vector<bool> standing_numeric = {false, false, false, true, true, true};
  out += row({"Exercise", "Figure", "Better", "Best", "Place", "Trainees"}, standing_numeric, "th");
  for (const Standing& s : d.standings)
    out += row({escape_html(s.exercise) + " <span class=\"sub\">" +
                    escape_html(s.exercise_version.substr(0, 8)) + "</span>",
                escape_html(figure_words(s.figure).label), s.higher_better ? "higher" : "lower",
                escape_html(figure_text(s.figure, s.best)), place_words(s.place, s.trainees, s.tied),
                std::to_string(s.trainees)},
               standing_numeric);
  out += "</table>\n</body></html>\n";
  return out;
}

std::string class_report_html(const ClassReportData& d) {
  std::string out = head("Class report");
  out += "<h1>Class report</h1>\n<p class=\"sub\">" + std::to_string(d.lines.size()) +
         " trainees · generated " + escape_html(d.generated_at) + " · harboursim</p>\n<table>\n";
  const std::vector<bool> numeric = {false, false, true, true, true, true, true, true, true, true, true};
  out += row({"Trainee", "Name", "Attempts", "Passed", "Best", "Last 3", "Trend", "Safety", "Precision",
              "Productivity"},
             numeric, "th");
  for (std::size_t i = 0; i < d.lines.size(); ++i) {
    const TraineeSummary& s = d.lines[i];
    out += row({escape_html(s.trainee), escape_html(i < d.names.size() ? d.names[i] : ""),
                std::to_string(s.attempts), std::to_string(s.passed) + " / " + std::to_string(s.finished),
                figure(s.best_score), figure(s.recent_score), figure(s.trend, "%+.1f"),
                figure(s.recent_skills[0]), figure(s.recent_skills[1]), figure(s.recent_skills[2])},
               numeric);
  }
  out +=
      "</table>\n<p class=\"sub\">Last 3: the mean score of the last three finished attempts, the skills "
      "likewise; trend: the least-squares slope of the score over the finished attempts.</p>\n";

  // bars: best and recent score per trainee
  out += "<h2>Scores</h2>\n";
  const double bar_h = 14, left = 120, width = 640, plot_w = width - left - 60;
  const double height = 24 + bar_h * 2.4 * static_cast<double>(d.lines.size());
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"" + number(height, "%.0f") +
         "\" font-size=\"10\" font-family=\"DejaVu Sans\">";
  out += "<rect x=\"" + number(left) + "\" y=\"2\" width=\"12\" height=\"8\" fill=\"#1f77b4\"/><text x=\"" +
         number(left + 16) + "\" y=\"10\">best</text><rect x=\"" + number(left + 70) +
         "\" y=\"2\" width=\"12\" height=\"8\" fill=\"#9ecae1\"/><text x=\"" + number(left + 86) +
         "\" y=\"10\">mean of the last 3</text>";
  for (std::size_t i = 0; i < d.lines.size(); ++i) {
    const double y = 18 + bar_h * 2.4 * static_cast<double>(i);
    const TraineeSummary& s = d.lines[i];
    out += "<text x=\"" + number(left - 6) + "\" y=\"" + number(y + bar_h) + "\" text-anchor=\"end\">" +
           escape_html(s.trainee) + "</text>";
    const auto bar = [&](const std::optional<double>& v, double top, const char* colour) {
      if (!v) return std::string();
      const double w = plot_w * std::clamp(*v, 0.0, 100.0) / 100.0;
      return "<rect x=\"" + number(left) + "\" y=\"" + number(top) + "\" width=\"" + number(w) +
             "\" height=\"" + number(bar_h) + "\" fill=\"" + colour + "\"/><text x=\"" +
             number(left + w + 4) + "\" y=\"" + number(top + bar_h - 3) + "\">" + number(*v) + "</text>";
    };
    out += bar(s.best_score, y, "#1f77b4") + bar(s.recent_score, y + bar_h, "#9ecae1");
  }
  out += "</svg>\n";

  out += "<h2>Training routes</h2>\n<table>\n";
  const std::vector<bool> route_numeric = {false, false, true, false};
  out += row({"Trainee", "Route", "Stages passed", "Next"}, route_numeric, "th");
  for (std::size_t i = 0; i < d.lines.size() && i < d.routes.size(); ++i) {
    for (const RouteStanding& r : d.routes[i]) {
      int passed = 0;
      for (const StageProgress& s : r.progress.stages)
        passed += s.state == StageState::kPassed ? 1 : 0;
      out += row({escape_html(d.lines[i].trainee), escape_html(r.route.name),
                  std::to_string(passed) + " / " + std::to_string(r.progress.stages.size()),
                  r.progress.complete ? std::string("complete")
                  : r.progress.next   ? escape_html(*r.progress.next)
                                      : std::string("<span class=\"blocked\">blocked</span>")},
                 route_numeric);
    }
  }
  out += "</table>\n";
  if (std::all_of(d.routes.begin(), d.routes.end(), [](const auto& r) { return r.empty(); }))
    out += "<p>No trainee is enrolled in a route.</p>\n";
  out += "</body></html>\n";
  return out;
}

}  // namespace harbour::training
