#include "harbour/bulk/HeightGrid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "harbour/core/Assert.h"

namespace harbour::bulk {
namespace {

// The 16-neighbour stencil: 4 axis, 4 diagonal and 8 knight moves, stored in opposite pairs
// (k and k ^ 1 point in opposite directions) so inflow uses the opposite direction's offset.
constexpr int kStencilDx[16] = {1, -1, 0, 0, 1, -1, 1, -1, 2, -2, 1, -1, -1, 1, -2, 2};
constexpr int kStencilDy[16] = {0, 0, 1, -1, 1, -1, -1, 1, 1, -1, 2, -2, 2, -2, 1, -1};

constexpr std::uint32_t kNeverExamine = std::numeric_limits<std::uint32_t>::max();

}  // namespace

HeightGrid::HeightGrid(const GridSettings& settings, const Material& material,
                       const RelaxationSettings& relaxation)
    : nx_(settings.cells_x),
      ny_(settings.cells_y),
      cell_m_(settings.cell_size_m),
      tan_repose_(std::tan(material.angle_of_repose_rad)),
      tan_flow_(std::tan(material.flow_friction_rad)),
      relaxation_(relaxation),
      stride_(static_cast<std::size_t>(settings.cells_x + 2 * kPad)) {
  HARBOUR_ASSERT(nx_ > 0 && ny_ > 0 && cell_m_ > 0.0, "grid settings must be validated by the loader");
  HARBOUR_ASSERT(
      material.flow_friction_rad > 0.0 && material.flow_friction_rad <= material.angle_of_repose_rad,
      "flow friction outside (0, repose]");
  const std::size_t padded = stride_ * static_cast<std::size_t>(ny_ + 2 * kPad);
  h_.assign(padded, 0.0);
  vel_.assign(padded * kPipes, 0.0f);
  flux_.assign(padded * kPipes, 0.0f);
  out_scale_.assign(padded, 1.0);
  comp_.assign(padded, kWall);
  active_stamp_.assign(padded, 0);
  examine_bits_.assign((padded + 63) / 64, 0);
  // the examined list and its scratch hold each cell at most once: no growth while stepping
  const std::size_t cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  examine_.reserve(cells);
  active_.reserve(cells);
  new_vel_.reserve(cells * kPipes);
  deltas_.reserve(cells);
  residual_.reserve(cells);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      comp_[index(i, j)] = 0.0;
    }
  for (int k = 0; k < kStencil; ++k)
    neighbour_offset_[k] =
        static_cast<std::ptrdiff_t>(kStencilDy[k]) * static_cast<std::ptrdiff_t>(stride_) + kStencilDx[k];
  tile_version_.assign(static_cast<std::size_t>(tiles_x() * tiles_y()), 0);
  update_slope_offsets();
}

void HeightGrid::update_slope_offsets() {
  level_ = slope_up_.x == 0.0 && slope_up_.y == 0.0;
  for (int k = 0; k < kStencil; ++k) {
    const double dx = kStencilDx[k] * cell_m_, dy = kStencilDy[k] * cell_m_;
    squared_distance_[k] = dx * dx + dy * dy;
    rise_[k] = slope_up_.x * dx + slope_up_.y * dy;  // world elevation gained by the grid's tilt
    distance_[k] = std::sqrt(squared_distance_[k]);
    level_offset_[k] = -distance_[k] * tan_repose_;
  }
  // pipe k carries a share 1 / (4 n) of the flow, n its length in cells: the axis, diagonal and knight pipes
  // each pass a quarter, a quarter and a half of a uniform flow in any direction (isotropic)
  for (int pipe = 0; pipe < kPipes; ++pipe)
    pipe_share_[pipe] = 1.0 / (4.0 * distance_[2 * pipe]);
}

void HeightGrid::set_pose(const core::Pose& pose, const core::Vec3& linear_velocity,
                          const core::Vec3& angular_velocity) {
  pose_ = pose;
  linear_velocity_ = linear_velocity;
  angular_velocity_ = angular_velocity;
  const core::Vec3 up = pose.rotation.row(2);
  if (core::length(up - slope_up_) > relaxation_.tilt_quantum_rad) {
    slope_up_ = up;
    update_slope_offsets();
    activate_loaded_cells();
  }
}

