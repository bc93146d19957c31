#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harbour/training/Cohort.h"
#include "harbour/training/Route.h"

namespace harbour::training {

/// A line series of a report plot: a value per finished attempt, in order.
struct Series {
  std::string name;
  std::string colour;  ///< a CSS colour ("#1f77b4")
  std::vector<double> values;
};

/// An SVG line plot of `series` over the attempt index 1..n, the y axis from y_min to y_max, with a legend:
/// a self-contained element a report (HTML, then PDF) embeds as it is.
std::string svg_plot(const std::vector<Series>& series, double y_min, double y_max, const std::string& title);

/// `text` with &, <, >, " and ' as HTML entities.
std::string escape_html(const std::string& text);

/// A trainee's route and where they stand on it.
struct RouteStanding {
  Route route;
  RouteProgress progress;
};

/// What a trainee's report holds; `attempts` are theirs, oldest first.
struct TraineeReportData {
  std::string trainee, name;
  std::string generated_at;  ///< UTC, as printed
  std::vector<AttemptFigures> attempts;
  std::vector<Standing> standings;
  std::vector<RouteStanding> routes;
};

/// What a class report holds: every trainee's line, name and routes.
struct ClassReportData {
  std::string generated_at;
  std::vector<TraineeSummary> lines;
  std::vector<std::string> names;                  ///< per line
  std::vector<std::vector<RouteStanding>> routes;  ///< per line
};

/// The report pages as self-contained HTML (inline CSS and SVG plots, no script), laid out for A4: the
/// console serves them, and chromium prints them to PDF.
std::string trainee_report_html(const TraineeReportData& data);
std::string class_report_html(const ClassReportData& data);

}  // namespace harbour::training
