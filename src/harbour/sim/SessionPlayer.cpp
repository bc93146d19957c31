#include "harbour/sim/SessionPlayer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace harbour::sim {

SessionPlayer::SessionPlayer(std::vector<Member> members) : members_(std::move(members)) {
  if (members_.empty()) throw std::runtime_error("a session replay needs a member");
  double earliest_s = members_.front().start_s;
  for (const Member& m : members_)
    earliest_s = std::min(earliest_s, m.start_s);
  for (Member& m : members_)
    m.start_s -= earliest_s;
  for (const Member& m : members_) {
    try {
      players_.push_back(std::make_unique<ReplayPlayer>(m.scenario, m.recording));
    } catch (const std::exception& e) {
      throw std::runtime_error((m.role.empty() ? std::string() : m.role + ": ") + e.what());
    }
    const scene::SceneDescription member = players_.back()->simulation().scene();
    first_entity_.push_back(static_cast<int>(scene_.entities.size()));
    const auto load =
        std::find_if(member.entities.begin(), member.entities.end(),
                     [](const scene::SceneDescription::Entity& e) { return e.name == scene::kTrailerLoad; });
    load_entity_.push_back(load == member.entities.end()
                               ? -1
                               : first_entity_.back() + static_cast<int>(load - member.entities.begin()));
    if (players_.size() == 1) {
      scene_ = member;  // the first: its machine, indicators and drives
    } else {
      scene_.entities.insert(scene_.entities.end(), member.entities.begin(), member.entities.end());
      scene_.rope_count += member.rope_count;
    }
    duration_s_ =
        std::max(duration_s_, m.start_s + static_cast<double>(m.recording.total_steps) * Simulation::kStep_s);
  }
  scene_.rope_count = std::min(scene_.rope_count, scene::kMaxRopes);
}

SessionPlayer::~SessionPlayer() = default;

std::int64_t SessionPlayer::member_step(std::size_t k, double t_s) const {
  const double local_s = std::max(0.0, t_s - members_[k].start_s);
  return std::min(static_cast<std::int64_t>(std::llround(local_s / Simulation::kStep_s)),
                  players_[k]->total_steps());
}

void SessionPlayer::seek(double t_s) {
  time_s_ = std::clamp(t_s, 0.0, duration_s_);
  for (std::size_t k = 0; k < players_.size(); ++k)
    players_[k]->seek(member_step(k, time_s_));
  name_loads();
}

void SessionPlayer::advance_to(double t_s) {
  time_s_ = std::clamp(t_s, time_s_, duration_s_);
  for (std::size_t k = 0; k < players_.size(); ++k)
    if (member_step(k, time_s_) > players_[k]->simulation().steps())
      players_[k]->advance_to(member_step(k, time_s_));
  name_loads();
}

void SessionPlayer::name_loads() {
  for (std::size_t k = 0; k < players_.size(); ++k) {
    if (load_entity_[k] < 0) continue;
    const std::string handed = handed_load_name(members_[k].recording, players_[k]->simulation().steps());
    std::string& name = scene_.entities[static_cast<std::size_t>(load_entity_[k])].name;
    const std::string now = handed.empty() ? std::string(scene::kTrailerLoad) : handed;
    if (name == now) continue;
    name = now;
    ++names_version_;
  }
}

void SessionPlayer::write_snapshot(scene::Snapshot& out) const {
  players_.front()->simulation().write_snapshot(out);
  out.time_s = time_s_;
  for (std::size_t k = 1; k < players_.size(); ++k) {
    scene::Snapshot& m = *member_snapshot_;
    players_[k]->simulation().write_snapshot(m);
    for (int n = 0; n < m.entity_count && out.entity_count < scene::kMaxEntities; ++n) {
      scene::Snapshot::Entity e = m.entities[static_cast<std::size_t>(n)];
      e.index += static_cast<std::uint32_t>(first_entity_[k]);
      out.entities[static_cast<std::size_t>(out.entity_count++)] = e;
    }
    int point = out.rope_count > 0 ? out.rope_first[static_cast<std::size_t>(out.rope_count - 1)] +
                                         out.rope_points[static_cast<std::size_t>(out.rope_count - 1)]
                                   : 0;
    for (int r = 0; r < m.rope_count && out.rope_count < scene::kMaxRopes; ++r) {
      const int count = m.rope_points[static_cast<std::size_t>(r)];
      if (point + count > scene::kMaxRopePoints) break;
      const int from = m.rope_first[static_cast<std::size_t>(r)];
      std::copy_n(m.points.begin() + from, count, out.points.begin() + point);
      out.rope_first[static_cast<std::size_t>(out.rope_count)] = static_cast<std::uint16_t>(point);
      out.rope_points[static_cast<std::size_t>(out.rope_count)] = static_cast<std::uint16_t>(count);
      ++out.rope_count;
      point += count;
    }
  }
}

std::optional<double> truck_start_s(const Recording& crane, int slot, const Recording& truck) {
  const auto taken = std::find_if(crane.team.begin(), crane.team.end(), [&](const Recording::TeamEvent& e) {
    return e.input.kind == TeamInput::Kind::kTakenOver && e.input.slot == slot;
  });
  const auto loaded = std::find_if(truck.team.begin(), truck.team.end(), [](const Recording::TeamEvent& e) {
    return e.input.kind == TeamInput::Kind::kLoadOn;
  });
  if (taken == crane.team.end() || loaded == truck.team.end()) return std::nullopt;
  return static_cast<double>(taken->step - loaded->step) * Simulation::kStep_s;
}

std::optional<std::pair<std::string, std::int64_t>> SessionPlayer::first_mismatch() const {
  for (std::size_t k = 0; k < players_.size(); ++k)
    if (const std::optional<std::int64_t> step = players_[k]->first_mismatch())
      return std::pair{members_[k].role, *step};
  return std::nullopt;
}

}  // namespace harbour::sim
