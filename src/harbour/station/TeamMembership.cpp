#include "harbour/station/TeamMembership.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "harbour/records/Centre.h"
#include "harbour/sim/Simulation.h"
#include "harbour/station/RealTimeLoop.h"

namespace harbour::station {

namespace fs = std::filesystem;

namespace {

constexpr auto kPeriod = std::chrono::milliseconds(20);  // 50 Hz, the team reader's rate
constexpr double kOfferEvery_s = 0.1;                    // a box offered again until it is acquired
constexpr double kStanding_mps = 0.05;                   // a trailer this slow stands
constexpr double kAtLoadStop_m = 1.5;                    // its centre this near its load stop
// how far a remote body may depart from where the simulation carries its last input on before it is given a
// new one: a team truck's deck within 2 mm (a box is set on it), an obstacle within 2 cm
struct FeedTolerance {
  double m, mps, rad, radps;
};
constexpr FeedTolerance kTruckTolerance{0.002, 0.002, 0.0005, 0.0005};
constexpr FeedTolerance kObstacleTolerance{0.02, 0.02, 0.002, 0.002};

// An input of `kind` for `slot`: a frame fixed to remote body `body` that stands at `at` now, moving with it
sim::TeamInput riding(sim::TeamInput::Kind kind, int slot, const RemoteMotion& body, const core::Pose& at) {
  sim::TeamInput in;
  in.kind = kind;
  in.slot = slot;
  in.pose = at;
  in.velocity_mps =
      body.velocity_mps + core::cross(body.angular_velocity_radps, at.position - body.pose.position);
  in.angular_velocity_radps = body.angular_velocity_radps;
  return in;
}

// `now` departs from where the simulation has carried `was` (given at `was_s`) on to `now_s`
bool departs(const sim::TeamInput& was, double was_s, const sim::TeamInput& now, double now_s,
             const FeedTolerance& tolerance) {
  const core::Vec3 carried = was.pose.position + (now_s - was_s) * was.velocity_mps;
  double turned = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      turned = std::max(turned, std::abs(now.pose.rotation.m[r][c] - was.pose.rotation.m[r][c]));
  return core::length(now.pose.position - carried) >= tolerance.m ||
         core::length(now.velocity_mps - was.velocity_mps) >= tolerance.mps || turned >= tolerance.rad ||
         core::length(now.angular_velocity_radps - was.angular_velocity_radps) >= tolerance.radps;
}

const scene::Snapshot::Entity* entity_in(const scene::Snapshot& s, int index) {
  for (int n = 0; n < s.entity_count; ++n)
    if (s.entities[static_cast<std::size_t>(n)].index == static_cast<std::uint32_t>(index))
      return &s.entities[static_cast<std::size_t>(n)];
  return nullptr;
}

int entity_named(const scene::SceneDescription& scene, const std::string& name) {
  for (std::size_t n = 0; n < scene.entities.size(); ++n)
    if (scene.entities[n].name == name) return static_cast<int>(n);
  return -1;
}

// the other roles' machines as this station knows them before it hears from them: their exercises built
// here (not stepped) for their bodies and where those start
std::vector<TeamMember> other_members(const io::Team& team, const std::string& role) {
  std::vector<TeamMember> members;
  for (const io::TeamRole& r : team.roles) {
    if (r.role == role) continue;
    const sim::ExerciseSettings exercise = records::load_resolved_exercise(r.exercise_file);
    const sim::Simulation simulation(exercise.scenario);
    const scene::SceneDescription scene = simulation.scene();
    const std::unique_ptr<scene::Snapshot> at_start = simulation.snapshot();
    // its machine's bodies, and its scene on to its last liftable item (what it sends while it holds one or
    // hands one over; hidden until then)
    std::size_t bodies = static_cast<std::size_t>(scene.machine_entities);
    for (const sim::ContainerPlacement& c : exercise.scenario.containers)
      for (std::size_t n = bodies; n < scene.entities.size(); ++n)
        if (scene.entities[n].name == c.id) bodies = n + 1;
    TeamMember m;
    m.role = r.role;
    m.machine_bodies = scene.machine_entities;
    std::vector<core::Pose> start(scene.entities.size());
    std::vector<std::uint32_t> start_flags(scene.entities.size(), scene::Snapshot::kHidden);
    for (int n = 0; n < at_start->entity_count; ++n) {
      const scene::Snapshot::Entity& e = at_start->entities[static_cast<std::size_t>(n)];
      if (e.index < start.size()) start[e.index] = e.pose, start_flags[e.index] = e.flags;
    }
    for (std::size_t b = 0; b < bodies; ++b) {
      m.bodies.push_back(scene.entities[b]);
      m.start_poses.push_back(start[b]);
      m.start_hidden.push_back(static_cast<int>(b) >= scene.machine_entities ||
                               (start_flags[b] & scene::Snapshot::kHidden) != 0);
    }
    members.push_back(std::move(m));
  }
  return members;
}

std::string team_folders_list() {
  std::string list;
  std::error_code ec;
  for (const auto& f : fs::directory_iterator(fs::path(records::shipped_data_folder()) / "teams", ec))
    if (f.path().extension() == ".yaml") list += (list.empty() ? "" : ", ") + f.path().stem().string();
  return list;
}

}  // namespace

std::string resolve_team(const std::string& name_or_path, const std::string& centre_exercises) {
  if (fs::is_regular_file(name_or_path)) return name_or_path;
  std::vector<fs::path> folders;
  if (!centre_exercises.empty()) folders.push_back(fs::path(centre_exercises).parent_path() / "teams");
  folders.push_back(fs::path(records::shipped_data_folder()) / "teams");
  for (const fs::path& folder : folders)
    if (const fs::path file = folder / (name_or_path + ".yaml"); fs::is_regular_file(file))
      return file.string();
  throw std::runtime_error("no team file '" + name_or_path + "' and no team of that name (" +
                           team_folders_list() + ")");
}

TeamMembership::TeamMembership(const io::Team& team, const std::string& role, const std::string& station,
                               int domain, const sim::ExerciseSettings& own_exercise,
                               const scene::SceneDescription& own_scene, double time_scale,
                               const SolidParts& solid)
    : team_(team),
      role_(role),
      time_scale_(time_scale),
      own_bodies_(own_scene.machine_entities),
      own_entities_(static_cast<int>(own_scene.entities.size())),
      link_(station, team.name, role, domain),
      presence_(own_scene, other_members(team, role)),
      started_unix_ms_(std::chrono::duration_cast<std::chrono::milliseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count()),
      earliest_unix_ms_(started_unix_ms_) {
  // a crane's team trucks: each a truck role's trailer, its deck where the crane's lane has a truck
  const io::TeamRole& own = *team.find(role);
  const int lane = own_exercise.scenario.trucks.team ? own_exercise.scenario.trucks.trucks : 0;
  if (static_cast<int>(own.trucks.size()) != lane)
    throw std::runtime_error("team " + team.name + ": " + role + " has " + std::to_string(own.trucks.size()) +
                             " trucks in the team file, its exercise " + own_exercise.name + " a lane of " +
                             std::to_string(lane) + " team trucks");
  const scene::SceneDescription& scene = presence_.scene();
  for (std::size_t k = 0; k < own.trucks.size(); ++k) {
    Truck t;
    t.role = own.trucks[k];
    t.entity = entity_named(scene, "truck " + std::to_string(k + 1));
    t.trailer_body = entity_named(scene, t.role + ": trailer");
    const int load = entity_named(scene, t.role + ": load");
    if (t.trailer_body < 0 || load < 0)
      throw std::runtime_error("team " + team.name + ": " + t.role + " is a truck of " + role +
                               ", but its exercise's trailer takes no box (trailer.receives)");
    t.deck_half_z_m = scene.entities[static_cast<std::size_t>(t.trailer_body)].half_extents_m.z;
    // its index among the member's bodies (they follow one another in this station's scene)
    int first = t.trailer_body;
    while (first > 0 && scene.entities[static_cast<std::size_t>(first - 1)].name.rfind(t.role + ": ", 0) == 0)
      --first;
    t.trailer_body -= first;
    trucks_.push_back(t);
  }
  // the others' machine bodies as obstacles, in the team's order (a crane's team trucks' trailers are its
  // decks, and the loads on them the boxes it set there)
  for (const TeamMember& m : presence_.known())
    for (int b = 0; b < std::min(m.machine_bodies, static_cast<int>(m.bodies.size())); ++b) {
      const scene::SceneDescription::Entity& body = m.bodies[static_cast<std::size_t>(b)];
      const core::Vec3 h = body.half_extents_m;
      const bool in_lane = std::any_of(trucks_.begin(), trucks_.end(), [&](const Truck& t) {
        return t.role == m.role && (t.trailer_body == b || body.name == scene::kTrailerLoad);
      });
      if (h.x > 0.0 && h.y > 0.0 && h.z > 0.0 && !in_lane)
        obstacles_.push_back({m.role, b, core::Pose{}, h, {}});
      if (const auto parts = solid.find(body.visual); parts != solid.end())
        for (const SolidPart& part : parts->second)
          obstacles_.push_back({m.role, b, part.local, part.half_extents_m, {}});
    }
  if (static_cast<int>(obstacles_.size()) > sim::TeamObstacles::kMostObstacles)
    obstacles_.resize(sim::TeamObstacles::kMostObstacles);
  for (const sim::ContainerPlacement& c : own_exercise.scenario.containers)
    box_mass_kg_[c.id] = c.gross_mass_kg;
  load_stop_ = own_exercise.load_stop;
  trailer_entity_ = entity_named(own_scene, "trailer");
  load_entity_ = entity_named(own_scene, scene::kTrailerLoad);
}

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

double TeamMembership::wall_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double TeamMembership::now_s() const {
  return wall_s() * time_scale_;
}

void TeamMembership::add_to(scene::Snapshot& snapshot) const {
  presence_.write(snapshot, now_s());
}

void TeamMembership::start(std::function<const scene::Snapshot*()> latest,
                           std::function<void(const std::string&)> said,
                           std::function<bool(const sim::TeamInput&)> input,
                           std::function<void(int entity, const std::string& id)> load_named) {
  latest_ = std::move(latest);
  load_named_ = std::move(load_named);
  said_ = std::move(said);
  input_ = std::move(input);
  thread_ = std::thread([this] { run(); });
}

void TeamMembership::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void TeamMembership::leave() {
  // best effort: said three times, 20 ms apart (one lost still leaves the others told)
  net::TeamState state;
  state.leaving(true);
  state.started_unix_ms(started_unix_ms_);
  for (int n = 0; n < 3; ++n) {
    link_.publish(state);
    std::this_thread::sleep_for(kPeriod);
  }
}

void TeamMembership::run() {
  // the previous snapshot's bodies, for their velocities by difference
  std::vector<core::Pose> before(static_cast<std::size_t>(own_entities_));
  std::vector<std::int64_t> before_at(static_cast<std::size_t>(own_entities_),
                                      -1);  // its step (-1: not sent)
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
    // every period, held or not (a frozen member is not a lost one)
    if (const scene::Snapshot* s = latest_ ? latest_() : nullptr) {
      net::TeamState state;
      state.step(s->step);
      state.time_s(s->time_s);
      state.held(s->held);
      state.started_unix_ms(started_unix_ms_);
      for (int n = 0; n < s->entity_count; ++n) {
        const scene::Snapshot::Entity& e = s->entities[static_cast<std::size_t>(n)];
        // its machine's bodies and the items it holds or hands over (one it does not draw, as a load still to
        // come, is not sent: the others hide it)
        const bool item = (e.flags & (scene::Snapshot::kLocked | scene::Snapshot::kOnTeamTruck)) != 0;
        if (e.index >= static_cast<std::uint32_t>(own_entities_) ||
            (e.flags & scene::Snapshot::kHidden) != 0 ||
            (e.index >= static_cast<std::uint32_t>(own_bodies_) && !item) ||
            state.entity_index().size() >= 256)
          continue;
        // (a body that has just appeared, as a load handed over, has no velocity yet)
        const core::Pose& was = before[e.index];
        const double dt = before_at[e.index] == before_step && before_step >= 0 && s->step > before_step
                              ? static_cast<double>(s->step - before_step) * 1e-3
                              : 0.0;
        const core::Vec3 v = dt > 0.0 ? (1.0 / dt) * (e.pose.position - was.position) : core::Vec3{};
        const core::Vec3 w =
            dt > 0.0 ? core::angular_velocity(was.rotation, e.pose.rotation, dt) : core::Vec3{};
        const core::Quat q = core::Quat::from(e.pose.rotation);
        state.entity_index().push_back(static_cast<std::uint16_t>(e.index));
        for (const double x : {e.pose.position.x, e.pose.position.y, e.pose.position.z, q.x, q.y, q.z, q.w,
                               v.x, v.y, v.z, w.x, w.y, w.z})
          state.motion().push_back(static_cast<float>(x));
        before[e.index] = e.pose;
        before_at[e.index] = s->step;
      }
      before_step = s->step;
      link_.publish(state);
      ++published_;
      for (const std::string& said : near_misses_.update(presence_.closest(*s, now_s())))
        if (said_) said_(said);
      offer_seated(*s);
      watch_load_stop(*s);
    }
    feed_trucks();
    feed_obstacles();
    take();
  }
}

