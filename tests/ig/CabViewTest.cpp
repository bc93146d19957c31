// The cab views frame the task: for every machine's main exercise under its scripted operator, the tool
// (spreader, grab, hook) and the target it must reach (the box to take, then where it goes; the pile in the
// hold, then the hopper) are in the cab's design view — the centre or a corner of their bounding boxes in
// front of the eye and inside the picture, projected through the image generator's own camera: what an
// operator aligns is a spreader's corner — for at least 95 % of the samples (every 0.1 s) of each move.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <osg/Image>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/ig/ImageGenerator.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"

namespace harbour::ig {
namespace {

constexpr int kWidth = 640, kHeight = 360;  // a desktop monitor's shape
constexpr double kSample_s = 0.1;

// A move's share of samples with the tool and with the target in view, over the whole move and over its
// approach (the tool within kApproach_m of the target, horizontally: where it is aligned and set down)
struct MoveFraming {
  int samples = 0, tool_in = 0, target_in = 0;
  int approach = 0, approach_target_in = 0;
  double tool_share() const { return samples ? static_cast<double>(tool_in) / samples : 0.0; }
  double target_share() const { return samples ? static_cast<double>(target_in) / samples : 0.0; }
  double approach_share() const {
    return approach ? static_cast<double>(approach_target_in) / approach : 0.0;
  }
};
constexpr double kApproach_m = 12.0;

int entity_named(const scene::SceneDescription& scene, const std::string& name) {
  for (std::size_t n = 0; n < scene.entities.size(); ++n)
    if (scene.entities[n].name == name) return static_cast<int>(n);
  return -1;
}

// the body an exercise's goal names: a box of the scene, or an item the machine brings
std::optional<physics::BodyId> item_named(const sim::Simulation& simulation, const std::string& id) {
  for (std::size_t c = 0; c < simulation.scenario().containers.size(); ++c)
    if (simulation.scenario().containers[c].id == id) return simulation.container_body(c);
  for (const auto& [name, body] : simulation.machine().own_items())
    if (name == id) return body;
  return std::nullopt;
}

// its half size: a box of the scene's; an item the machine brings, a metre each way
core::Vec3 item_half_m(const sim::Simulation& simulation, const std::string& id) {
  for (const sim::ContainerPlacement& c : simulation.scenario().containers)
    if (c.id == id) return c.half_extents_m;
  return {1.0, 1.0, 1.0};
}

// the middle of a bulk grid's surface, in the world
core::Vec3 grid_surface_m(const bulk::HeightGrid& grid) {
  const int i = grid.cells_x() / 2, j = grid.cells_y() / 2;
  const core::Vec3 c = grid.cell_centre(i, j);
  return grid.pose().to_parent({c.x, c.y, grid.height(i, j)});
}

// The scripted operator runs `exercise_name`; every 0.1 s the cab view is aimed as the station's desktop
// picture would be, and the tool's and the target's centres are projected through it. One entry per move
// (per bite and discharge for a grab).
std::vector<MoveFraming> framing(const std::string& exercise_name, const std::string& tool_name,
                                 double most_s = 900.0) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + exercise_name + ".yaml");
  sim::Simulation simulation(exercise.scenario);
  const std::unique_ptr<sim::Pilot> pilot = sim::make_pilot(exercise);
  sim::Evaluator evaluator(exercise);
  const scene::SceneDescription scene = simulation.scene();
  const int tool = entity_named(scene, tool_name);
  EXPECT_GE(tool, 0) << "no entity '" << tool_name << "'";
  Looks looks = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  ImageGenerator generator(scene, std::move(looks.visuals), kWidth, kHeight);
  generator.set_view(view_named("cab"));
  auto snapshot = std::make_unique<scene::Snapshot>();
  const auto in_picture = [&](const core::Vec3& p) {
    const auto at = generator.project(p);
    return at && at->first >= 0.0 && at->first <= kWidth && at->second >= 0.0 && at->second <= kHeight;
  };
  // a box (its pose and half extents) shows when its centre or one of its corners does
  const auto in_view = [&](const core::Pose& box, const core::Vec3& half) {
    if (in_picture(box.position)) return true;
    for (int corner = 0; corner < 8; ++corner)
      if (in_picture(box.to_parent(
              {corner & 1 ? half.x : -half.x, corner & 2 ? half.y : -half.y, corner & 4 ? half.z : -half.z})))
        return true;
    return false;
  };
  std::vector<MoveFraming> moves(1);
  int phase = 0;
  bool was_carrying = false;
  double next_sample_s = 0.0;
  while (!evaluator.finished() && simulation.time_s() < most_s && !simulation.diverged()) {
    const scene::Controls in = pilot->next(simulation);
    simulation.step(in);
    evaluator.observe(simulation, in);
    const bool carrying = simulation.carrying();
    // a new move: the last one done (a container), or the grab opened its load (a bite delivered)
    const int done = exercise.moves.empty() ? phase + (was_carrying && !carrying ? 1 : 0)
                                            : evaluator.metrics().moves_completed;
    was_carrying = carrying;
    if (done != phase) {
      phase = done;
      moves.emplace_back();
    }
    if (simulation.time_s() + 1e-9 < next_sample_s) continue;
    next_sample_s += kSample_s;
    // what it must reach now: the item to take, then where it goes (the item's box there); the pile, then
    // the hopper
    std::optional<core::Pose> target;
    core::Vec3 target_half;
    if (!exercise.moves.empty() && phase < static_cast<int>(exercise.moves.size())) {
      const sim::MoveGoal& goal = exercise.moves[static_cast<std::size_t>(phase)];
      const std::optional<physics::BodyId> item = item_named(simulation, goal.container_id);
      target_half = item_half_m(simulation, goal.container_id);
      if (carrying || !item) {
        target = core::Pose{item ? simulation.world().pose(*item).rotation : core::Mat3::identity(),
                            goal.target_m};
      } else {
        target = simulation.world().pose(*item);
      }
    } else if (exercise.deliver && simulation.bulk()) {
      const bulk::BulkWorld& material = *simulation.bulk();
      int pile = -1;  // the grid with the most material other than the hopper
      double most_m3 = -1.0;
      for (int g = 0; g < material.grid_count(); ++g) {
        if (g == exercise.deliver->grid_index) continue;
        if (material.grid(g).total_volume_m3() > most_m3)
          most_m3 = material.grid(g).total_volume_m3(), pile = g;
      }
      target = core::Pose{core::Mat3::identity(),
                          grid_surface_m(material.grid(carrying ? exercise.deliver->grid_index : pile))};
    }
    simulation.write_snapshot(*snapshot);
    generator.update(*snapshot);
    generator.aim();
    MoveFraming& m = moves.back();
    ++m.samples;
    const auto& entity = snapshot->entities[static_cast<std::size_t>(tool)];
    m.tool_in += in_view(entity.pose, scene.entities[static_cast<std::size_t>(tool)].half_extents_m) ? 1 : 0;
    const bool target_in = target && in_view(*target, target_half);
    m.target_in += target_in ? 1 : 0;
    if (target && std::hypot(target->position.x - entity.pose.position.x,
                             target->position.y - entity.pose.position.y) < kApproach_m) {
      ++m.approach;
      m.approach_target_in += target_in ? 1 : 0;
    }
  }
  EXPECT_TRUE(evaluator.finished()) << exercise_name << " did not finish in " << most_s << " s";
  if (moves.back().samples < 10) moves.pop_back();  // the last moment after the last move
  for (std::size_t n = 0; n < moves.size(); ++n)
    std::printf(
        "%s move %zu: tool in view %.1f %%, target %.1f %% of %d samples (%.1f %% of %d approaching)\n",
        exercise_name.c_str(), n + 1, 100.0 * moves[n].tool_share(), 100.0 * moves[n].target_share(),
        moves[n].samples, 100.0 * moves[n].approach_share(), moves[n].approach);
  return moves;
}

