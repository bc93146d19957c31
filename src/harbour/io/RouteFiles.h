#pragma once

#include <string>
#include <vector>

#include "harbour/io/YamlFile.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/training/Route.h"

namespace harbour::io {

/// Reads a training route (data/routes/*.yaml): training goals, each with its stages in order. A stage's
/// exercise is an exercise's name (looked up in `exercise_folders` in order: a centre's own, then the
/// shipped ones) or a path relative to the route's folder, and is read by the exercise loader; its metric
/// bounds must name figures that exercise's evaluation stores; prerequisites must name stages of the route
/// and form no cycle. Every error is a DataError naming the route file, the line and the field.
training::Route load_route(const YamlFile& file, const std::string& folder,
                           const std::vector<std::string>& exercise_folders);
training::Route load_route(const std::string& path, const std::vector<std::string>& exercise_folders);

/// Every route in `routes_folders` (*.yaml; a centre's own, then the shipped ones) by file name; the first
/// bad one throws, and so does a route name found in two folders (the records know a route by its name),
/// naming the first of the two.
std::vector<training::Route> load_routes(const std::vector<std::string>& routes_folders,
                                         const std::vector<std::string>& exercise_folders);

/// The names of the figures the records store for an attempt at `exercise` (sim::Metrics::rows() of its
/// evaluation, and the three skills), read off a real evaluation of one step of its simulation.
std::vector<std::string> stored_metric_names(const sim::ExerciseSettings& exercise);

/// The exercise file a stage names (see load_route), or "" when there is none.
std::string stage_exercise_file(const std::string& exercise, const std::string& route_folder,
                                const std::vector<std::string>& exercise_folders);

}  // namespace harbour::io