void HeightGrid::mark(std::size_t cell) {
  const int i = static_cast<int>(cell % stride_) - kPad, j = static_cast<int>(cell / stride_) - kPad;
  ++tile_version_[static_cast<std::size_t>((j / kTileCells) * tiles_x() + i / kTileCells)];
  activate(cell);
}

void HeightGrid::activate(std::size_t cell) {
  if (active_stamp_[cell] == epoch_) return;
  active_stamp_[cell] = epoch_;
  active_.push_back(cell);
}

void HeightGrid::add_volume(int i, int j, double volume_m3) {
  HARBOUR_ASSERT(volume_m3 >= 0.0, "added volume must not be negative");
  const std::size_t c = index(i, j);
  h_[c] += volume_m3 / cell_area_m2();
  mark(c);
}

double HeightGrid::remove_layer(int i, int j, double thickness_m) {
  const std::size_t c = index(i, j);
  const double removed = std::clamp(thickness_m, 0.0, h_[c]);
  if (removed <= 0.0) return 0.0;
  h_[c] -= removed;
  mark(c);
  return removed * cell_area_m2();
}

double HeightGrid::sink_evenly(double share) {
  double removed = 0.0;
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const std::size_t c = index(i, j);
      if (h_[c] <= 0.0) continue;
      const double layer = h_[c] * share;
      h_[c] -= layer;
      removed += layer;
      ++tile_version_[static_cast<std::size_t>((j / kTileCells) * tiles_x() + i / kTileCells)];
      if (comp_[c] != 0.0) activate(c);
    }
  return removed * cell_area_m2();
}

void HeightGrid::set_compression(int i, int j, double height_m) {
  const std::size_t c = index(i, j);
  if (comp_[c] == height_m) return;
  comp_[c] = height_m;
  mark(c);
}

bool HeightGrid::contains(double x, double y) const {
  return x >= 0.0 && y >= 0.0 && x < nx_ * cell_m_ && y < ny_ * cell_m_;
}

std::optional<CellIndex> HeightGrid::cell_at(double x, double y) const {
  if (!contains(x, y)) return std::nullopt;
  return CellIndex{std::min(static_cast<int>(x / cell_m_), nx_ - 1),
                   std::min(static_cast<int>(y / cell_m_), ny_ - 1)};
}

core::Vec3 HeightGrid::cell_centre(int i, int j) const {
  return {(i + 0.5) * cell_m_, (j + 0.5) * cell_m_, 0.0};
}

double HeightGrid::surface_height(double x, double y) const {
  // bilinear between cell centres, clamped to the outermost centres
  const double u = std::clamp(x / cell_m_ - 0.5, 0.0, nx_ - 1.0);
  const double v = std::clamp(y / cell_m_ - 0.5, 0.0, ny_ - 1.0);
  const int i0 = std::min(static_cast<int>(u), nx_ - 1), j0 = std::min(static_cast<int>(v), ny_ - 1);
  const int i1 = std::min(i0 + 1, nx_ - 1), j1 = std::min(j0 + 1, ny_ - 1);
  const double fu = u - i0, fv = v - j0;
  const double bottom = height(i0, j0) * (1 - fu) + height(i1, j0) * fu;
  const double top = height(i0, j1) * (1 - fu) + height(i1, j1) * fu;
  return bottom * (1 - fv) + top * fv;
}

double HeightGrid::total_volume_m3() const {
  double sum = 0.0;
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      sum += height(i, j);
  return sum * cell_area_m2();
}

double HeightGrid::max_height_m() const {
  return *std::max_element(h_.begin(), h_.end());
}