struct Task {
  const char* exercise;
  const char* tool;
  /// A slewing crane's target may lie far round from where its boom points (the MHC's hopper 78 degrees off
  /// the hold): the operator turns the head to it (the station's look-around), and the design view frames it
  /// as the tool approaches; else it frames the target through the whole move
  bool slews = false;
};

class CabView : public testing::TestWithParam<Task> {};

TEST_P(CabView, FramesTheToolAndItsTargetThroughEveryMove) {
  const std::vector<MoveFraming> moves = framing(GetParam().exercise, GetParam().tool);
  ASSERT_FALSE(moves.empty());
  for (std::size_t n = 0; n < moves.size(); ++n) {
    EXPECT_GE(moves[n].tool_share(), 0.95) << "move " << n + 1;
    EXPECT_GE(GetParam().slews ? moves[n].approach_share() : moves[n].target_share(), 0.95)
        << "move " << n + 1;
  }
}

INSTANTIATE_TEST_SUITE_P(MainExercises, CabView,
                         testing::Values(Task{"sts_discharge", "spreader"}, Task{"rtg_rehandle", "spreader"},
                                         Task{"mhc_hook_lift", "hook", true},
                                         Task{"mhc_coal_discharge", "grab", true},
                                         Task{"reach_stacker_stack", "spreader"}),
                         [](const testing::TestParamInfo<Task>& task) {
                           return std::string(task.param.exercise);
                         });

