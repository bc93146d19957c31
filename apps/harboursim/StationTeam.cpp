#include "StationTeam.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "StsRun.h"
#include "harbour/sim/Simulation.h"
#include "harbour/station/RealTimeLoop.h"

namespace harbour::apps {

namespace fs = std::filesystem;

namespace {

constexpr auto kPeriod = std::chrono::milliseconds(20);  // 50 Hz, the team reader's rate

// the other roles' machines as this station knows them before it hears from them: their exercises built
// here (not stepped) for their bodies and where those start
std::vector<station::TeamMember> other_members(const io::Team& team, const std::string& role) {
  std::vector<station::TeamMember> members;
  for (const io::TeamRole& r : team.roles) {
    if (r.role == role) continue;
    const sim::ExerciseSettings exercise = load_resolved_exercise(r.exercise_file);
    const sim::Simulation simulation(exercise.scenario);
    const sim::SceneDescription scene = simulation.scene();
    const std::unique_ptr<sim::Snapshot> at_start = simulation.snapshot();
    station::TeamMember m;
    m.role = r.role;
    for (int b = 0; b < scene.machine_entities; ++b) {
      m.bodies.push_back(scene.entities[static_cast<std::size_t>(b)]);
      m.start_poses.push_back(at_start->entities[static_cast<std::size_t>(b)].pose);
    }
    members.push_back(std::move(m));
  }
  return members;
}

std::string team_folders_list() {
  std::string list;
  std::error_code ec;
  for (const auto& f : fs::directory_iterator(fs::path(HARBOUR_DATA_DIR) / "teams", ec))
    if (f.path().extension() == ".yaml") list += (list.empty() ? "" : ", ") + f.path().stem().string();
  return list;
}

}  // namespace

std::string resolve_team(const std::string& name_or_path, const std::string& centre_exercises) {
  if (fs::is_regular_file(name_or_path)) return name_or_path;
  std::vector<fs::path> folders;
  if (!centre_exercises.empty()) folders.push_back(fs::path(centre_exercises).parent_path() / "teams");
  folders.push_back(fs::path(HARBOUR_DATA_DIR) / "teams");
  for (const fs::path& folder : folders)
    if (const fs::path file = folder / (name_or_path + ".yaml"); fs::is_regular_file(file))
      return file.string();
  throw std::runtime_error("no team file '" + name_or_path + "' and no team of that name (" +
                           team_folders_list() + ")");
}

TeamMembership::TeamMembership(const io::Team& team, const std::string& role, const std::string& station,
                               int domain, const sim::SceneDescription& own_scene)
    : team_(team),
      role_(role),
      own_bodies_(own_scene.machine_entities),
      link_(station, team.name, role, domain),
      presence_(own_scene, other_members(team, role)),
      started_unix_ms_(std::chrono::duration_cast<std::chrono::milliseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count()),
      earliest_unix_ms_(started_unix_ms_) {}

std::string TeamMembership::session() const {
  const std::time_t at = static_cast<std::time_t>(earliest_unix_ms_.load() / 1000);
  std::tm utc{};
  gmtime_r(&at, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return team_.name + "@" + stamp;
}

TeamMembership::~TeamMembership() {
  stop();
}

double TeamMembership::now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void TeamMembership::add_to(sim::Snapshot& snapshot) const {
  presence_.write(snapshot, now_s());
}

void TeamMembership::start(std::function<const sim::Snapshot*()> latest,
                           std::function<void(const std::string&)> said) {
  latest_ = std::move(latest);
  said_ = std::move(said);
  thread_ = std::thread([this] { run(); });
}

void TeamMembership::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void TeamMembership::run() {
  // the previous snapshot's bodies, for their velocities by difference
  std::vector<core::Pose> before(static_cast<std::size_t>(own_bodies_));
  std::int64_t before_step = -1;
  auto next = std::chrono::steady_clock::now();
  while (!stop_) {
    // the others' states as they come, this machine's every period
    const auto now = std::chrono::steady_clock::now();
    if (now < next) {
      if (link_.wait(std::min<std::chrono::nanoseconds>(next - now, std::chrono::milliseconds(50)))) take();
      continue;
    }
    next += kPeriod;
    if (const sim::Snapshot* s = latest_ ? latest_() : nullptr; s && s->step != before_step) {
      net::TeamState state;
      state.step(s->step);
      state.time_s(s->time_s);
      state.held(s->held);
      state.started_unix_ms(started_unix_ms_);
      const double dt = before_step < 0 ? 0.0 : static_cast<double>(s->step - before_step) * 1e-3;
      for (int n = 0; n < s->entity_count && n < own_bodies_; ++n) {
        const sim::Snapshot::Entity& e = s->entities[static_cast<std::size_t>(n)];
        if (e.index >= static_cast<std::uint32_t>(own_bodies_)) continue;
        const core::Pose& was = before[e.index];
        const core::Vec3 v = dt > 0.0 ? (1.0 / dt) * (e.pose.position - was.position) : core::Vec3{};
        const core::Vec3 w =
            dt > 0.0 ? core::angular_velocity(was.rotation, e.pose.rotation, dt) : core::Vec3{};
        const core::Quat q = core::Quat::from(e.pose.rotation);
        state.entity_index().push_back(static_cast<std::uint16_t>(e.index));
        for (const double x : {e.pose.position.x, e.pose.position.y, e.pose.position.z, q.x, q.y, q.z, q.w,
                               v.x, v.y, v.z, w.x, w.y, w.z})
          state.motion().push_back(static_cast<float>(x));
        before[e.index] = e.pose;
      }
      before_step = s->step;
      link_.publish(state);
      ++published_;
      for (const std::string& said : near_misses_.update(presence_.closest(*s, now_s())))
        if (said_) said_(said);
    }
    take();
  }
}

void TeamMembership::take() {
  {
    const std::int64_t arrived_ns = net::TeamLink::monotonic_ns();
    for (const net::TeamState& t : link_.take()) {
      station::TeamSample sample;
      sample.role = t.role().to_string();
      sample.received_s = now_s();
      sample.age_s = static_cast<double>(arrived_ns - t.sent_ns()) * 1e-9;  // one host: one monotonic clock
      const std::vector<float>& m = t.motion();
      sample.body = t.entity_index();
      if (m.size() != sample.body.size() * 13) continue;  // torn: not ours to draw
      for (std::size_t k = 0; k < sample.body.size(); ++k) {
        const float* f = &m[k * 13];
        station::RemoteMotion r;
        r.pose.position = {f[0], f[1], f[2]};
        r.pose.rotation = core::Quat{f[3], f[4], f[5], f[6]}.matrix();
        r.velocity_mps = {f[7], f[8], f[9]};
        r.angular_velocity_radps = {f[10], f[11], f[12]};
        sample.motion.push_back(r);
      }
      const std::string why = presence_.offer(sample);
      if (why.empty() && t.started_unix_ms() > 0 && t.started_unix_ms() < earliest_unix_ms_)
        earliest_unix_ms_ = t.started_unix_ms();
      if (!why.empty() && said_ && refused_.insert(t.station().to_string() + why).second)
        said_(t.station().to_string() + ": " + why);  // once each
      if (why.empty() && joined_.insert(sample.role).second && said_)
        said_(sample.role + ": joined (" + t.station().to_string() + ")");
    }
  }
  {
    std::vector<std::string> changed;
    for (const station::TeamPresence::MemberState& m : presence_.members(now_s(), &changed))
      for (const std::string& role : changed)
        if (role == m.role && said_) said_(role + (m.lost ? ": lost" : ": back"));
  }
}

TeamMembership::Figures TeamMembership::figures() const {
  Figures f;
  for (const station::NearMissWatch::Tally& t : near_misses_.tallies()) {
    f.near_misses += t.near_misses;
    f.contacts += t.contacts;
    const double closest = std::max(t.closest_m, 0.0);
    f.closest_m = f.closest_m < 0.0 ? closest : std::min(f.closest_m, closest);
  }
  return f;
}

std::vector<std::string> TeamMembership::report() {
  std::vector<std::string> lines;
  char line[256];
  std::snprintf(line, sizeof line, "team %s: %s, %lld states published", team_.name.c_str(), role_.c_str(),
                static_cast<long long>(published_));
  lines.emplace_back(line);
  for (const station::TeamPresence::MemberState& m : presence_.members(now_s(), nullptr, true)) {
    if (!m.heard) {
      lines.push_back("  " + m.role + ": never heard (drawn where its exercise starts it)");
      continue;
    }
    std::snprintf(line, sizeof line,
                  "  %s: %lld states, age on arrival p50 %.2f ms, p99 %.2f ms, max %.2f ms%s", m.role.c_str(),
                  static_cast<long long>(m.samples), m.age_p50_s * 1e3, m.age_p99_s * 1e3, m.age_max_s * 1e3,
                  m.lost ? ", LOST" : "");
    std::string text = line;
    for (const station::NearMissWatch::Tally& t : near_misses_.tallies())
      if (t.role == m.role) {
        std::snprintf(line, sizeof line, "; closest %.2f m, %d near miss%s, %d contact%s",
                      std::max(t.closest_m, 0.0), t.near_misses, t.near_misses == 1 ? "" : "es", t.contacts,
                      t.contacts == 1 ? "" : "s");
        text += line;
      }
    lines.push_back(text);
  }
  return lines;
}

}  // namespace harbour::apps