template <bool kLevel, bool kStill>
void HeightGrid::update_pipes(std::size_t cell, double dt, float* velocities) const {
  // each pipe from this cell to a stencil neighbour: du/dt = g (slope - mu_flow sign u) minus the advection
  // of u along the pipe's line (Burgers, Engquist-Osher flux between pipes end to end), from rest only where
  // the slope beats the repose angle; Coulomb friction stops it rather than turning it round
  const double g = relaxation_.gravity_mps2;
  const double sp = h_[cell] + comp_[cell];
  const float* u_here = &vel_[cell * kPipes];
  for (int pipe = 0; pipe < kPipes; ++pipe) {
    const int k = 2 * pipe;
    const std::size_t q = cell + neighbour_offset_[k], behind = cell - neighbour_offset_[k];
    if (is_wall(q)) {
      velocities[pipe] = 0.0;
      continue;
    }
    const double ds = sp - (h_[q] + comp_[q]);
    double drop, run;  // world elevation lost towards the neighbour, horizontal distance to it
    if constexpr (kLevel) {
      drop = ds;
      run = distance_[k];
    } else {
      drop = slope_up_.z * ds - rise_[k];
      run = std::sqrt(std::max(squared_distance_[k] + ds * ds - drop * drop, 1e-12 * squared_distance_[k]));
    }
    // kStill: no pipe of the grid moves (a dig, a slow pour): nothing to read
    const double u = kStill ? 0.0 : u_here[pipe];
    const double u_behind = kStill || is_wall(behind) ? 0.0 : vel_[behind * kPipes + pipe];
    const double u_ahead = kStill ? 0.0 : vel_[q * kPipes + pipe];
    if (u == 0.0 && u_behind <= 0.0 && u_ahead >= 0.0 &&
        std::abs(drop) - run * tan_repose_ <= relaxation_.flow_start_excess_m) {
      velocities[pipe] = 0.0;  // at rest, no momentum arriving, not steep enough to start
      continue;
    }
    const auto flux = [](double left, double right) {
      return 0.5 * (std::max(left, 0.0) * std::max(left, 0.0) + std::min(right, 0.0) * std::min(right, 0.0));
    };
    const double length = distance_[k];
    double v = u - dt * (flux(u, u_ahead) - flux(u_behind, u)) / length + dt * g * drop / run;
    const double friction = dt * g * tan_flow_;
    v = std::abs(v) <= friction ? 0.0 : v - std::copysign(friction, v);
    velocities[pipe] = static_cast<float>(v);
  }
}

double HeightGrid::pipe_flux(std::size_t cell, int pipe, double dt) const {
  // height moved from `cell` to its neighbour (negative: back), from the upstream cell's height
  const double u = vel_[cell * kPipes + pipe];
  if (u == 0.0) return 0.0;
  const std::size_t from = u > 0.0 ? cell : cell + neighbour_offset_[2 * pipe];
  return u * dt * pipe_share_[pipe] * h_[from] * out_scale_[from];
}

template <bool kLevel, bool kStill>
double HeightGrid::residual_inflow(std::size_t cell, bool& may_start) const {
  // the paper's rule on the pairs whose pipe is at rest: flow p->q = c/16 min(excess, h_p), excess the
  // world elevation drop beyond the repose angle's over the pair's horizontal distance
  const double fraction = relaxation_.residual_fraction / kStencil;
  const double hp = h_[cell];
  const double sp = hp + comp_[cell];
  double delta = 0.0;
  for (int k = 0; k < kStencil; ++k) {
    const std::size_t q = cell + neighbour_offset_[k];
    if constexpr (!kStill) {
      const double pipe_velocity =
          k % 2 == 0 ? vel_[cell * kPipes + k / 2] : vel_[q * kPipes + (k ^ 1) / 2];  // the pair's pipe
      if (pipe_velocity != 0.0) continue;
    }
    const double hq = h_[q];
    const double ds = sp - (hq + comp_[q]);
    double drop, critical_drop;
    if constexpr (kLevel) {
      drop = ds;
      critical_drop = -level_offset_[k];
    } else {
      drop = slope_up_.z * ds - rise_[k];
      critical_drop = std::sqrt(std::max(0.0, squared_distance_[k] + ds * ds - drop * drop)) * tan_repose_;
    }
    const double out_excess = drop - critical_drop, in_excess = -drop - critical_drop;
    // a pipe this cell owns may start (update_pipes decides; the margin covers its horizontal run's rounding)
    if constexpr (kStill)
      if (k % 2 == 0 && std::max(out_excess, in_excess) > relaxation_.flow_start_excess_m - 1e-6)
        may_start = true;
    if (out_excess > relaxation_.min_excess_m)
      delta -= fraction * std::min(out_excess, hp);
    else if (in_excess > relaxation_.min_excess_m)
      delta += fraction * std::min(in_excess, hq);
  }
  return delta;
}