// Reversing a semi-trailer into its bay: the trailer is always in one of the cab's mirrors or on its
// reversing camera's monitor (the insets of the cab view, mirrored as mirrors are).
TEST(CabView, TheTrailerIsInAMirrorOrOnTheReversingCameraWhileReversing) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/tractor_semi_reverse.yaml");
  sim::Simulation simulation(exercise.scenario);
  const std::unique_ptr<sim::Pilot> pilot = sim::make_pilot(exercise);
  sim::Evaluator evaluator(exercise);
  const scene::SceneDescription scene = simulation.scene();
  const int trailer = entity_named(scene, "trailer");
  ASSERT_GE(trailer, 0);
  Looks looks = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  ImageGenerator generator(scene, std::move(looks.visuals), kWidth, kHeight);
  generator.use(looks);
  generator.set_view(view_named("cab"));
  ASSERT_EQ(generator.insets().size(), 3u);  // two mirrors, the reversing camera
  auto snapshot = std::make_unique<scene::Snapshot>();
  int samples = 0, seen = 0;
  double next_sample_s = 0.0;
  while (!evaluator.finished() && simulation.time_s() < 300.0) {
    const scene::Controls in = pilot->next(simulation);
    simulation.step(in);
    evaluator.observe(simulation, in);
    if (simulation.time_s() + 1e-9 < next_sample_s) continue;
    next_sample_s += kSample_s;
    simulation.write_snapshot(*snapshot);
    generator.update(*snapshot);
    generator.aim();
    const auto& entity = snapshot->entities[static_cast<std::size_t>(trailer)];
    const core::Vec3 half = scene.entities[static_cast<std::size_t>(trailer)].half_extents_m;
    bool in_one = false;
    for (std::size_t n = 0; n < generator.insets().size() && !in_one; ++n)
      for (int corner = -1; corner < 8 && !in_one; ++corner)
        in_one = generator
                     .project_inset(n, corner < 0 ? entity.pose.position
                                                  : entity.pose.to_parent({corner & 1 ? half.x : -half.x,
                                                                           corner & 2 ? half.y : -half.y,
                                                                           corner & 4 ? half.z : -half.z}))
                     .has_value();
    ++samples;
    seen += in_one ? 1 : 0;
  }
  EXPECT_TRUE(evaluator.finished());
  std::printf(
      "tractor_semi_reverse: the trailer in a mirror or on the reversing camera in %d of %d samples\n", seen,
      samples);
  EXPECT_GE(seen, 0.95 * samples);
}

// The HUD shows what each machine's own display shows, by the names it publishes.
TEST(CabView, TheHudShowsWhatEachMachinesDisplayShows) {
  const std::pair<const char*, std::vector<std::string>> machines[] = {
      {"sts_discharge", {"load ", "spreader 40 ft"}},
      {"rtg_rehandle", {"load ", "spreader "}},
      {"mhc_hook_lift", {"load ", "radius ", "SWL ", "LMI "}},
      {"reach_stacker_stack", {"load ", "reach ", "SWL ", "LMI ", "speed "}},
      {"tractor_semi_reverse", {"speed ", "selector ", "gear "}}};
  for (const auto& [name, fields] : machines) {
    const sim::ExerciseSettings exercise =
        io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + name + ".yaml");
    sim::Simulation simulation(exercise.scenario);
    for (int k = 0; k < 200; ++k)
      simulation.step(simulation.control_table().neutral());
    Looks looks = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
    ImageGenerator generator(simulation.scene(), std::move(looks.visuals), 320, 180);
    generator.use(looks);
    generator.update(*simulation.snapshot());
    for (const std::string& field : fields)
      EXPECT_NE(generator.hud_text().find(field), std::string::npos) << name << ": " << generator.hud_text();
    // one load each: the quay cranes' tared payload, not the rope pull with the spreader
    const std::string& hud = generator.hud_text();
    EXPECT_EQ(hud.find("load "), hud.rfind("load ")) << name << ": " << hud;
    EXPECT_EQ(hud.find("-0.0"), std::string::npos) << name << ": " << hud;
  }
}

