#include "harbour/station/TeamPresence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace harbour::station {

namespace {
constexpr std::size_t kMostAges = 1 << 20;  // an hour and more at 50 Hz per member
}

void DeadReckoning::place(const RemoteMotion& motion, double at_s) {
  old_ = new_ = motion;
  old_at_s_ = new_at_s_ = at_s;
  blending_ = false;
}

void DeadReckoning::update(const RemoteMotion& motion, double at_s) {
  // blend from where the body is drawn now, moving as it is drawn moving: the newest sample's velocities, or
  // a blend in progress frozen into a sample
  core::Vec3 velocity = new_.velocity_mps, spin = new_.angular_velocity_radps;
  if (blending_) {
    const double f = std::clamp((at_s - new_at_s_) / blend_s_, 0.0, 1.0);
    velocity = (1.0 - f) * old_.velocity_mps + f * new_.velocity_mps;
    spin = (1.0 - f) * old_.angular_velocity_radps + f * new_.angular_velocity_radps;
  }
  old_ = {at(at_s), velocity, spin};
  old_at_s_ = at_s;
  new_ = motion;
  new_at_s_ = at_s;
  blending_ = true;
}

core::Pose DeadReckoning::carried(const RemoteMotion& m, double from_s, double t_s) const {
  const double dt = std::clamp(t_s - from_s, 0.0, horizon_s_);
  return {core::turned(m.pose.rotation, m.angular_velocity_radps, dt), m.pose.position + dt * m.velocity_mps};
}

core::Pose DeadReckoning::at(double t_s) const {
  const core::Pose ahead = carried(new_, new_at_s_, t_s);
  if (!blending_) return ahead;
  const double f = std::clamp((t_s - new_at_s_) / blend_s_, 0.0, 1.0);
  if (f >= 1.0) return ahead;
  const core::Pose before = carried(old_, old_at_s_, t_s);
  return {core::between(before.rotation, ahead.rotation, f),
          (1.0 - f) * before.position + f * ahead.position};
}

double box_clearance(const core::Pose& a, const core::Vec3& half_a, const core::Pose& b,
                     const core::Vec3& half_b) {
  const core::Vec3 ea[3] = {a.rotation.column(0), a.rotation.column(1), a.rotation.column(2)};
  const core::Vec3 eb[3] = {b.rotation.column(0), b.rotation.column(1), b.rotation.column(2)};
  const double ha[3] = {half_a.x, half_a.y, half_a.z}, hb[3] = {half_b.x, half_b.y, half_b.z};
  const core::Vec3 d = b.position - a.position;
  double best = -1e300;
  const auto along = [&](core::Vec3 axis) {
    const double n = core::length(axis);
    if (n < 1e-9) return;  // parallel edges: their cross product is no axis
    axis = (1.0 / n) * axis;
    double ra = 0.0, rb = 0.0;
    for (int k = 0; k < 3; ++k) {
      ra += ha[k] * std::abs(core::dot(ea[k], axis));
      rb += hb[k] * std::abs(core::dot(eb[k], axis));
    }
    best = std::max(best, std::abs(core::dot(d, axis)) - ra - rb);
  };
  for (int i = 0; i < 3; ++i) {
    along(ea[i]);
    along(eb[i]);
    for (int j = 0; j < 3; ++j)
      along(core::cross(ea[i], eb[j]));
  }
  return best;
}

TeamPresence::TeamPresence(const scene::SceneDescription& own_scene, std::vector<TeamMember> members)
    : scene_(own_scene) {
  for (TeamMember& known : members) {
    Member m;
    m.first_entity = static_cast<int>(scene_.entities.size());
    for (std::size_t b = 0; b < known.bodies.size(); ++b) {
      scene::SceneDescription::Entity e = known.bodies[b];
      e.name = known.role + ": " + e.name;
      scene_.entities.push_back(e);
      DeadReckoning body(kBlend_s, kHorizon_s);
      body.place({b < known.start_poses.size() ? known.start_poses[b] : core::Pose{}, {}, {}}, 0.0);
      m.bodies.push_back(body);
      m.present.push_back(!(b < known.start_hidden.size() && known.start_hidden[b]));
    }
    m.state.role = known.role;
    m.known = std::move(known);
    members_.push_back(std::move(m));
  }
}

std::string TeamPresence::offer(const TeamSample& sample) {
  const std::lock_guard lock(mutex_);
  const auto member = std::find_if(members_.begin(), members_.end(),
                                   [&](const Member& m) { return m.known.role == sample.role; });
  if (member == members_.end()) return "no member of this team has the role '" + sample.role + "'";
  if (sample.body.size() != sample.motion.size()) return "a sample of '" + sample.role + "' is torn";
  for (const std::uint16_t b : sample.body)
    if (b >= member->bodies.size())
      return "'" + sample.role + "' has " + std::to_string(member->bodies.size()) + " bodies, not body " +
             std::to_string(b);
  const std::vector<bool> was_present = member->present;
  std::fill(member->present.begin(), member->present.end(), false);
  for (std::size_t k = 0; k < sample.body.size(); ++k) {
    member->present[sample.body[k]] = true;
    DeadReckoning& body = member->bodies[sample.body[k]];
    // (one that has just appeared, as a load handed over, is put there, not blended in from where it was)
    if (member->state.heard && was_present[sample.body[k]])
      body.update(sample.motion[k], sample.received_s);
    else
      body.place(sample.motion[k], sample.received_s);
  }
  member->state.heard = true;
  ++member->state.samples;
  if (sample.age_s >= 0.0 && member->ages_s.size() < kMostAges) member->ages_s.push_back(sample.age_s);
  member->last_heard_s = sample.received_s;
  return "";
}

