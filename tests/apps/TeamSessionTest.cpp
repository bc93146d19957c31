// Team sessions as a centre runs them: `harboursim station` processes on loopback DDS, each under its
// autopilot, watched by a console's link: the crane (STS) and the tractor of data/teams/sts_and_tractor.yaml;
// the crane and the two tractors of data/teams/sts_and_two_tractors.yaml handing boxes over.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/net/DdsLink.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/sim/Recording.h"
#include "harbour/sim/SessionPlayer.h"
#include "support/AppProcess.h"

namespace harbour::apps {
namespace {

constexpr int kDomain = 187;

using Clock = std::chrono::steady_clock;

// where entity `name` of a station's scene is in its newest state ("" and nullopt when it has none)
std::optional<core::Vec3> entity_position(const net::ConsoleLink::Station& s, const std::string& name) {
  if (!s.scene || !s.state) return std::nullopt;
  const auto& names = s.scene->entity_names();
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k].to_string() == name && (k + 1) * 7 <= s.state->entity_poses().size()) {
      const float* p = &s.state->entity_poses()[k * 7];
      return core::Vec3{p[0], p[1], p[2]};
    }
  return std::nullopt;
}

bool scene_has(const net::ConsoleLink::Station& s, const std::string& name) {
  if (!s.scene) return false;
  for (const auto& n : s.scene->entity_names())
    if (n.to_string() == name) return true;
  return false;
}

struct Track {
  std::vector<double> t;
  std::vector<core::Vec3> at;
  // linear between the samples around `time` (nullopt outside them)
  std::optional<core::Vec3> interpolated(double time) const {
    for (std::size_t k = 1; k < t.size(); ++k)
      if (t[k - 1] <= time && time <= t[k]) {
        const double f = t[k] > t[k - 1] ? (time - t[k - 1]) / (t[k] - t[k - 1]) : 0.0;
        return (1.0 - f) * at[k - 1] + f * at[k];
      }
    return std::nullopt;
  }
};

