// The console's exercise designer and route editor: a source to start from, a design checked or saved.
#include "harbour/console/ConsoleServer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/io/TeamFiles.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/records/Reports.h"
#include "harbour/sim/MachineType.h"
#include "harbour/training/Figures.h"

namespace harbour::console {

std::optional<Console::Response> Console::design_source(Call& c) {
  const std::string name = query_param(c.query, "exercise");
  for (const std::string& folder : centre().exercise_folders()) {
    try {
      const std::string text = console::design_source(folder, name);
      return json_reply(c.request, http::status::ok,
                        {{"exercise", name}, {"text", text}, {"designed", designed(text)}});
    } catch (const std::out_of_range&) {
    }
  }
  return error(c.request, http::status::not_found, "no exercise '" + core::printable(name) + "'");
}

std::optional<Console::Response> Console::check_or_save_design(Call& c) {
  std::string why;
  const std::optional<json> body = parse_object(c.request.body(), why);
  const auto text = body ? body->find("text") : json::const_iterator{};
  if (!body || text == body->end() || !text->is_string())
    return error(c.request, http::status::bad_request, body ? "field 'text': the exercise's YAML" : why);
  const bool save = c.target == "/api/designer/save";
  // the loader and the preview's world run beside the console's thread: a slow or hostile design holds up
  // nobody else
  beside(c, checks_, kMostChecksAtOnce, kCheckBudget,
         [this, save, folder = exercise_folder(), yaml = text->get<std::string>(), request = c.request,
          account = c.account->name]() -> Finish {
           DesignCheck design;
           try {
             design = check_design(folder, yaml);
           } catch (const std::invalid_argument& e) {
             return [this, request, why = std::string(e.what())] {
               return error(request, http::status::unprocessable_entity, why);
             };
           }
           if (save)
             return [this, request, account, design] {
               std::string file;
               try {
                 file = save_design(exercise_folder(), design);
               } catch (const std::logic_error& e) {
                 return error(request, http::status::conflict, e.what());
               }
               audit_.add(account, "save_exercise", design.exercise.name, design.version);
               return json_reply(
                   request, http::status::created,
                   {{"exercise", design.exercise.name}, {"version", design.version}, {"file", file}});
             };
           json preview;
           try {
             preview = design_preview(folder, design);
           } catch (const std::exception& e) {
             return [this, request, why = std::string(e.what())] {
               return error(request, http::status::unprocessable_entity,
                            "the design loads but its world cannot be built: " + why);
             };
           }
           return [this, request, preview = std::move(preview)] {
             return json_reply(request, http::status::ok, preview);
           };
         });
  return std::nullopt;
}

std::optional<Console::Response> Console::route_text(Call& c) {
  const std::string id = query_param(c.query, "route");
  try {
    const std::string text = route_source(centre(), id);
    return json_reply(c.request, http::status::ok,
                      {{"route", id}, {"text", text}, {"designed", designed(text)}});
  } catch (const std::out_of_range& e) {
    return error(c.request, http::status::not_found, e.what());
  }
}

std::optional<Console::Response> Console::check_or_save_route(Call& c) {
  const auto& request = c.request;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const auto id = body->find("id"), text = body->find("text");
  if (id == body->end() || !id->is_string())
    return error(request, http::status::bad_request, "field 'id': the route's file name");
  if (text == body->end() || !text->is_string())
    return error(request, http::status::bad_request, "field 'text': the route's YAML");
  const bool save = c.target == "/api/routes/save";
  beside(c, checks_, kMostChecksAtOnce, kCheckBudget,
         [this, save, folders = centre(), id = id->get<std::string>(), yaml = text->get<std::string>(),
          request, account = c.account->name]() -> Finish {
           RouteCheck route;
           try {
             route = check_route_text(folders, id, yaml);
           } catch (const std::invalid_argument& e) {
             return [this, request, why = std::string(e.what())] {
               return error(request, http::status::unprocessable_entity, why);
             };
           }
           json stages = route_json(route.route);
           for (std::size_t n = 0; n < route.route.stages.size(); ++n)
             stages["stages"][n]["exercise_version"] =
                 io::exercise_version(route.route.stages[n].exercise_file);
           return [this, save, request, account, route, stages = std::move(stages)]() mutable {
             // people pick a route by its title: another route's is refused (the console's routes: its
             // thread)
             for (const training::Route& other : routes_)
               if (other.id != route.route.id && other.name == route.route.name)
                 return error(request, http::status::unprocessable_entity,
                              "route.name: '" + route.route.name + "' is also the name of route '" +
                                  other.id + "': give this route a name of its own");
             if (!save) return json_reply(request, http::status::ok, stages);
             return save_route_now(request, account, route, std::move(stages));
           };
         });
  return std::nullopt;
}

Console::Response Console::save_route_now(const http::request<http::string_body>& request,
                                          const std::string& account, const RouteCheck& route, json stages) {
  const std::string file_name = route.route.id + ".yaml";
  std::string file, before;
  try {
    before = route_source(centre(), route.route.id);
  } catch (const std::out_of_range&) {
  }
  try {
    file = save_route(centre(), route);
  } catch (const std::logic_error& e) {
    return error(request, http::status::conflict, e.what());
  }
  // the console's routes with it; should another file of the folder spoil them, the save is undone
  try {
    routes_ = records::load_centre_routes(centre());
  } catch (const std::exception& e) {
    std::error_code ec;
    if (before.empty())
      std::filesystem::remove(file, ec);
    else
      std::ofstream(file, std::ios::binary) << before;
    return error(request, http::status::unprocessable_entity,
                 std::string("saved, the centre's routes no longer load, so it was undone: ") + e.what());
  }
  audit_.add(account, "save_route", route.route.id, file_name);
  stages["file"] = file;
  return json_reply(request, http::status::created, stages);
}

}  // namespace harbour::console