// The chase view frames the machine whole at any size — its parts in the picture, spanning a good share of
// it — and in thick fog it fades but never draws a blank frame.
TEST(CabView, TheChaseViewFramesEveryMachineAndFogFadesItWithoutBlankingIt) {
  for (const char* name : {"sts_discharge", "rtg_rehandle", "mhc_coal_discharge", "reach_stacker_stack",
                           "tractor_semi_reverse"}) {
    const sim::ExerciseSettings exercise =
        io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + name + ".yaml");
    sim::Simulation simulation(exercise.scenario);
    for (int k = 0; k < 100; ++k)
      simulation.step(simulation.control_table().neutral());
    const scene::SceneDescription scene = simulation.scene();
    ASSERT_GT(scene.machine_entities, 0) << name;
    Looks looks = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
    ImageGenerator generator(scene, std::move(looks.visuals), kWidth, kHeight);
    generator.use(looks);
    generator.set_view(view_named("chase"));
    for (const double visibility_m : {20000.0, 80.0}) {
      SCOPED_TRACE(std::string(name) + ", visibility " + std::to_string(visibility_m) + " m");
      auto snapshot = simulation.snapshot();
      snapshot->visibility_m = visibility_m;
      generator.update(*snapshot);
      const osg::Image& image = generator.render();
      double top = kHeight, bottom = 0.0, left = kWidth, right = 0.0;
      for (int n = 0; n < scene.machine_entities; ++n) {
        const core::Pose& pose = snapshot->entities[static_cast<std::size_t>(n)].pose;
        const core::Vec3 half = scene.entities[static_cast<std::size_t>(n)].half_extents_m;
        const auto at = generator.project(pose.position);
        ASSERT_TRUE(at) << scene.entities[static_cast<std::size_t>(n)].name << " behind the camera";
        if (visibility_m > 1000.0) {
          EXPECT_GE(at->first, 0.0);
          EXPECT_LE(at->first, kWidth);
          EXPECT_GE(at->second, 0.0);
          EXPECT_LE(at->second, kHeight);
        }
        for (int corner = -1; corner < 8; ++corner) {  // its centre and its box's corners
          const auto p = generator.project(
              corner < 0 ? pose.position
                         : pose.to_parent({corner & 1 ? half.x : -half.x, corner & 2 ? half.y : -half.y,
                                           corner & 4 ? half.z : -half.z}));
          if (!p) continue;
          top = std::min(top, p->second);
          bottom = std::max(bottom, p->second);
          left = std::min(left, p->first);
          right = std::max(right, p->first);
        }
      }
      if (visibility_m > 1000.0) {
        EXPECT_GT(std::max(bottom - top, right - left), 0.12 * kWidth) << "the machine is a speck";
      }
      // below the HUD's line, the picture is not one colour: some pixels differ from the mean by 6 % (grey
      // fog takes a machine at a third of the visibility to a quarter of its contrast)
      double sum = 0.0, far = 0.0;
      int count = 0;
      for (int y = 0; y < image.t() * 4 / 5; ++y)
        for (int x = 0; x < image.s(); x += 2, ++count) {
          const unsigned char* p = image.data(x, y);
          sum += (p[0] + p[1] + p[2]) / 765.0;
        }
      const double mean = sum / count;
      for (int y = 0; y < image.t() * 4 / 5; ++y)
        for (int x = 0; x < image.s(); x += 2) {
          const unsigned char* p = image.data(x, y);
          far = std::max(far, std::abs((p[0] + p[1] + p[2]) / 765.0 - mean));
        }
      EXPECT_GT(far, 0.06) << "a blank frame";
    }
  }
}

}  // namespace
}  // namespace harbour::ig