void TeamPresence::write(scene::Snapshot& snapshot, double now_s) const {
  const std::lock_guard lock(mutex_);
  for (const Member& m : members_)
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      if (snapshot.entity_count >= scene::kMaxEntities) return;
      const int index = m.first_entity + static_cast<int>(b);
      snapshot.entities[static_cast<std::size_t>(snapshot.entity_count++)] = {
          static_cast<std::uint32_t>(index), m.present[b] ? 0u : scene::Snapshot::kHidden,
          m.bodies[b].at(now_s)};
    }
}

std::optional<RemoteMotion> TeamPresence::motion_of(const std::string& role, int body, double now_s) const {
  const std::lock_guard lock(mutex_);
  for (const Member& m : members_) {
    if (m.known.role != role) continue;
    if (body < 0 || body >= static_cast<int>(m.bodies.size())) return std::nullopt;
    const DeadReckoning& d = m.bodies[static_cast<std::size_t>(body)];
    RemoteMotion r = d.newest();
    r.pose = d.at(now_s);
    if (!m.state.heard || m.state.lost) r.velocity_mps = r.angular_velocity_radps = {};  // where it stands
    return r;
  }
  return std::nullopt;
}

std::vector<TeamPresence::Closest> TeamPresence::closest(const scene::Snapshot& own, double now_s) const {
  const auto sized = [](const core::Vec3& h) { return h.x > 0.0 && h.y > 0.0 && h.z > 0.0; };
  const std::lock_guard lock(mutex_);
  std::vector<Closest> result;
  for (const Member& m : members_) {
    Closest c{m.known.role, "", "", 1e300};
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const core::Vec3& half_b = m.known.bodies[b].half_extents_m;
      if (!sized(half_b) || !m.present[b] || static_cast<int>(b) >= m.known.machine_bodies) continue;
      const core::Pose pose_b = m.bodies[b].at(now_s);
      for (int n = 0; n < own.entity_count; ++n) {
        const scene::Snapshot::Entity& e = own.entities[static_cast<std::size_t>(n)];
        if (static_cast<int>(e.index) >= scene_.machine_entities || (e.flags & scene::Snapshot::kHidden) != 0)
          continue;
        const scene::SceneDescription::Entity& body = scene_.entities[e.index];
        if (!sized(body.half_extents_m)) continue;
        const double gap = box_clearance(e.pose, body.half_extents_m, pose_b, half_b);
        if (gap < c.clearance_m) c = {m.known.role, body.name, m.known.bodies[b].name, gap};
      }
    }
    if (!c.own_body.empty()) result.push_back(c);
  }
  return result;
}

std::vector<TeamPresence::MemberState> TeamPresence::members(double now_s, std::vector<std::string>* changed,
                                                             bool with_ages) {
  const std::lock_guard lock(mutex_);
  std::vector<MemberState> states;
  for (Member& m : members_) {
    const bool lost = m.state.heard && !m.state.left && now_s - m.last_heard_s > kLostAfter_s;
    if (lost != m.state.lost && changed) changed->push_back(m.known.role);
    m.state.lost = lost;
    m.state.measured = static_cast<std::int64_t>(m.ages_s.size());
    if (with_ages && !m.ages_s.empty()) {
      std::vector<double> ages = m.ages_s;
      const auto quantile = [&](double q) {
        const auto at = ages.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(ages.size() - 1));
        std::nth_element(ages.begin(), at, ages.end());
        return *at;
      };
      m.state.age_p50_s = quantile(0.5);
      m.state.age_p99_s = quantile(0.99);
      m.state.age_max_s = *std::max_element(ages.begin(), ages.end());
    }
    states.push_back(m.state);
  }
  return states;
}

void TeamPresence::left(const std::string& role) {
  const std::lock_guard lock(mutex_);
  for (Member& m : members_)
    if (m.known.role == role) m.state.left = true;
}

std::vector<TeamMember> TeamPresence::known() const {
  const std::lock_guard lock(mutex_);
  std::vector<TeamMember> result;
  for (const Member& m : members_)
    result.push_back(m.known);
  return result;
}

bool TeamPresence::there(const std::string& role, int body) const {
  const std::lock_guard lock(mutex_);
  for (const Member& m : members_)
    if (m.known.role == role)
      return !m.state.left && body >= 0 && body < static_cast<int>(m.present.size()) &&
             m.present[static_cast<std::size_t>(body)];
  return false;
}

std::vector<std::string> NearMissWatch::update(const std::vector<TeamPresence::Closest>& closest) {
  std::vector<std::string> said;
  for (const TeamPresence::Closest& c : closest) {
    auto tally =
        std::find_if(tallies_.begin(), tallies_.end(), [&](const Tally& t) { return t.role == c.role; });
    if (tally == tallies_.end()) {
      tallies_.push_back({c.role});
      episodes_.push_back({});
      tally = tallies_.end() - 1;
    }
    Episode& episode = episodes_[static_cast<std::size_t>(tally - tallies_.begin())];
    tally->closest_m = std::min(tally->closest_m, c.clearance_m);
    char line[160];
    if (!episode.near && c.clearance_m < kNearMiss_m) {
      episode.near = true;
      ++tally->near_misses;
      std::snprintf(line, sizeof line, "near miss: %s %.2f m from %s: %s", c.own_body.c_str(),
                    std::max(c.clearance_m, 0.0), c.role.c_str(), c.member_body.c_str());
      said.emplace_back(line);
    }
    if (episode.near && !episode.touched && c.clearance_m <= 0.0) {
      episode.touched = true;
      ++tally->contacts;
      said.push_back("contact: " + c.own_body + " with " + c.role + ": " + c.member_body);
    }
    if (episode.near && c.clearance_m > kClear_m) episode = {};
  }
  return said;
}

}  // namespace harbour::station