void TeamMembership::feed_trucks() {
  if (!input_) return;
  const double now = now_s();
  for (std::size_t k = 0; k < trucks_.size(); ++k) {
    Truck& truck = trucks_[k];
    const std::optional<RemoteMotion> m = presence_.motion_of(truck.role, truck.trailer_body, now);
    if (!m) continue;
    // its deck's top centre, moving with the trailer
    const sim::TeamInput in = riding(sim::TeamInput::Kind::kTruckAt, static_cast<int>(k), *m,
                                     sim::deck_of_trailer(m->pose, truck.deck_half_z_m));
    // only where it departs from where the simulation carries the last one on (each input is recorded: a
    // tractor standing under the crane for minutes costs nothing)
    if (!truck.fed.input || departs(*truck.fed.input, truck.fed.at_s, in, now, kTruckTolerance))
      give(truck.fed, in, now);
  }
}

void TeamMembership::give(Fed& fed, const sim::TeamInput& in, double now_s) {
  if (input_(in)) fed = {in, now_s};  // (refused: tried again next period)
}

void TeamMembership::feed_obstacles() {
  if (!input_) return;
  const double now = now_s();
  for (std::size_t k = 0; k < obstacles_.size(); ++k) {
    Obstacle& o = obstacles_[k];
    const std::optional<RemoteMotion> m = presence_.motion_of(o.role, o.body, now);
    if (!m) continue;
    sim::TeamInput in = riding(sim::TeamInput::Kind::kObstacleAt, static_cast<int>(k), *m,
                               {m->pose.rotation * o.local.rotation, m->pose.to_parent(o.local.position)});
    if (presence_.there(o.role, o.body)) in.half_extents_m = o.half_extents_m;  // else gone: no size
    const std::optional<sim::TeamInput>& was = o.fed.input;
    if (!was || was->half_extents_m != in.half_extents_m ||
        (in.half_extents_m != core::Vec3{} && departs(*was, o.fed.at_s, in, now, kObstacleTolerance)))
      give(o.fed, in, now);
  }
}

