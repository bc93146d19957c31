// A team's hand-off on the executive alone: the crane's simulation and two tractors' simulations stepped side
// by side, joined as their stations join them (the tractors' trailers as the crane's team trucks, 50 times a
// second; a box seated on a chassis handed to that tractor), each under its autopilot.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/tractor/TractorAutopilot.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Recording.h"

namespace harbour::sim {
namespace {

struct Member {
  explicit Member(const std::string& exercise_name)
      : exercise(io::load_exercise(HARBOUR_DATA_DIR "/exercises/" + exercise_name + ".yaml")),
        sim(exercise.scenario),
        evaluator(exercise),
        recorder(exercise.name, sim.control_table()) {}
  ExerciseSettings exercise;
  Simulation sim;
  Evaluator evaluator;
  Recorder recorder;
  std::unique_ptr<Pilot> pilot;
  void step() {
    if (sim.diverged()) return;
    const scene::Controls c = pilot->next(sim);
    sim.step(c);
    evaluator.observe(sim, c);
    recorder.after_step(sim, c);
  }
  // as a station applies what the other stations made happen: before its next step, recorded with it
  void input(const TeamInput& in) {
    sim.team_input(in);
    recorder.on_team(sim.steps(), in);
  }
};

// a tractor's trailer deck (its top centre) as the crane's team truck sees it
TeamInput truck_at(const Simulation& tractor, int slot) {
  const auto& t = dynamic_cast<const TerminalTractor&>(tractor.machine());
  const core::Pose body = tractor.world().pose(t.trailer_body());
  const double half_z = tractor.scene().entities[1].half_extents_m.z;
  TeamInput in;
  in.kind = TeamInput::Kind::kTruckAt;
  in.slot = slot;
  in.pose = deck_of_trailer(body, half_z);
  in.velocity_mps = tractor.world().point_velocity(t.trailer_body(), {0, 0, half_z});
  in.angular_velocity_radps = tractor.world().angular_velocity(t.trailer_body());
  return in;
}

TEST(TeamHandOff, TheCraneSetsABoxOnEachTractorsChassisAndEachTractorTakesItsBoxAway) {
  Member crane("sts_discharge_team");
  crane.pilot = std::make_unique<GantryAutopilot>(crane.exercise);
  Member tractor[2] = {Member("tractor_sts_collect_1"), Member("tractor_sts_collect_2")};
  for (Member& t : tractor)
    t.pilot = std::make_unique<TractorAutopilot>(t.exercise);
  const double half_z = tractor[0].sim.scene().entities[1].half_extents_m.z;

  int handed[2] = {-1, -1};
  double handed_at_s[2] = {-1, -1}, loaded_wait_s[2] = {-1, -1};
  double standing_since_s[2] = {-1, -1};
  const double limit_s = crane.exercise.rules.time_limit_s;
  while (crane.sim.time_s() < limit_s && !(tractor[0].evaluator.finished() &&
                                           tractor[1].evaluator.finished() && crane.evaluator.finished())) {
    if (crane.sim.steps() % 20 == 0)
      for (int k = 0; k < 2; ++k)
        crane.input(truck_at(tractor[k].sim, k));
    crane.step();
    for (Member& t : tractor)
      t.step();
    for (int k = 0; k < 2; ++k) {
      const auto& tt = dynamic_cast<const TerminalTractor&>(tractor[k].sim.machine());
      if (standing_since_s[k] < 0 && std::abs(tt.forward_mps()) < 0.05 && tractor[k].sim.time_s() > 5.0 &&
          std::hypot(tractor[k].sim.world().pose(tt.trailer_body()).position.y, 0.0) < 1.0)
        standing_since_s[k] = tractor[k].sim.time_s();
      const int box = crane.sim.trucks()->seated_box(k);
      if (box < 0 || handed[k] >= 0) continue;
      // the box's centre in the trailer's frame, its mass: the tractor takes it; the crane lets it go
      const core::Pose deck = crane.sim.trucks()->truck_pose(k);
      const core::Pose on = crane.sim.world().pose(crane.sim.container_body(static_cast<std::size_t>(box)));
      TeamInput load;
      load.kind = TeamInput::Kind::kLoadOn;
      load.pose = on_trailer(deck, on, half_z);
      load.mass_kg = crane.sim.world().mass_kg(crane.sim.container_body(static_cast<std::size_t>(box)));
      tractor[k].input(load);
      TeamInput gone;
      gone.kind = TeamInput::Kind::kTakenOver;
      gone.slot = k;
      crane.input(gone);
      handed[k] = box;
      handed_at_s[k] = crane.sim.time_s();
      loaded_wait_s[k] = standing_since_s[k] >= 0 ? handed_at_s[k] - standing_since_s[k] : -1.0;
    }
  }
  ASSERT_FALSE(crane.sim.diverged()) << crane.sim.divergence();
  for (const Member& t : tractor)
    ASSERT_FALSE(t.sim.diverged()) << t.sim.divergence();
  const auto parked_s = [&](int k) {
    const std::vector<double>& t = tractor[k].evaluator.metrics().cycle_times_s;
    return t.empty() ? -1.0 : t[0];
  };
  std::printf(
      "handed over at %.1f s and %.1f s (tractors waited %.1f s and %.1f s); crane %d moves, "
      "tractors parked at %.1f s and %.1f s\n",
      handed_at_s[0], handed_at_s[1], loaded_wait_s[0], loaded_wait_s[1],
      crane.evaluator.metrics().moves_completed, parked_s(0), parked_s(1));
  // each tractor got one box, a different one, the first the first move's
  EXPECT_GE(handed[0], 0);
  EXPECT_GE(handed[1], 0);
  EXPECT_NE(handed[0], handed[1]);
  EXPECT_EQ(crane.evaluator.metrics().moves_completed, 2);
  EXPECT_TRUE(crane.evaluator.finished());  // both boxes taken over: the crane's part is done
  EXPECT_EQ(crane.evaluator.metrics().collisions, 0);
  for (int k = 0; k < 2; ++k) {
    const Metrics& m = tractor[k].evaluator.metrics();
    EXPECT_EQ(m.moves_completed, 1) << "tractor " << k + 1;
    EXPECT_EQ(m.collisions, 0) << "tractor " << k + 1;
    // its box rides on its dropped trailer, 22 t on the deck, where the trailer stands
    const Machine& machine = tractor[k].sim.machine();
    ASSERT_TRUE(machine.load().has_value());
    EXPECT_NEAR(tractor[k].sim.world().mass_kg(*machine.load()), 22000.0, 1.0);
    const auto& tt = dynamic_cast<const TerminalTractor&>(machine);
    const core::Pose trailer = tractor[k].sim.world().pose(tt.trailer_body());
    const core::Vec3 on = trailer.to_local(tractor[k].sim.world().pose(*machine.load()).position);
    EXPECT_LT(std::hypot(on.x, on.y), 0.35) << "tractor " << k + 1;  // set down within the crane's tolerance
    EXPECT_NEAR(on.z, half_z + 1.3, 0.05) << "tractor " << k + 1;    // on the deck (a 2.59 m box)
  }
  // the crane draws neither box any longer (their tractors' stations do), nor the trucks
  const std::unique_ptr<scene::Snapshot> s = crane.sim.snapshot();
  const scene::SceneDescription scene = crane.sim.scene();
  int hidden_boxes = 0, hidden_trucks = 0;
  for (int n = 0; n < s->entity_count; ++n) {
    const scene::Snapshot::Entity& e = s->entities[static_cast<std::size_t>(n)];
    if ((e.flags & scene::Snapshot::kHidden) == 0) continue;
    const std::string& name = scene.entities[e.index].name;
    if (name.rfind("truck", 0) == 0) ++hidden_trucks;
    if (name.rfind("TGHU", 0) == 0) ++hidden_boxes;
  }
  EXPECT_EQ(hidden_boxes, 2);
  EXPECT_EQ(hidden_trucks, 2);

  // each station's recording replays its own machine bit for bit, the others' doings read back from it
  for (Member* m : {&crane, &tractor[0]}) {
    EXPECT_FALSE(m->recorder.recording().team.empty());
    const ReplayResult r = replay(m->exercise.scenario, m->recorder.recording());
    EXPECT_FALSE(r.first_mismatch.has_value())
        << m->exercise.name << " at step " << r.first_mismatch.value_or(-1);
    EXPECT_EQ(r.simulation->state_hash(), m->sim.state_hash()) << m->exercise.name;
  }
}

}  // namespace
}  // namespace harbour::sim
