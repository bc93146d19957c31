// Another station's machine drawn here: dead reckoning between samples checked against motions known in
// closed form (a straight run, a steady turn), with samples lost and arriving late, and a member that falls
// silent.
#include "harbour/station/TeamPresence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace harbour::station {
namespace {

constexpr double kPeriod_s = 0.02;  // members publish at 50 Hz

// a steady turn: speed v on a circle of radius r about the origin, heading along the track
RemoteMotion on_circle(double v, double r, double t) {
  const double w = v / r, a = w * t;
  RemoteMotion m;
  m.pose.position = {r * std::cos(a), r * std::sin(a), 1.0};
  m.pose.rotation = core::Mat3::rotation({0, 0, 1}, a + std::numbers::pi / 2);
  m.velocity_mps = {-v * std::sin(a), v * std::cos(a), 0.0};
  m.angular_velocity_radps = {0, 0, w};
  return m;
}

double heading(const core::Mat3& r) {
  return std::atan2(r.m[1][0], r.m[0][0]);
}

double angle_between(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * std::numbers::pi));
}

TEST(DeadReckoning, AStraightRunIsDrawnExactlyBetweenSamples) {
  DeadReckoning body(TeamPresence::kBlend_s, TeamPresence::kHorizon_s);
  const core::Vec3 v{3.0, -1.0, 0.0};
  const auto truth = [&](double t) { return core::Vec3{5.0, 2.0, 0.5} + t * v; };
  body.place({{core::Mat3::identity(), truth(0)}, v, {}}, 0.0);
  double worst = 0.0;
  for (int k = 1; k <= 100; ++k) {
    const double t = k * kPeriod_s;
    body.update({{core::Mat3::identity(), truth(t)}, v, {}}, t);
    for (double dt = 0.0; dt < kPeriod_s; dt += 0.001)
      worst = std::max(worst, core::length(body.at(t + dt).position - truth(t + dt)));
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(DeadReckoning, ASteadyTurnWithLossAndLateSamplesStaysWithinTheExtrapolationBound) {
  // v = 5 m/s on r = 20 m: the straight extrapolation over a gap tau strays at most (v^2 / r) tau^2 / 2 from
  // the circle; samples arrive 0-10 ms late (the lateness is not compensated: it adds v x lateness) and 2 %
  // are lost (a gap of two periods)
  const double v = 5.0, r = 20.0;
  DeadReckoning body(TeamPresence::kBlend_s, TeamPresence::kHorizon_s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> late(0.0, 0.010);
  std::bernoulli_distribution lost(0.02);
  body.place(on_circle(v, r, 0.0), 0.0);
  double worst_position = 0.0, worst_heading = 0.0, worst_after_blend = 0.0;
  double last_arrival = 0.0;
  int dropped = 0;
  for (int k = 1; k <= 3000; ++k) {  // 60 s, 2.4 laps
    const double sent = k * kPeriod_s;
    if (lost(rng)) {
      ++dropped;
      continue;
    }
    const double arrival = std::max(last_arrival, sent + late(rng));
    // drawn between the last arrival and this one
    for (double t = last_arrival; t < arrival; t += 0.001) {
      const RemoteMotion truth = on_circle(v, r, t);
      const core::Pose drawn = body.at(t);
      const double error = core::length(drawn.position - truth.pose.position);
      worst_position = std::max(worst_position, error);
      worst_heading =
          std::max(worst_heading, angle_between(heading(drawn.rotation), heading(truth.pose.rotation)));
      if (t - last_arrival > TeamPresence::kBlend_s) worst_after_blend = std::max(worst_after_blend, error);
    }
    body.update(on_circle(v, r, sent), arrival);
    last_arrival = arrival;
  }
  EXPECT_GT(dropped, 30);
  // lateness: 10 ms x 5 m/s = 5 cm; curvature over 3 periods: (25/20) 0.06^2 / 2 = 2.3 mm
  EXPECT_LT(worst_position, 0.05 + 0.0023 + 0.005);
  EXPECT_GT(worst_position, 0.01);  // the lateness is really there
  EXPECT_LT(worst_heading, (v / r) * (0.010 + 3 * kPeriod_s));
  EXPECT_LT(worst_after_blend, 0.06);
}

TEST(DeadReckoning, ACorrectionIsBlendedInWithoutAJump) {
  DeadReckoning body(TeamPresence::kBlend_s, TeamPresence::kHorizon_s);
  body.place({{core::Mat3::identity(), {0, 0, 0}}, {2, 0, 0}, {}}, 0.0);
  // the member stopped at 0.5 m: the track said 1.0 m at 0.5 s; the sample says 0.5 m and standing
  const core::Pose before = body.at(0.5);
  body.update({{core::Mat3::rotation({0, 0, 1}, 0.3), {0.5, 0, 0}}, {}, {}}, 0.5);
  const core::Pose after = body.at(0.5);
  EXPECT_LT(core::length(after.position - before.position), 1e-9);
  EXPECT_LT(angle_between(heading(after.rotation), 0.0), 1e-9);
  // halfway through the blend: halfway between the old track (carried on at 2 m/s) and the sample
  const double mid = 0.5 + TeamPresence::kBlend_s / 2;
  EXPECT_NEAR(body.at(mid).position.x, 0.5 * (1.0 + 2.0 * (mid - 0.5)) + 0.5 * 0.5, 1e-9);
  EXPECT_NEAR(heading(body.at(mid).rotation), 0.15, 1e-9);
  // after it: the sample
  EXPECT_NEAR(body.at(0.5 + TeamPresence::kBlend_s).position.x, 0.5, 1e-12);
  EXPECT_NEAR(heading(body.at(0.7).rotation), 0.3, 1e-12);
}

scene::SceneDescription own_scene() {
  scene::SceneDescription d;
  d.machine = "sts";
  d.entities = {{"gantry", "sts.gantry", {}}, {"trolley", "sts.trolley", {}}};
  d.machine_entities = 2;
  return d;
}

TeamMember tractor() {
  TeamMember m;
  m.role = "tractor-1";
  m.bodies = {{"tractor", "tractor.chassis", {3, 1.2, 1.5}}, {"trailer", "trailer", {6.1, 1.2, 0.8}}};
  m.start_poses = {{core::Mat3::identity(), {0, -40, 1.5}}, {core::Mat3::identity(), {-9, -40, 1.0}}};
  return m;
}

TEST(TeamPresence, AMembersBodiesFollowTheOwnEntitiesAndStartWhereItsExerciseStartsThem) {
  TeamPresence team(own_scene(), {tractor()});
  ASSERT_EQ(team.scene().entities.size(), 4u);
  EXPECT_EQ(team.scene().machine_entities, 2);  // the chase view still frames this station's machine
  EXPECT_EQ(team.scene().entities[2].name, "tractor-1: tractor");
  EXPECT_EQ(team.scene().entities[3].visual, "trailer");
  EXPECT_EQ(team.scene().entities[3].half_extents_m.x, 6.1);
  auto snapshot = std::make_unique<scene::Snapshot>();
  snapshot->entity_count = 2;
  team.write(*snapshot, 5.0);
  ASSERT_EQ(snapshot->entity_count, 4);
  EXPECT_EQ(snapshot->entities[2].index, 2u);
  EXPECT_EQ(snapshot->entities[3].index, 3u);
  EXPECT_EQ(snapshot->entities[3].pose.position.x, -9.0);
  EXPECT_FALSE(team.members(5.0).front().heard);
}

TEST(TeamPresence, AMemberThatFallsSilentStopsWithinTheHorizonAndIsLostAfterTwoSeconds) {
  TeamPresence team(own_scene(), {tractor()});
  TeamSample sample;
  sample.role = "tractor-1";
  sample.body = {0};
  sample.motion = {{{core::Mat3::identity(), {0, -40, 1.5}}, {0, 4, 0}, {}}};
  for (int k = 0; k <= 50; ++k) {  // a second at 4 m/s along y
    sample.received_s = 10.0 + k * kPeriod_s;
    sample.age_s = 0.001 * (k % 5);
    sample.motion[0].pose.position.y = -40 + 4 * k * kPeriod_s;
    ASSERT_EQ(team.offer(sample), "");
  }
  auto snapshot = std::make_unique<scene::Snapshot>();
  const auto drawn_y = [&](double t) {
    snapshot->entity_count = 2;
    team.write(*snapshot, t);
    return snapshot->entities[2].pose.position.y;
  };
  EXPECT_NEAR(drawn_y(11.1), -36 + 0.4, 1e-9);                           // carried on at 4 m/s
  EXPECT_NEAR(drawn_y(13.0), -36 + 4 * TeamPresence::kHorizon_s, 1e-9);  // and no further
  EXPECT_EQ(drawn_y(20.0), drawn_y(13.0));
  std::vector<std::string> changed;
  std::vector<TeamPresence::MemberState> states = team.members(12.9, &changed, true);
  EXPECT_TRUE(states[0].heard);
  EXPECT_FALSE(states[0].lost);
  EXPECT_TRUE(changed.empty());
  EXPECT_EQ(states[0].samples, 51);
  EXPECT_EQ(states[0].measured, 51);
  EXPECT_DOUBLE_EQ(states[0].age_p50_s, 0.002);
  EXPECT_DOUBLE_EQ(states[0].age_max_s, 0.004);
  states = team.members(13.1, &changed);
  EXPECT_TRUE(states[0].lost);
  EXPECT_EQ(changed, std::vector<std::string>{"tractor-1"});
  changed.clear();
  team.members(13.2, &changed);
  EXPECT_TRUE(changed.empty());  // said once
  // back: no longer lost, said again
  sample.received_s = 14.0;
  ASSERT_EQ(team.offer(sample), "");
  EXPECT_FALSE(team.members(14.0, &changed)[0].lost);
  EXPECT_EQ(changed, std::vector<std::string>{"tractor-1"});
}

TEST(TeamPresence, ABodyLeftOutIsHiddenAndOneThatAppearsIsPutThereAndAMemberThatLeftIsNotLost) {
  TeamMember m = tractor();
  m.start_hidden = {false, true};  // its trailer (say, a load still to come) not there at the start
  TeamPresence team(own_scene(), {m});
  auto snapshot = std::make_unique<scene::Snapshot>();
  const auto drawn = [&](double t, int entity) {
    snapshot->entity_count = 2;
    team.write(*snapshot, t);
    return snapshot->entities[static_cast<std::size_t>(entity)];
  };
  EXPECT_EQ(drawn(0.0, 2).flags, 0u);
  EXPECT_EQ(drawn(0.0, 3).flags, scene::Snapshot::kHidden);
  TeamSample sample;
  sample.role = "tractor-1";
  sample.received_s = 1.0;
  sample.body = {0};
  sample.motion = {{{core::Mat3::identity(), {0, -40, 1.5}}, {}, {}}};
  ASSERT_EQ(team.offer(sample), "");
  EXPECT_EQ(drawn(1.0, 3).flags, scene::Snapshot::kHidden);
  // it appears 100 m from where it started: drawn there at once, not blended in from its start
  sample.received_s = 1.02;
  sample.body = {0, 1};
  sample.motion.push_back({{core::Mat3::identity(), {-9, 60, 1.0}}, {}, {}});
  ASSERT_EQ(team.offer(sample), "");
  EXPECT_EQ(drawn(1.03, 3).flags, 0u);
  EXPECT_NEAR(drawn(1.03, 3).pose.position.y, 60.0, 1e-9);
  // left out again: hidden again
  sample.received_s = 1.04;
  sample.body = {0};
  sample.motion.resize(1);
  ASSERT_EQ(team.offer(sample), "");
  EXPECT_EQ(drawn(1.05, 3).flags, scene::Snapshot::kHidden);
  // it said it left: silent from then on, never lost
  team.left("tractor-1");
  std::vector<std::string> changed;
  const TeamPresence::MemberState state = team.members(10.0, &changed).front();
  EXPECT_TRUE(state.left);
  EXPECT_FALSE(state.lost);
  EXPECT_TRUE(changed.empty());
}

TEST(TeamPresence, SamplesOfAnotherRoleOrABodyItLacksAreRefused) {
  TeamPresence team(own_scene(), {tractor()});
  TeamSample sample;
  sample.role = "tractor-2";
  EXPECT_EQ(team.offer(sample), "no member of this team has the role 'tractor-2'");
  sample.role = "tractor-1";
  sample.body = {2};
  sample.motion.resize(1);
  EXPECT_EQ(team.offer(sample), "'tractor-1' has 2 bodies, not body 2");
  sample.body = {0, 1};
  EXPECT_EQ(team.offer(sample), "a sample of 'tractor-1' is torn");
  EXPECT_FALSE(team.members(0.0)[0].heard);
}

TEST(BoxClearance, SideBySideTurnedAndOverlappingBoxesAgainstTheirGeometry) {
  const core::Vec3 unit{1, 1, 1};
  const core::Pose at_origin{core::Mat3::identity(), {}};
  EXPECT_NEAR(box_clearance(at_origin, unit, {core::Mat3::identity(), {3, 0, 0}}, unit), 1.0, 1e-12);
  EXPECT_NEAR(box_clearance(at_origin, unit, {core::Mat3::identity(), {1.5, 0.2, 0}}, unit), -0.5, 1e-12);
  // turned 45 degrees about z: its corner reaches sqrt(2) towards the other
  const core::Pose turned{core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 4), {4, 0, 0}};
  EXPECT_NEAR(box_clearance(at_origin, unit, turned, unit), 3.0 - std::sqrt(2.0), 1e-12);
  // a long thin box (a trailer, 6.1 x 1.2 x 0.8 half) passing 0.3 m under a spreader's (6.1 x 1.25 x 0.3)
  const core::Pose spreader{core::Mat3::rotation({0, 0, 1}, 0.2), {0.5, -1.0, 1.8 + 0.3 + 0.3}};
  EXPECT_NEAR(
      box_clearance({core::Mat3::identity(), {0, 0, 1.0}}, {6.1, 1.2, 0.8}, spreader, {6.1, 1.25, 0.3}), 0.3,
      1e-12);
  // apart along a diagonal (the nearest features are edges): a lower bound on the true distance (here 1.0)
  const core::Pose diagonal{core::Mat3::identity(),
                            {2.0 + 1.0 / std::sqrt(2.0), 2.0 + 1.0 / std::sqrt(2.0), 0}};
  const double bound = box_clearance(at_origin, unit, diagonal, unit);
  EXPECT_GT(bound, 0.0);
  EXPECT_LE(bound, 1.0 + 1e-12);
}

TEST(NearMissWatch, OneEpisodePerApproachAContactSaidOnceAndTheClosestKept) {
  NearMissWatch watch;
  const auto at = [&](double gap) { return watch.update({{"tractor", "spreader", "trailer", gap}}); };
  EXPECT_TRUE(at(3.0).empty());
  EXPECT_EQ(at(0.8), std::vector<std::string>{"near miss: spreader 0.80 m from tractor: trailer"});
  EXPECT_TRUE(at(0.5).empty());
  EXPECT_TRUE(at(1.2).empty());  // still the same approach
  EXPECT_TRUE(at(0.9).empty());
  EXPECT_TRUE(at(2.0).empty());  // clear: the episode ends
  EXPECT_EQ(at(0.7).size(), 1u);
  EXPECT_EQ(at(-0.1), std::vector<std::string>{"contact: spreader with tractor: trailer"});
  EXPECT_TRUE(at(-0.2).empty());
  ASSERT_EQ(watch.tallies().size(), 1u);
  EXPECT_EQ(watch.tallies()[0].near_misses, 2);
  EXPECT_EQ(watch.tallies()[0].contacts, 1);
  EXPECT_DOUBLE_EQ(watch.tallies()[0].closest_m, -0.2);
}

TEST(TeamPresence, TheClosestApproachIsBetweenSizedBodiesOfBothMachines) {
  scene::SceneDescription own;
  own.entities = {{"gantry", "sts.gantry", {}}, {"spreader", "sts.spreader", {6.1, 1.25, 0.3}}};
  own.machine_entities = 2;
  TeamPresence team(own, {tractor()});  // the tractor at y = -40, its trailer behind it
  auto snapshot = std::make_unique<scene::Snapshot>();
  snapshot->entity_count = 2;
  snapshot->entities[0] = {0, 0, {core::Mat3::identity(), {0, -40, 30}}};
  // 0.5 m over the trailer (its top at 1.8 m), 2.9 m behind the tractor's cab (its back at x = -3)
  snapshot->entities[1] = {1, 0, {core::Mat3::identity(), {-12, -40, 1.0 + 0.8 + 0.5 + 0.3}}};
  const std::vector<TeamPresence::Closest> c = team.closest(*snapshot, 0.0);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].role, "tractor-1");
  EXPECT_EQ(c[0].own_body, "spreader");  // the gantry has no size: left out
  EXPECT_EQ(c[0].member_body, "trailer");
  EXPECT_NEAR(c[0].clearance_m, 0.5, 1e-12);
}

}  // namespace
}  // namespace harbour::station