void TeamMembership::offer_seated(const scene::Snapshot& s) {
  if (trucks_.empty()) return;
  const double now = wall_s();
  const scene::SceneDescription& scene = presence_.scene();
  for (int n = 0; n < s.entity_count; ++n) {
    const scene::Snapshot::Entity& e = s.entities[static_cast<std::size_t>(n)];
    if ((e.flags & scene::Snapshot::kOnTeamTruck) == 0) continue;
    const std::string& id = scene.entities[e.index].name;
    Offer& offer = offers_[id];
    if (offer.settled || now - offer.last_s < kOfferEvery_s) continue;
    if (offer.truck < 0) {
      // the truck whose deck it sits on (the nearest across the deck), and where it sits on that trailer
      double nearest = 1e300;
      core::Pose on_trailer;
      for (std::size_t k = 0; k < trucks_.size(); ++k) {
        const scene::Snapshot::Entity* truck = entity_in(s, trucks_[k].entity);
        if (!truck) continue;
        const core::Vec3 on = truck->pose.to_local(e.pose.position);
        if (std::hypot(on.x, on.y) >= nearest) continue;
        nearest = std::hypot(on.x, on.y);
        offer.truck = static_cast<int>(k);
        on_trailer = sim::on_trailer(truck->pose, e.pose, trucks_[k].deck_half_z_m);
      }
      if (offer.truck < 0) continue;
      const core::Quat q = core::Quat::from(on_trailer.rotation);
      std::array<float, 7> at{};
      std::size_t n_at = 0;
      for (const double v :
           {on_trailer.position.x, on_trailer.position.y, on_trailer.position.z, q.x, q.y, q.z, q.w})
        at[n_at++] = static_cast<float>(v);
      offer.message.on_trailer(at);
      offer.first_s = now;
      offer.message.kind(0);
      offer.message.to_role(trucks_[static_cast<std::size_t>(offer.truck)].role);
      offer.message.item(id);
      offer.message.mass_kg(static_cast<float>(box_mass_kg_[id]));
      if (said_) said_(id + ": offered to " + trucks_[static_cast<std::size_t>(offer.truck)].role);
    }
    offer.last_s = now;
    link_.hand_off(offer.message);
  }
}

