#include "harbour/bulk/BulkWorld.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "harbour/core/Assert.h"

namespace harbour::bulk {
namespace {

// a jaw tip this close above the surface counts as touching it
constexpr double kGrabTouchTolerance_m = 0.02;

bool pressed_before(const auto& a, const auto& b) {
  return std::tie(a.grid, a.j, a.i) < std::tie(b.grid, b.j, b.i);
}

}  // namespace

BulkWorld::BulkWorld(const Material& material, const BulkWorldSettings& settings)
    : material_(material), settings_(settings) {
  parcels_.reserve(kParcelsReserved);
}

int BulkWorld::add_grid(const GridSettings& grid, const core::Pose& pose) {
  grids_.emplace_back(grid, material_, settings_.relaxation);
  grids_.back().set_pose(pose);
  outflow_m3_per_s_.push_back(0.0);
  landed_m3_.push_back(0.0);
  // a footprint covers at most a whole grid, the pressed cells at most every grid's: no growth while stepping
  const std::size_t cells = static_cast<std::size_t>(grid.cells_x) * static_cast<std::size_t>(grid.cells_y);
  footprint_.reserve(std::max(footprint_.capacity(), cells));
  pressed_.reserve(pressed_.capacity() + cells);
  pressing_.reserve(pressing_.capacity() + cells);
  return static_cast<int>(grids_.size()) - 1;
}

void BulkWorld::fill_level(int grid_id, double depth_m) {
  HeightGrid& g = grid(grid_id);
  const double per_cell = depth_m * g.cell_area_m2();
  for (int j = 0; j < g.cells_y(); ++j)
    for (int i = 0; i < g.cells_x(); ++i)
      g.add_volume(i, j, per_cell);
  added_m3_ += per_cell * g.cells_x() * g.cells_y();
}

void BulkWorld::set_outflow(int id, double m3_per_s) {
  HARBOUR_ASSERT(m3_per_s >= 0.0, "a hopper's outflow is not negative");
  outflow_m3_per_s_[static_cast<std::size_t>(id)] = m3_per_s;
}

void BulkWorld::drain_hoppers(double dt_s) {
  // a hopper's outlet takes up to its rate from the material in it, the same share of every cell (the
  // material above sinks evenly towards the outlet)
  for (std::size_t n = 0; n < grids_.size(); ++n) {
    if (outflow_m3_per_s_[n] <= 0.0) continue;
    HeightGrid& g = grids_[n];
    const double held = g.total_volume_m3();
    if (held <= 0.0) continue;
    delivered_m3_ += g.sink_evenly(std::min(1.0, outflow_m3_per_s_[n] * dt_s / held));
  }
}

int BulkWorld::add_grab(const GrabSettings& grab) {
  grab_settings_.push_back(grab);
  GrabState state;
  state.opening_m = grab.max_opening_m;
  grabs_.push_back(state);
  return static_cast<int>(grabs_.size()) - 1;
}

bool BulkWorld::pour(int grid_id, double x, double y, double volume_m3) {
  HeightGrid& g = grid(grid_id);
  const auto cell = g.cell_at(x, y);
  if (!cell || !(volume_m3 >= 0.0)) return false;
  g.add_volume(cell->i, cell->j, volume_m3);
  added_m3_ += volume_m3;
  return true;
}

double BulkWorld::add_heap(int grid_id, double x, double y, double volume_m3) {
  // cone volume V = pi r^2 h / 3 with h = r tan(repose)
  HeightGrid& g = grid(grid_id);
  const double tan_repose = std::tan(material_.angle_of_repose_rad);
  const double radius = std::cbrt(3.0 * volume_m3 / (std::numbers::pi * tan_repose));
  double added = 0.0;
  for (int j = 0; j < g.cells_y(); ++j)
    for (int i = 0; i < g.cells_x(); ++i) {
      const core::Vec3 c = g.cell_centre(i, j);
      const double r = std::hypot(c.x - x, c.y - y);
      if (r >= radius) continue;
      const double volume = (radius - r) * tan_repose * g.cell_area_m2();
      g.add_volume(i, j, volume);
      added += volume;
    }
  added_m3_ += added;
  return added;
}

ContactResult BulkWorld::contact(const ContactBody& body) {
  ContactResult result;
  core::Vec3 weighted_point;
  double total_force = 0.0;
  for (int gid = 0; gid < grid_count(); ++gid) {
    HeightGrid& g = grid(gid);
    const core::Vec3 normal = g.pose().rotation.column(2);
    for (const core::Vec3& body_point : body.points) {
      // penetration of the point below the material surface, along the grid's up axis
      const core::Vec3 p = body.pose.to_parent(body_point);
      if (!std::isfinite(p.x + p.y + p.z)) {  // a broken body state: count it, touch nothing
        warnings_.raise(core::Warning::kNonFinite);
        continue;
      }
      const core::Vec3 local = g.pose().to_local(p);
      if (!g.contains(local.x, local.y)) continue;
      const double penetration = g.surface_height(local.x, local.y) - local.z;
      if (penetration <= 0.0) continue;

      // highly damped linear spring on depth and its rate, relative to a moving grid; never pulls
      const core::Vec3 v_body =
          body.linear_velocity + core::cross(body.angular_velocity, p - body.pose.position);
      const core::Vec3 v_grid =
          g.linear_velocity() + core::cross(g.angular_velocity(), p - g.pose().position);
      const double penetration_rate = -core::dot(v_body - v_grid, normal);
      const double force = settings_.contact.stiffness_n_per_m * penetration +
                           settings_.contact.damping_n_s_per_m * penetration_rate;
      if (!std::isfinite(force)) {
        warnings_.raise(core::Warning::kNonFinite);
        continue;
      }
      ++result.points_in_contact;
      result.max_penetration_m = std::max(result.max_penetration_m, penetration);
      if (force > 0.0) {
        result.force += normal * force;
        weighted_point += p * force;
        total_force += force;
      }

      // compression: the pressed cell looks higher to the slope rule, so material escapes sideways
      const auto cell = g.cell_at(local.x, local.y);
      pressing_.push_back({gid, cell->i, cell->j, material_.compression_gain * penetration});
    }
  }
  result.point = total_force > 0.0 ? weighted_point * (1.0 / total_force) : body.pose.position;
  return result;
}

void BulkWorld::update_compression() {
  // this step's pressed cells (deepest press per cell) replace last step's; unpressed cells relax to zero
  std::sort(pressing_.begin(), pressing_.end(), [](const PressedCell& a, const PressedCell& b) {
    return pressed_before(a, b) || (!pressed_before(b, a) && a.height_m > b.height_m);
  });
  pressing_.erase(std::unique(pressing_.begin(), pressing_.end(),
                              [](const PressedCell& a, const PressedCell& b) {
                                return !pressed_before(a, b) && !pressed_before(b, a);
                              }),
                  pressing_.end());
  for (const PressedCell& old : pressed_)
    if (!std::binary_search(pressing_.begin(), pressing_.end(), old,
                            pressed_before<PressedCell, PressedCell>))
      grid(old.grid).set_compression(old.i, old.j, 0.0);
  for (const PressedCell& now : pressing_)
    grid(now.grid).set_compression(now.i, now.j, now.height_m);
  pressed_.swap(pressing_);
  pressing_.clear();
}

void BulkWorld::step(double dt_s, std::span<const GrabCommand> grab_commands) {
  HARBOUR_ASSERT(grab_commands.size() == grabs_.size(), "one command per grab");
  update_compression();
  for (std::size_t n = 0; n < grabs_.size(); ++n)
    step_grab(grab_settings_[n], grabs_[n], grab_commands[n], dt_s);
  step_parcels(dt_s);
  drain_hoppers(dt_s);
  for (HeightGrid& g : grids_) {
    const std::uint32_t rejected = g.non_finite_count();
    if (full_sweep_)
      g.relax_full_sweep(dt_s);
    else
      g.relax_active(dt_s);
    if (g.non_finite_count() != rejected) warnings_.raise(core::Warning::kNonFinite);
  }
}

void BulkWorld::step_grab(const GrabSettings& settings, GrabState& state, const GrabCommand& command,
                          double dt_s) {
  state.pose = command.pose;
  state.velocity = command.velocity;
  const double rate = std::clamp(command.close_rate, -1.0, 1.0);
  const bool closing = rate > 0.0 && state.opening_m > 0.0;
  state.digging = closing && dig(settings, state, rate * dt_s);  // the jaws cut as fast as they close
  state.opening_m =
      std::clamp(state.opening_m - rate * settings.max_opening_m / settings.closing_time_s * dt_s, 0.0,
                 settings.max_opening_m);
  // opening, the tips swing back up their arc: the cut they can deepen starts from there
  if (rate < 0.0)
    state.cut_depth_m =
        std::min(state.cut_depth_m, settings.max_depth_m * (1.0 - state.opening_m / settings.max_opening_m));

  // a grab opened wider than it held its load spills through the gap (w - w_held) x W at v0, as a falling
  // parcel: material cut and held at an opening stays wedged there
  if (state.load_m3 <= 0.0) state.held_opening_m = state.opening_m;
  state.held_opening_m = std::min(state.held_opening_m, state.opening_m);
  const double gap = state.opening_m - state.held_opening_m;
  if (rate <= 0.0 && gap > 0.0 && state.load_m3 > 0.0) {
    const double out = std::min(state.load_m3, gap * settings.width_m * settings.spill_speed_mps * dt_s);
    state.load_m3 -= out;
    unloaded_m3_ += out;
    parcels_.push_back(
        {state.pose.position, state.velocity, out, std::sqrt(state.opening_m * settings.width_m)});
  }
}

double BulkWorld::dig(const GrabSettings& settings, GrabState& state, double dt_s) {
  // the grid under the jaw tips, if they touch its surface
  for (int gid = 0; gid < grid_count(); ++gid) {
    HeightGrid& g = grid(gid);
    // the jaw tips swing down on their arc as the shells close: d below the jaws' reference when shut
    const double closed_share = 1.0 - state.opening_m / settings.max_opening_m;
    const core::Vec3 tip =
        g.pose().to_local(state.pose.to_parent({0.0, 0.0, -settings.max_depth_m * closed_share}));
    if (!g.contains(tip.x, tip.y) || tip.z > g.surface_height(tip.x, tip.y) + kGrabTouchTolerance_m) continue;
    if (state.cut_depth_m >= settings.max_depth_m || state.load_m3 >= settings.capacity_m3) return false;

    // cells whose centres lie inside the jaw footprint w x W (grab frame x across, y along the hinge)
    std::vector<CellIndex>& cells = footprint_;
    cells.clear();
    const double half_w = 0.5 * state.opening_m, half_W = 0.5 * settings.width_m;
    const double reach = std::sqrt(half_w * half_w + half_W * half_W);
    const int i0 = std::max(0, static_cast<int>((tip.x - reach) / g.cell_size_m()));
    const int i1 = std::min(g.cells_x() - 1, static_cast<int>((tip.x + reach) / g.cell_size_m()));
    const int j0 = std::max(0, static_cast<int>((tip.y - reach) / g.cell_size_m()));
    const int j1 = std::min(g.cells_y() - 1, static_cast<int>((tip.y + reach) / g.cell_size_m()));
    // cell centres map affinely into the grab frame: step along i and j instead of transforming each
    const core::Vec3 origin = state.pose.to_local(g.pose().to_parent(g.cell_centre(i0, j0)));
    const core::Vec3 step_i =
        state.pose.direction_to_local(g.pose().direction_to_parent({g.cell_size_m(), 0, 0}));
    const core::Vec3 step_j =
        state.pose.direction_to_local(g.pose().direction_to_parent({0, g.cell_size_m(), 0}));
    for (int j = j0; j <= j1; ++j) {
      const core::Vec3 row = origin + step_j * static_cast<double>(j - j0);
      for (int i = i0; i <= i1; ++i) {
        const core::Vec3 in_grab = row + step_i * static_cast<double>(i - i0);
        if (std::abs(in_grab.x) <= half_w && std::abs(in_grab.y) <= half_W) cells.push_back({i, j});
      }
    }
    if (cells.empty()) return false;

    // one layer v*dt off every cell (dt scaled by the closing rate), never more than the cell holds nor than
    // the grab has room for
    const double layer = settings.sinking_speed_mps * dt_s;
    const double room = settings.capacity_m3 - state.load_m3;
    const double scale = std::min(1.0, room / (static_cast<double>(cells.size()) * layer * g.cell_area_m2()));
    double taken = 0.0;
    for (const CellIndex& c : cells)
      taken += g.remove_layer(c.i, c.j, layer * scale);
    state.load_m3 += taken;
    loaded_m3_ += taken;
    state.cut_depth_m += layer;
    return true;
  }
  return false;
}

void BulkWorld::step_parcels(double dt_s) {
  // semi-implicit Euler under gravity; a parcel lands on the first grid whose surface it reaches
  std::size_t kept = 0;
  for (Parcel& parcel : parcels_) {
    parcel.velocity.z -= settings_.gravity_mps2 * dt_s;
    parcel.position += parcel.velocity * dt_s;
    if (land(parcel)) continue;
    if (parcel.position.z < settings_.spill_level_m) {
      spilled_m3_ += parcel.volume_m3;
      continue;
    }
    parcels_[kept++] = parcel;
  }
  parcels_.resize(kept);
}

bool BulkWorld::land(const Parcel& parcel) {
  for (std::size_t n = 0; n < grids_.size(); ++n) {
    HeightGrid& g = grids_[n];
    const core::Vec3 local = g.pose().to_local(parcel.position);
    if (!g.contains(local.x, local.y) || local.z > g.surface_height(local.x, local.y)) continue;

    // spread evenly over the cells whose centres lie in the parcel's square footprint
    std::vector<CellIndex>& cells = footprint_;
    cells.clear();
    const double half = 0.5 * parcel.footprint_m, size = g.cell_size_m();
    const int i0 = std::max(0, static_cast<int>(std::ceil((local.x - half) / size - 0.5)));
    const int i1 = std::min(g.cells_x() - 1, static_cast<int>(std::floor((local.x + half) / size - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((local.y - half) / size - 0.5)));
    const int j1 = std::min(g.cells_y() - 1, static_cast<int>(std::floor((local.y + half) / size - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        cells.push_back({i, j});
    if (cells.empty()) cells.push_back(*g.cell_at(local.x, local.y));
    const double share = parcel.volume_m3 / static_cast<double>(cells.size());
    for (const CellIndex& c : cells)
      g.add_volume(c.i, c.j, share);
    landed_m3_[n] += parcel.volume_m3;
    return true;
  }
  return false;
}

VolumeBalance BulkWorld::balance() const {
  VolumeBalance b;
  for (const HeightGrid& g : grids_)
    b.in_grids_m3 += g.total_volume_m3();
  for (const GrabState& s : grabs_)
    b.in_grabs_m3 += s.load_m3;
  for (const Parcel& p : parcels_)
    b.in_flight_m3 += p.volume_m3;
  b.spilled_m3 = spilled_m3_;
  b.delivered_m3 = delivered_m3_;
  b.added_m3 = added_m3_;
  return b;
}

std::uint64_t BulkWorld::state_hash() const {
  core::StateHash hash;
  for (const HeightGrid& g : grids_)
    g.hash_into(hash);
  for (const GrabState& s : grabs_) {
    hash.add(s.pose);
    hash.add(s.opening_m);
    hash.add(s.load_m3);
    hash.add(s.cut_depth_m);
  }
  for (const Parcel& p : parcels_)
    hash.add(p);
  hash.add(spilled_m3_);
  hash.add(delivered_m3_);
  hash.add(added_m3_);
  for (double landed : landed_m3_)
    hash.add(landed);
  return hash.value();
}

template <typename Self, typename Archive>
void BulkWorld::archive(Self& self, Archive& ar) {
  ar.section(0x424C4B31, "bulk");  // "BLK1"
  std::size_t grids = self.grids_.size();
  ar(grids);
  if constexpr (Archive::kRestoring)
    if (grids != self.grids_.size()) throw core::StateError("saved state has other bulk grids");
  for (auto& g : self.grids_)
    ar.part(g);
  ar.sized(self.grabs_);
  ar(self.parcels_, self.pressed_, self.pressing_);
  if constexpr (Archive::kRestoring)
    for (const auto* cells : {&self.pressed_, &self.pressing_})
      for (const PressedCell& c : *cells)
        if (c.grid < 0 || c.grid >= self.grid_count() || c.i < 0 || c.j < 0 ||
            c.i >= self.grids_[static_cast<std::size_t>(c.grid)].cells_x() ||
            c.j >= self.grids_[static_cast<std::size_t>(c.grid)].cells_y())
          throw core::StateError("saved bulk state presses a cell off its grids");
  ar(self.added_m3_, self.spilled_m3_, self.delivered_m3_, self.loaded_m3_, self.unloaded_m3_);
  ar.sized(self.landed_m3_);
  ar(self.full_sweep_, self.warnings_);
}

void BulkWorld::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void BulkWorld::restore_state(core::StateReader& in) {
  archive(*this, in);
}

}  // namespace harbour::bulk