void HeightGrid::flow(const std::vector<std::size_t>& cells, double dt) {
  // the residual relaxation on the pairs at rest, all from the old state (synchronous: order-independent)
  bool may_start = false;
  const auto relax_residual = [&](bool pipes_still) {
    residual_.resize(cells.size());
    for (std::size_t n = 0; n < cells.size(); ++n)
      residual_[n] = pipes_still ? (level_ ? residual_inflow<true, true>(cells[n], may_start)
                                           : residual_inflow<false, true>(cells[n], may_start))
                                 : (level_ ? residual_inflow<true, false>(cells[n], may_start)
                                           : residual_inflow<false, false>(cells[n], may_start));
  };
  bool still = moving_pipes_ == 0;  // no pipe moved last sub-step
  deltas_.assign(cells.size(), 0.0);
  if (still) {  // the fast path: the residual rule alone, unless some pair is steep enough for a pipe to
                // start
    relax_residual(true);
    if (!may_start) {
      finish_sub_step(cells, true);
      return;
    }
  }
  // 1. the pipes' new velocities, all from the old state
  new_vel_.resize(cells.size() * kPipes);
  for (std::size_t n = 0; n < cells.size(); ++n) {
    float* v = &new_vel_[n * kPipes];
    if (still)
      level_ ? update_pipes<true, true>(cells[n], dt, v) : update_pipes<false, true>(cells[n], dt, v);
    else
      level_ ? update_pipes<true, false>(cells[n], dt, v) : update_pipes<false, false>(cells[n], dt, v);
  }
  if (still)  // and none starts now: the pipes' passes have nothing to do
    still = std::all_of(new_vel_.begin(), new_vel_.end(), [](double v) { return v == 0.0; });
  if (!still) {
    for (std::size_t n = 0; n < cells.size(); ++n)
      std::copy_n(&new_vel_[n * kPipes], kPipes, &vel_[cells[n] * kPipes]);
    // 2. no cell gives more than it holds: its outflows scaled down together where they would, leaving room
    // for the residual relaxation's share
    for (const std::size_t c : cells) {
      double out = 0.0;  // share of the height leaving per sub-step
      for (int pipe = 0; pipe < kPipes; ++pipe) {
        const double mine = vel_[c * kPipes + pipe];
        const double theirs = vel_[(c - neighbour_offset_[2 * pipe]) * kPipes + pipe];
        out += (std::max(mine, 0.0) - std::min(theirs, 0.0)) * pipe_share_[pipe];
      }
      out *= dt;
      const double room = 1.0 - relaxation_.residual_fraction;
      out_scale_[c] = out > room ? room / out : 1.0;
    }
    // 3. heights from the pipes' fluxes: each moving pipe's flux once, read by both its ends (mass exact)
    for (const std::size_t c : cells)
      for (int pipe = 0; pipe < kPipes; ++pipe)
        flux_[c * kPipes + pipe] = static_cast<float>(pipe_flux(c, pipe, dt));
    for (std::size_t n = 0; n < cells.size(); ++n) {
      const std::size_t c = cells[n];
      double delta = 0.0;
      for (int pipe = 0; pipe < kPipes; ++pipe) {
        const std::size_t from = (c - neighbour_offset_[2 * pipe]) * kPipes + pipe;  // its pipe towards c
        if (vel_[from] != 0.0) delta += flux_[from];  // a moving pipe's owner is examined: its flux is fresh
        delta -= flux_[c * kPipes + pipe];
      }
      deltas_[n] = delta;
    }
  }
  // 4. the residual relaxation on the pairs at rest, from the same heights (done above while the pipes stay
  // still)
  if (!still) relax_residual(false);
  finish_sub_step(cells, still);
}

void HeightGrid::finish_sub_step(const std::vector<std::size_t>& cells, bool still) {
  // 5. a new epoch: cells whose height changed or whose pipes move are examined next
  active_.clear();
  if (++epoch_ == kNeverExamine) {
    epoch_ = 1;
    std::replace_if(
        active_stamp_.begin(), active_stamp_.end(), [](std::uint32_t s) { return s != 0; }, 0u);
  }
  fastest_mps_ = 0.0;
  moving_pipes_ = 0;
  for (std::size_t n = 0; n < cells.size(); ++n) {
    const std::size_t c = cells[n];
    bool moving = deltas_[n] != 0.0 || residual_[n] != 0.0;
    for (int pipe = 0; pipe < kPipes && !still; ++pipe) {
      const double u = vel_[c * kPipes + pipe];
      if (u == 0.0) continue;
      moving = true;
      ++moving_pipes_;
      fastest_mps_ = std::max(fastest_mps_, std::abs(u));
      activate(c + neighbour_offset_[2 * pipe]);  // the pipe's far end is examined next too
    }
    if (!moving) continue;
    if (!std::isfinite(deltas_[n]) || !std::isfinite(residual_[n])) {  // never let a NaN into the heights
      ++non_finite_;
      continue;
    }
    h_[c] = std::max(h_[c] + deltas_[n] + residual_[n], 0.0);
    mark(c);
  }
  examined_ = cells.size();
}