void TeamMembership::watch_load_stop(const scene::Snapshot& s) {
  if (!load_stop_ || trailer_entity_ < 0 || load_entity_ < 0 || waited_s_ >= 0.0) return;
  for (int n = 0; n < s.entity_count; ++n) {
    const scene::Snapshot::Entity& e = s.entities[static_cast<std::size_t>(n)];
    if (e.index == static_cast<std::uint32_t>(load_entity_) && (e.flags & scene::Snapshot::kHidden) == 0) {
      waited_s_ = standing_since_s_ >= 0.0 ? s.time_s - standing_since_s_ : 0.0;  // its box is on
      return;
    }
    if (e.index != static_cast<std::uint32_t>(trailer_entity_)) continue;
    const core::Vec3 p = e.pose.position;
    const double speed = trailer_was_s_ >= 0.0 && s.time_s > trailer_was_s_
                             ? core::length(p - trailer_was_) / (s.time_s - trailer_was_s_)
                             : 0.0;
    const bool there =
        std::hypot(p.x - load_stop_->trailer_at_m.x, p.y - load_stop_->trailer_at_m.y) < kAtLoadStop_m;
    if (there && speed < kStanding_mps && standing_since_s_ < 0.0) standing_since_s_ = s.time_s;
    if (!there) standing_since_s_ = -1.0;
    trailer_was_ = p;
    trailer_was_s_ = s.time_s;
  }
}

