#include "harbour/debrief/Screenshot.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/ig/ImageGenerator.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/MachineDataFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/records/Centre.h"
#include "harbour/sim/Pilot.h"

namespace harbour::debrief {

int take_screenshot(const ScreenshotOptions& options) {
  if (const std::string why = io::why_not_writable(options.out); !why.empty())
    throw std::runtime_error("--out " + options.out + ": " + why);
  const sim::ExerciseSettings exercise =
      records::load_resolved_exercise(records::resolve_exercise(options.exercise));
  sim::Simulation simulation(exercise.scenario);
  // a scripted operator drives the exercises it can (container moves, grab deliveries); else the levers rest
  std::unique_ptr<sim::Pilot> pilot;
  if (sim::why_no_pilot(exercise).empty()) pilot = sim::make_pilot(exercise);
  using Kind = sim::InstructorCommand::Kind;
  for (const auto& [kind, value] :
       {std::pair{Kind::kSetTimeOfDay, options.time_of_day_h},
        std::pair{Kind::kSetVisibility, options.visibility_m},
        std::pair{Kind::kSetRain, options.rain_mm_per_h}, std::pair{Kind::kSetCloud, options.cloud_oktas}}) {
    if (!value) continue;
    sim::InstructorCommand c;
    c.kind = kind;
    c.value = *value;
    simulation.command(c);
  }
  std::vector<io::TimedCommand> commands;
  for (const std::string& text : options.commands)
    commands.push_back(io::parse_instructor_command(text));  // a bad one stops it before it starts
  std::stable_sort(commands.begin(), commands.end(),
                   [](const io::TimedCommand& a, const io::TimedCommand& b) { return a.at_s < b.at_s; });
  std::size_t next_command = 0;
  while (simulation.time_s() < options.at_s && !simulation.diverged()) {
    for (; next_command < commands.size() && commands[next_command].at_s <= simulation.time_s();
         ++next_command)
      simulation.command(commands[next_command].command);
    simulation.step(pilot ? pilot->next(simulation) : simulation.control_table().neutral());
  }
  const std::string data = records::shipped_data_folder();
  ig::Looks looks = ig::load_looks(options.looks.empty() ? data + "/visuals/harbour.yaml" : options.looks,
                                   io::machine_data_files(data, sim::machine_kinds(), exercise.machine_file));
  ig::ImageGenerator generator(simulation.scene(), std::move(looks.visuals), options.width, options.height,
                               options.multisamples);
  if (options.soft_shadows) generator.set_soft_shadows(*options.soft_shadows);
  if (options.surface_detail) generator.set_surface_detail(*options.surface_detail);
  generator.use(looks);
  generator.update(*simulation.snapshot());
  if (const bulk::BulkWorld* material = simulation.bulk()) {
    scene::BulkView view;
    bulk::publish(*material, view);
    generator.update_bulk(view);
  }
  const std::vector<std::string> names = generator.view_names();
  if (std::find(names.begin(), names.end(), options.view) == names.end()) {
    std::string list;
    for (const std::string& n : names)
      list += (list.empty() ? "" : ", ") + n;
    throw std::runtime_error("--view " + options.view + ": one of " + list);
  }
  ig::View view = ig::view_named(options.view);
  if (!options.camera.empty()) {
    if (view.kind != ig::View::Kind::kFree) throw std::runtime_error("--camera is for --view free");
    view.position_m = {options.camera[0], options.camera[1], options.camera[2]};
    view.yaw_rad = options.camera[3] * std::numbers::pi / 180.0;
    view.pitch_rad = options.camera[4] * std::numbers::pi / 180.0;
  }
  generator.set_view(view);
  generator.render();
  if (!generator.write_png(options.out)) throw std::runtime_error(options.out + ": cannot be written");
  std::printf("%s: %s at t=%.1f s, %s view, %dx%d (%s)\n", options.out.c_str(), exercise.name.c_str(),
              simulation.time_s(), options.view.c_str(), options.width, options.height,
              generator.renderer().c_str());
  return 0;
}

}  // namespace harbour::debrief
