#include "harbour/bulk/HeightGrid.h"

#include <algorithm>
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
      pair_fraction_(material.flow_fraction / kStencil),
      relaxation_(relaxation),
      stride_(static_cast<std::size_t>(settings.cells_x + 2 * kPad)) {
  HARBOUR_ASSERT(nx_ > 0 && ny_ > 0 && cell_m_ > 0.0, "grid settings must be validated by the loader");
  HARBOUR_ASSERT(material.flow_fraction > 0.0 && material.flow_fraction < 1.0,
                 "flow fraction outside (0, 1)");
  const std::size_t padded = stride_ * static_cast<std::size_t>(ny_ + 2 * kPad);
  h_.assign(padded, 0.0);
  comp_.assign(padded, kWall);
  active_stamp_.assign(padded, 0);
  examine_stamp_.assign(padded, kNeverExamine);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      comp_[index(i, j)] = 0.0;
      examine_stamp_[index(i, j)] = 0;
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
    level_offset_[k] = -std::sqrt(squared_distance_[k]) * tan_repose_;
  }
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

template <bool kLevel>
double HeightGrid::net_inflow(std::size_t cell, bool& moved) const {
  // gather the flows across all 16 pairs of this cell from the previous heights (synchronous update);
  // flow p->q = c/16 * min(excess, h_p), excess = world elevation drop minus horizontal distance *
  // tan(repose)
  const double hp = h_[cell];
  const double sp = hp + comp_[cell];
  double delta = 0.0;
  for (int k = 0; k < kStencil; ++k) {
    const std::size_t q = cell + neighbour_offset_[k];
    const double hq = h_[q];
    const double ds = sp - (hq + comp_[q]);
    double drop, critical_drop;
    if constexpr (kLevel) {
      drop = ds;
      critical_drop = -level_offset_[k];
    } else {
      // on a tilted grid the height difference also shifts the points horizontally
      drop = slope_up_.z * ds - rise_[k];
      critical_drop = std::sqrt(std::max(0.0, squared_distance_[k] + ds * ds - drop * drop)) * tan_repose_;
    }
    const double out_excess = drop - critical_drop;
    const double in_excess = -drop - critical_drop;
    if (out_excess > relaxation_.min_excess_m) {
      const double flow = pair_fraction_ * std::min(out_excess, hp);
      if (flow > 0.0) {
        delta -= flow;
        moved = true;
      }
    } else if (in_excess > relaxation_.min_excess_m) {
      const double flow = pair_fraction_ * std::min(in_excess, hq);
      if (flow > 0.0) {
        delta += flow;
        moved = true;
      }
    }
  }
  return delta;
}

void HeightGrid::examine(const std::vector<std::size_t>& cells) {
  deltas_.resize(cells.size());
  moved_.resize(cells.size());
  for (std::size_t n = 0; n < cells.size(); ++n) {
    bool moved = false;
    deltas_[n] = level_ ? net_inflow<true>(cells[n], moved) : net_inflow<false>(cells[n], moved);
    moved_[n] = moved;
  }
  examined_ = cells.size();
  apply(cells, deltas_, moved_);
}

void HeightGrid::apply(const std::vector<std::size_t>& cells, const std::vector<double>& deltas,
                       const std::vector<std::uint8_t>& moved) {
  // a new epoch: cells that moved now are examined next step
  active_.clear();
  if (++epoch_ == kNeverExamine) {
    epoch_ = 1;
    std::replace_if(
        active_stamp_.begin(), active_stamp_.end(), [](std::uint32_t s) { return s != 0; }, 0u);
    std::replace_if(
        examine_stamp_.begin(), examine_stamp_.end(), [](std::uint32_t s) { return s != kNeverExamine; }, 0u);
  }
  for (std::size_t n = 0; n < cells.size(); ++n) {
    if (!moved[n]) continue;
    if (!std::isfinite(deltas[n])) {  // never let a NaN into the heights: count it and skip the cell
      ++non_finite_;
      continue;
    }
    h_[cells[n]] += deltas[n];
    mark(cells[n]);
  }
}

void HeightGrid::relax_active() {
  // cells to examine: the active ones and every stencil neighbour, each once
  examine_.clear();
  for (const std::size_t cell : active_) {
    if (examine_stamp_[cell] != epoch_) {
      examine_stamp_[cell] = epoch_;
      examine_.push_back(cell);
    }
    for (const std::ptrdiff_t off : neighbour_offset_) {
      const std::size_t q = cell + off;
      if (examine_stamp_[q] == epoch_ || examine_stamp_[q] == kNeverExamine) continue;
      examine_stamp_[q] = epoch_;
      examine_.push_back(q);
    }
  }
  examine(examine_);
}

void HeightGrid::relax_full_sweep() {
  examine_.clear();
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      examine_.push_back(index(i, j));
  examine(examine_);
}

void HeightGrid::activate_loaded_cells() {
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      if (height(i, j) > 0.0) mark(index(i, j));
}

void HeightGrid::hash_into(core::StateHash& hash) const {
  hash.add(std::span<const double>(h_));
  hash.add(std::span<const double>(comp_));
  hash.add(slope_up_);
  hash.add(active_.size());
}

}  // namespace harbour::bulk