void TeamMembership::take_hand_offs() {
  const double now = wall_s();
  for (const net::TeamHandOff& m : link_.take_hand_offs()) {
    const std::string item = m.item().to_string();
    if (m.kind() == 0 && m.to_role().to_string() == role_) {
      // offered to this tractor: onto its trailer (once), and say so to every offer
      if (!acquired_.count(item)) {
        const std::array<float, 7>& p = m.on_trailer();
        sim::TeamInput in;
        in.kind = sim::TeamInput::Kind::kLoadOn;
        in.pose = {core::Quat{p[3], p[4], p[5], p[6]}.matrix(), {p[0], p[1], p[2]}};
        in.mass_kg = m.mass_kg();
        in.name_item(item);  // recorded: a replay draws the box by its name (a longer one: as "load")
        if (!input_ || !input_(in)) continue;  // not taken: the next offer tries again
        acquired_.insert(item);
        if (load_named_ && load_entity_ >= 0) load_named_(load_entity_, item);
        ++hand_offs_;
        const double took_s = static_cast<double>(net::TeamLink::monotonic_ns() - m.sent_ns()) * 1e-9;
        worst_hand_off_s_ = std::max(worst_hand_off_s_, took_s);
        if (said_) said_(item + ": acquired from " + m.from_role().to_string());
      }
      net::TeamHandOff answer;
      answer.kind(1);
      answer.from_role(m.from_role());
      answer.item(m.item());
      link_.hand_off(answer);
    } else if (m.kind() == 1 && m.from_role().to_string() == role_) {
      // the tractor has it: this crane lets it go
      const auto offer = offers_.find(item);
      if (offer == offers_.end() || offer->second.settled) continue;
      sim::TeamInput in;
      in.kind = sim::TeamInput::Kind::kTakenOver;
      in.slot = offer->second.truck;
      if (!input_ || !input_(in)) continue;
      offer->second.settled = true;
      ++hand_offs_;
      const double took_s = now - offer->second.first_s;
      worst_hand_off_s_ = std::max(worst_hand_off_s_, took_s);
      char line[160];
      std::snprintf(line, sizeof line, "%s: handed over to %s (%.0f ms)", item.c_str(),
                    m.to_role().to_string().c_str(), took_s * 1e3);
      if (said_) said_(line);
    }
  }
}

