#pragma once

#include <string>
#include <vector>

#include "harbour/io/YamlFile.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/training/Route.h"

namespace harbour::io {

/// Reads a training route (data/routes/*.yaml): training goals, each with its stages in order. A stage's
/// exercise is a shipped exercise's name (looked up in `exercises_folder`) or a path relative to the route's
/// folder, and is read by the exercise loader; its metric bounds must name figures that exercise's
/// evaluation stores; prerequisites must name stages of the route and form no cycle. Every error is a
/// DataError naming the route file, the line and the field.
training::Route load_route(const YamlFile& file, const std::string& folder,
                           const std::string& exercises_folder);
training::Route load_route(const std::string& path, const std::string& exercises_folder);

/// Every route in `routes_folder` (*.yaml) by file name; the first bad one throws.
std::vector<training::Route> load_routes(const std::string& routes_folder,
                                         const std::string& exercises_folder);

/// The names of the figures the records store for an attempt at `exercise` (sim::Metrics::rows() of its
/// evaluation, and the three skills), read off a real evaluation of one step of its simulation.
std::vector<std::string> stored_metric_names(const sim::ExerciseSettings& exercise);

/// The exercise file a stage names (see load_route), or "" when there is none.
std::string stage_exercise_file(const std::string& exercise, const std::string& route_folder,
                                const std::string& exercises_folder);

}  // namespace harbour::io