void HeightGrid::collect_examined() {
  // cells to examine: the active ones and every stencil neighbour, each once, in memory order (a bit per
  // cell, then a scan of the rows they touch: the passes over them then walk memory forwards)
  std::size_t first = examine_bits_.size(), last = 0;  // words touched
  for (const std::size_t cell : active_) {
    for (int k = -1; k < kStencil; ++k) {
      const std::size_t q = k < 0 ? cell : cell + neighbour_offset_[k];
      if (is_wall(q)) continue;
      const std::size_t word = q / 64;
      examine_bits_[word] |= std::uint64_t{1} << (q % 64);
      first = std::min(first, word);
      last = std::max(last, word);
    }
  }
  examine_.clear();
  for (std::size_t word = first; word <= last && first < examine_bits_.size(); ++word) {
    std::uint64_t bits = examine_bits_[word];
    examine_bits_[word] = 0;
    while (bits != 0) {
      examine_.push_back(word * 64 + static_cast<std::size_t>(std::countr_zero(bits)));
      bits &= bits - 1;
    }
  }
}

void HeightGrid::relax_active(double dt_s) {
  advance(dt_s, false);
}

void HeightGrid::relax_full_sweep(double dt_s) {
  advance(dt_s, true);
}

void HeightGrid::advance(double dt_s, bool full_sweep) {
  // sub-steps: the fastest pipe moves material at most max_courant cells per sub-step
  substeps_ =
      std::max(1, static_cast<int>(std::ceil(fastest_mps_ * dt_s / (relaxation_.max_courant * cell_m_))));
  if (full_sweep) {
    examine_.clear();
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i)
        examine_.push_back(index(i, j));
  }
  for (int n = 0; n < substeps_; ++n) {
    if (!full_sweep) collect_examined();
    flow(examine_, dt_s / substeps_);
  }
}

void HeightGrid::activate_loaded_cells() {
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      if (height(i, j) > 0.0) mark(index(i, j));
}

void HeightGrid::hash_into(core::StateHash& hash) const {
  hash.add(std::span<const double>(h_));
  hash.add(std::span<const double>(comp_));
  for (const float v : vel_)
    hash.add(static_cast<double>(v));
  hash.add(slope_up_);
  hash.add(active_.size());
}

template <typename Self, typename Archive>
void HeightGrid::archive(Self& self, Archive& ar) {
  ar.section(0x48475231, "bulk grid");  // "HGR1"
  int nx = self.nx_, ny = self.ny_;
  double cell_m = self.cell_m_;
  ar(nx, ny, cell_m);
  if constexpr (Archive::kRestoring)
    if (nx != self.nx_ || ny != self.ny_ || cell_m != self.cell_m_)
      throw core::StateError("saved state has a bulk grid of another size");
  ar.sized(self.h_);
  ar.sized(self.comp_);
  ar.sized(self.vel_);
  ar.sized(self.tile_version_);
  ar(self.pose_, self.linear_velocity_, self.angular_velocity_, self.slope_up_, self.fastest_mps_,
     self.moving_pipes_, self.substeps_, self.active_);
  if constexpr (Archive::kRestoring) {
    if (self.active_.size() > self.h_.size())
      throw core::StateError("saved bulk grid's active list is longer than the grid");
    for (const std::size_t cell : self.active_)
      if (cell >= self.h_.size()) throw core::StateError("saved bulk grid's active list points off the grid");
  }
  ar.sized(self.active_stamp_);
  ar.sized(self.examine_bits_);
  ar(self.epoch_, self.non_finite_, self.examined_);
}

void HeightGrid::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void HeightGrid::restore_state(core::StateReader& in) {
  archive(*this, in);
  update_slope_offsets();
}

}  // namespace harbour::bulk