void TeamMembership::take() {
  take_hand_offs();
  {
    const std::int64_t arrived_ns = net::TeamLink::monotonic_ns();
    for (const net::TeamState& t : link_.take()) {
      const std::string role = t.role().to_string();
      if (t.leaving()) {  // its machine stays where it was last drawn
        if (role != role_ && team_.find(role) && left_.insert(role).second) {
          presence_.left(role);
          if (said_) said_(role + ": left (" + t.station().to_string() + ", its attempt ended)");
        }
        continue;
      }
      TeamSample sample;
      sample.role = role;
      sample.received_s = now_s();
      sample.age_s = static_cast<double>(arrived_ns - t.sent_ns()) * 1e-9;  // one host: one monotonic clock
      const std::vector<float>& m = t.motion();
      sample.body = t.entity_index();
      if (m.size() != sample.body.size() * 13) continue;  // torn: not ours to draw
      for (std::size_t k = 0; k < sample.body.size(); ++k) {
        const float* f = &m[k * 13];
        RemoteMotion r;
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
    for (const TeamPresence::MemberState& m : presence_.members(now_s(), &changed))
      for (const std::string& role : changed)
        if (role == m.role && said_) said_(role + (m.lost ? ": lost" : ": back"));
  }
}

sim::TeamFigures TeamMembership::figures() const {
  sim::TeamFigures f;
  for (const NearMissWatch::Tally& t : near_misses_.tallies()) {
    f.near_misses += t.near_misses;
    f.contacts += t.contacts;
    const double closest = std::max(t.closest_m, 0.0);
    f.closest_m = f.closest_m < 0.0 ? closest : std::min(f.closest_m, closest);
  }
  f.hand_offs = hand_offs_;
  f.worst_hand_off_ms = worst_hand_off_s_ < 0.0 ? -1.0 : worst_hand_off_s_ * 1e3;
  f.waited_s = waited_s_;
  return f;
}

std::vector<std::string> TeamMembership::report() {
  std::vector<std::string> lines;
  char line[256];
  std::snprintf(line, sizeof line, "team %s: %s, %lld states published", team_.name.c_str(), role_.c_str(),
                static_cast<long long>(published_));
  lines.emplace_back(line);
  for (const TeamPresence::MemberState& m : presence_.members(now_s(), nullptr, true)) {
    if (!m.heard) {
      lines.push_back("  " + m.role + ": never heard (drawn where its exercise starts it)");
      continue;
    }
    std::snprintf(line, sizeof line,
                  "  %s: %lld states, age on arrival p50 %.2f ms, p99 %.2f ms, max %.2f ms%s", m.role.c_str(),
                  static_cast<long long>(m.samples), m.age_p50_s * 1e3, m.age_p99_s * 1e3, m.age_max_s * 1e3,
                  m.lost   ? ", LOST"
                  : m.left ? ", left"
                           : "");
    std::string text = line;
    for (const NearMissWatch::Tally& t : near_misses_.tallies())
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

}  // namespace harbour::station