TEST(TeamSession, TwoStationsDrawEachOthersMachinesWhereTheirOwnStationsHaveThemAndNoticeALostMember) {
  const fs::path folder = fresh_folder("harbour_team_session");
  net::ConsoleLink console("team-watch", kDomain);
  const auto member = [&](const std::string& role) {
    return start_app({"station", "--team", "sts_and_tractor", "--role", role, "--autopilot", "--name",
                      role + "-cab", "--domain", std::to_string(kDomain), "--seconds", "300", "--window",
                      "off", "--sound", "off", "--db", "sqlite3://db=" + (folder / (role + ".db")).string()},
                     folder / (role + ".log"));
  };
  const pid_t crane = member("crane");
  const pid_t tractor = member("tractor");
  const auto logs = [&] {
    return read_text(folder / "crane.log") + "\n---\n" + read_text(folder / "tractor.log");
  };

  // both stations' scenes hold the other's machine: the tractor draws the STS, the crane the tractor and
  // trailer; each says when it first hears the other
  const auto deadline = Clock::now() + std::chrono::seconds(150);
  bool both = false;
  std::vector<std::string> said;
  const auto heard = [&](const std::string& station, const std::string& text) {
    return std::find(said.begin(), said.end(), station + " " + text) != said.end();
  };
  while (!(both && heard("crane-cab", "tractor: joined (tractor-cab)") &&
           heard("tractor-cab", "crane: joined (crane-cab)")) &&
         Clock::now() < deadline) {
    console.poll();
    for (const net::StationEvent& e : console.take_events())
      if (e.kind().to_string() == "team")
        said.push_back(e.station().to_string() + " " + e.text().to_string());
    const auto& st = console.stations();
    both = st.count("crane-cab") && st.count("tractor-cab") && st.at("crane-cab").state &&
           st.at("tractor-cab").state && scene_has(st.at("crane-cab"), "tractor: trailer") &&
           scene_has(st.at("tractor-cab"), "crane: gantry");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(both) << logs();
  ASSERT_TRUE(heard("crane-cab", "tractor: joined (tractor-cab)")) << logs();
  ASSERT_TRUE(heard("tractor-cab", "crane: joined (crane-cab)")) << logs();
  EXPECT_TRUE(scene_has(console.stations().at("tractor-cab"), "crane: spreader"));
  EXPECT_FALSE(scene_has(console.stations().at("tractor-cab"), "tractor: tractor"));  // not itself twice

  // for 15 s: the tractor where its own station has it, and where the crane's station draws it
  Track own, seen_by_crane;
  std::uint64_t own_count = 0, seen_count = 0;
  const Clock::time_point start = Clock::now();
  while (Clock::now() - start < std::chrono::seconds(15)) {
    console.poll();
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    const net::ConsoleLink::Station& tr = console.stations().at("tractor-cab");
    const net::ConsoleLink::Station& cr = console.stations().at("crane-cab");
    if (tr.state_count != own_count) {
      own_count = tr.state_count;
      if (const auto p = entity_position(tr, "tractor")) {
        own.t.push_back(t);
        own.at.push_back(*p);
      }
    }
    if (cr.state_count != seen_count) {
      seen_count = cr.state_count;
      if (const auto p = entity_position(cr, "tractor: tractor")) {
        seen_by_crane.t.push_back(t);
        seen_by_crane.at.push_back(*p);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_GT(own.at.size(), 50u) << logs();
  ASSERT_GT(seen_by_crane.at.size(), 50u) << logs();
  EXPECT_GT(core::length(own.at.back() - own.at.front()), 10.0) << "the tractor drove";
  std::vector<double> gaps;
  for (std::size_t k = 0; k < seen_by_crane.t.size(); ++k)
    if (const auto truth = own.interpolated(seen_by_crane.t[k]))
      gaps.push_back(core::length(seen_by_crane.at[k] - *truth));
  ASSERT_GT(gaps.size(), 40u);
  std::sort(gaps.begin(), gaps.end());
  std::printf(
      "the tractor drawn at the crane's station vs its own: median %.3f m, 90th percentile %.3f m, largest "
      "%.3f m (%zu states)\n",
      gaps[gaps.size() / 2], gaps[gaps.size() * 9 / 10], gaps.back(), gaps.size());
  // at ~3 m/s, each state 0-100 ms old on arrival at the console (10 Hz): a few tens of centimetres apart
  EXPECT_LT(gaps[gaps.size() / 2], 0.5) << "median";
  EXPECT_LT(gaps[gaps.size() * 9 / 10], 1.0) << "90th percentile";

  // the tractor's station dies: the crane's tells the consoles the tractor is lost
  kill(tractor, SIGKILL);
  EXPECT_EQ(exit_code(tractor), -SIGKILL);
  const Clock::time_point killed = Clock::now();
  bool lost = false;
  while (!lost && Clock::now() - killed < std::chrono::seconds(20)) {
    console.poll();
    for (const net::StationEvent& e : console.take_events())
      lost = lost || (e.station().to_string() == "crane-cab" && e.kind().to_string() == "team" &&
                      e.text().to_string() == "tractor: lost");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(lost) << logs();
  kill(crane, SIGINT);
  EXPECT_EQ(exit_code(crane), 130);
  const std::string crane_log = read_text(folder / "crane.log");
  EXPECT_NE(crane_log.find("team sts_and_tractor: crane"), std::string::npos) << crane_log;
  EXPECT_NE(crane_log.find("  tractor: "), std::string::npos) << crane_log;
  EXPECT_NE(crane_log.find(", LOST"), std::string::npos) << crane_log;
}

// Each box of a session replayed as a whole (the crane first, then its trucks): which member draws it at
// every replayed step (the crane its box by name, slot k's truck its "load" entity, which the session's scene
// names after the box from its recorded hand-off on), and where it is at the moment the drawing passes from
// the crane to the truck.
struct HandOffsSeen {
  int drawn_twice[2] = {0, 0}, not_drawn[2] = {0, 0}, hand_offs[2] = {0, 0};
  int load_misnamed[2] = {0, 0};  // steps the truck drew the box under another name than its own
  std::string load_name_at_start[2];
  double at_s[2] = {0.0, 0.0}, jump_m[2] = {0.0, 0.0};
};
HandOffsSeen watch_hand_offs(sim::SessionPlayer& session, const std::vector<std::string>& boxes) {
  HandOffsSeen seen;
  const auto index_of = [&](std::size_t member, const std::string& name) {
    int first = 0;
    for (std::size_t k = 0; k < member; ++k)
      first += static_cast<int>(session.player(k).simulation().scene().entities.size());
    const auto& entities = session.player(member).simulation().scene().entities;
    for (std::size_t e = 0; e < entities.size(); ++e)
      if (entities[e].name == name) return first + static_cast<int>(e);
    return -1;
  };
  int by_crane[2], by_truck[2];
  for (std::size_t slot = 0; slot < 2; ++slot) {
    by_crane[slot] = index_of(0, boxes[slot]);
    by_truck[slot] = index_of(1 + slot, "load");
    EXPECT_TRUE(by_crane[slot] >= 0 && by_truck[slot] >= 0) << boxes[slot];
  }
  const auto snapshot = std::make_unique<scene::Snapshot>();
  std::optional<core::Vec3> crane_had[2];
  const auto steps = static_cast<std::int64_t>(std::llround(session.duration_s() / sim::Simulation::kStep_s));
  for (std::int64_t step = 0; step <= steps; ++step) {
    const double t = static_cast<double>(step) * sim::Simulation::kStep_s;
    session.advance_to(t);
    session.write_snapshot(*snapshot);
    for (std::size_t slot = 0; slot < 2; ++slot) {
      std::optional<core::Vec3> crane_at, truck_at;
      for (int n = 0; n < snapshot->entity_count; ++n) {
        const scene::Snapshot::Entity& e = snapshot->entities[static_cast<std::size_t>(n)];
        if ((e.flags & scene::Snapshot::kHidden) != 0) continue;
        if (static_cast<int>(e.index) == by_crane[slot]) crane_at = e.pose.position;
        if (static_cast<int>(e.index) == by_truck[slot]) truck_at = e.pose.position;
      }
      const std::string& truck_names = session.scene()
                                           .entities[static_cast<std::size_t>(by_truck[slot])]
                                           .name;  // by the recorded hand-off
      if (step == 0) seen.load_name_at_start[slot] = truck_names;
      seen.load_misnamed[slot] += truck_at && truck_names != boxes[slot];
      seen.drawn_twice[slot] += crane_at && truck_at;
      seen.not_drawn[slot] += !crane_at && !truck_at;
      if (truck_at && crane_had[slot]) {
        ++seen.hand_offs[slot];
        seen.at_s[slot] = t;
        seen.jump_m[slot] = core::length(*truck_at - *crane_had[slot]);
      }
      crane_had[slot] = crane_at;
    }
  }
  return seen;
}

TEST(TeamSession, ThreeStationsHandEachBoxOverOnceAndStoreOneSessionThatReplaysBitForBit) {
  // data/teams/sts_and_two_tractors.yaml: the crane sets a box on each tractor's chassis; each tractor takes
  // its box away. All three under their autopilots at five times real time (the session's clock with them).
  const fs::path folder = fresh_folder("harbour_team_hand_off");
  net::ConsoleLink console("team-watch", kDomain + 1);
  const std::vector<std::string> roles = {"crane", "tractor_1", "tractor_2"};
  std::vector<pid_t> members;
  for (const std::string& role : roles)
    members.push_back(start_app({"station",
                                 "--team",
                                 "sts_and_two_tractors",
                                 "--role",
                                 role,
                                 "--autopilot",
                                 "--name",
                                 role + "-cab",
                                 "--domain",
                                 std::to_string(kDomain + 1),
                                 "--time-scale",
                                 "5",
                                 "--seconds",
                                 "150",
                                 "--window",
                                 "off",
                                 "--sound",
                                 "off",
                                 "--db",
                                 "sqlite3://db=" + (folder / (role + ".db")).string(),
                                 "--record",
                                 (folder / (role + ".hsrc")).string()},
                                folder / (role + ".log")));
  const auto logs = [&] {
    std::string all;
    for (const std::string& role : roles)
      all += "--- " + role + "\n" + read_text(folder / (role + ".log"));
    return all;
  };
  // what the stations tell the consoles about the boxes, until all three have ended
  std::vector<std::string> said;
  std::vector<bool> ended(roles.size(), false);
  std::vector<int> codes(roles.size(), -1);
  const auto deadline = Clock::now() + std::chrono::seconds(200);
  while (std::count(ended.begin(), ended.end(), true) < 3 && Clock::now() < deadline) {
    console.poll();
    for (const net::StationEvent& e : console.take_events())
      if (e.kind().to_string() == "team")
        said.push_back(e.station().to_string() + " " + e.text().to_string());
    for (std::size_t k = 0; k < roles.size(); ++k)
      if (!ended[k]) {
        int status = 0;
        if (waitpid(members[k], &status, WNOHANG) == members[k]) {
          ended[k] = true;
          codes[k] = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        }
      }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (std::size_t k = 0; k < roles.size(); ++k) {
    if (!ended[k]) {
      kill(members[k], SIGKILL);
      exit_code(members[k]);
    }
    EXPECT_TRUE(ended[k] && codes[k] == 0) << roles[k] << " ended " << codes[k] << "\n" << logs();
  }
  const auto count_said = [&](const std::string& prefix) {
    return std::count_if(said.begin(), said.end(),
                         [&](const std::string& s) { return s.rfind(prefix, 0) == 0; });
  };
  // each box handed over once, each to its own tractor, both sides saying so
  EXPECT_EQ(count_said("crane-cab TGHU1000012: handed over to tractor_1"), 1) << logs();
  EXPECT_EQ(count_said("crane-cab TGHU1000014: handed over to tractor_2"), 1) << logs();
  EXPECT_EQ(count_said("crane-cab TGHU1000010"), 0) << logs();  // not one of the moves
  EXPECT_EQ(count_said("tractor_1-cab TGHU1000012: acquired from crane"), 1) << logs();
  EXPECT_EQ(count_said("tractor_2-cab TGHU1000014: acquired from crane"), 1) << logs();
  // each tractor's scene sent again with its load named as the box handed over onto it (the consoles' 3D
  // views draw it with that box's paint)
  for (const auto& [station, box] :
       {std::pair{"tractor_1-cab", "TGHU1000012"}, {"tractor_2-cab", "TGHU1000014"}}) {
    const auto found = console.stations().find(station);
    ASSERT_TRUE(found != console.stations().end() && found->second.scene) << station;
    const auto& names = found->second.scene->entity_names();
    EXPECT_TRUE(std::any_of(names.begin(), names.end(), [&](const auto& n) { return n.to_string() == box; }))
        << station << " has no entity named " << box;
    EXPECT_GE(found->second.scene_count, 2u) << station;
  }
  // a tractor that has parked its box leaves the session in order: the others say so, not that it is lost
  EXPECT_EQ(count_said("crane-cab tractor_1: left (tractor_1-cab, its attempt ended)"), 1) << logs();
  EXPECT_EQ(count_said("crane-cab tractor_1: lost"), 0) << logs();

  // three attempts, finished and passed, of one team session; each with its team figures; each recording
  // replays its own machine bit for bit with the others' doings read back from it
  std::string session;
  std::vector<sim::SessionPlayer::Member> replayed;
  for (const std::string& role : roles) {
    records::RecordsStore records("sqlite3://db=" + (folder / (role + ".db")).string());
    const std::vector<records::AttemptRow> attempts = records.attempts();
    ASSERT_EQ(attempts.size(), 1u) << role;
    const records::AttemptRow& a = attempts.front();
    EXPECT_EQ(a.status, "finished") << role << "\n" << logs();
    EXPECT_EQ(a.team, "sts_and_two_tractors");
    EXPECT_EQ(a.team_role, role);
    if (session.empty()) session = a.team_session;
    EXPECT_EQ(a.team_session, session) << role;
    std::map<std::string, double> figures;
    for (const auto& [name, value] : records.metrics(a.id))
      figures[name] = value;
    EXPECT_EQ(figures["moves_completed"], role == "crane" ? 2.0 : 1.0) << role;
    EXPECT_EQ(figures["team_hand_offs"], role == "crane" ? 2.0 : 1.0) << role;
    EXPECT_EQ(figures["team_contacts"], 0.0) << role;
    EXPECT_GT(figures["team_worst_hand_off_ms"], 0.0) << role;
    EXPECT_LT(figures["team_worst_hand_off_ms"], 1000.0) << role;  // (loopback; the benchmark holds 100 ms)
    if (role != "crane") {
      EXPECT_GT(figures["team_waited_s"], 0.0) << role;
    }
    std::printf("%s: hand-offs %.0f, worst settled in %.1f ms, waited %.1f s, closest %.2f m\n", role.c_str(),
                figures["team_hand_offs"], figures["team_worst_hand_off_ms"], figures["team_waited_s"],
                figures["team_closest_m"]);
    sim::Recording recording = records.read_recording_of(a);
    EXPECT_FALSE(recording.team.empty()) << role;
    replayed.push_back(
        {role,
         io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + a.exercise + ".yaml").scenario,
         std::move(recording), 0.0});
  }
  ASSERT_EQ(replayed.size(), 3u);
  // the session as a whole, as the console replays it: each tractor from the hand-off both recorded
  for (int slot : {0, 1}) {
    const std::optional<double> start =
        sim::truck_start_s(replayed[0].recording, slot, replayed[1 + slot].recording);
    ASSERT_TRUE(start.has_value()) << roles[1 + slot];
    replayed[1 + slot].start_s = *start;
  }
  sim::SessionPlayer session_replay(std::move(replayed));
  const HandOffsSeen seen = watch_hand_offs(session_replay, {"TGHU1000012", "TGHU1000014"});
  for (std::size_t k = 0; k < 3; ++k) {
    const sim::ReplayPlayer& played = session_replay.player(k);
    EXPECT_EQ(played.simulation().steps(), played.total_steps()) << roles[k];
    EXPECT_FALSE(played.first_mismatch().has_value())
        << roles[k] << " at step " << played.first_mismatch().value_or(-1);
    EXPECT_GT(played.checkpoints_checked(), 60) << roles[k];
    // the others' machine bodies as its obstacles: at the crane each tractor (its trailer is a team truck's
    // deck there, its load the box the crane set on it); at a tractor the crane's spreader and its gantry's
    // four legs (the gantry's look's solid parts) and the other tractor, its trailer and its load
    EXPECT_EQ(played.simulation().obstacles().count(), k == 0 ? 2 : 8) << roles[k];
  }
  // a tractor's first four obstacles are the crane's legs, where the crane's gantry has them (its look's
  // solid parts: 2 x 2 x 50 m at x -13 and 15 m, y -9 and 9 m, z 25 m in the gantry's frame)
  const sim::Simulation& crane_replayed = session_replay.player(0).simulation();
  const core::Pose gantry =
      crane_replayed.world().pose(dynamic_cast<const sim::StsCrane&>(crane_replayed.machine()).gantry_body());
  const core::Vec3 legs[] = {{-13, -9, 25}, {-13, 9, 25}, {15, -9, 25}, {15, 9, 25}};
  const sim::TeamObstacles& at_tractor = session_replay.player(1).simulation().obstacles();
  for (int leg = 0; leg < 4; ++leg) {
    EXPECT_LT(core::length(at_tractor.pose(leg).position - gantry.to_parent(legs[leg])), 0.05)
        << "leg " << leg;
    EXPECT_TRUE(at_tractor.half_extents_m(leg) == (core::Vec3{1, 1, 25})) << "leg " << leg;
  }
  for (std::size_t slot = 0; slot < 2; ++slot) {
    EXPECT_EQ(seen.drawn_twice[slot], 0) << "box " << slot << " drawn by the crane and its tractor together";
    EXPECT_EQ(seen.not_drawn[slot], 0) << "box " << slot << " drawn by nobody";
    EXPECT_EQ(seen.hand_offs[slot], 1) << "box " << slot;
    EXPECT_EQ(seen.load_name_at_start[slot], "load") << "box " << slot;
    EXPECT_EQ(seen.load_misnamed[slot], 0) << "box " << slot << " drawn on its truck by another name";
    EXPECT_LT(seen.jump_m[slot], 0.05) << "box " << slot << " moved at its hand-off from crane to tractor";
    std::printf("box %zu handed over at %.2f s of the session, drawn %.3f m apart either side\n", slot,
                seen.at_s[slot], seen.jump_m[slot]);
  }
}

TEST(TeamSession, ARoleTheTeamLacksIsRefusedNamingItsRoles) {
  const fs::path folder = fresh_folder("harbour_team_role");
  const pid_t child =
      start_app({"station", "--team", "sts_and_tractor", "--role", "signaller", "--autopilot", "--window",
                 "off", "--sound", "off", "--db", "sqlite3://db=" + (folder / "r.db").string()},
                folder / "station.log");
  EXPECT_NE(exit_code(child), 0);
  const std::string log = read_text(folder / "station.log");
  EXPECT_NE(log.find("team sts_and_tractor has no role 'signaller' (its roles: crane, tractor)"),
            std::string::npos)
      << log;
}

}  // namespace
}  // namespace harbour::apps
