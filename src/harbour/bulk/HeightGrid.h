#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "harbour/bulk/Material.h"
#include "harbour/core/StateArchive.h"
#include "harbour/core/StateHash.h"
#include "harbour/core/Vec3.h"

namespace harbour::bulk {

/// Size of a height grid (settings). The grid frame has its origin at the outer corner of cell (0, 0),
/// x along i, y along j, z up from the floor; the grid's edges are walls (material stays inside).
struct GridSettings {
  int cells_x = 0;           ///< cells along x
  int cells_y = 0;           ///< cells along y
  double cell_size_m = 0.1;  ///< [m] side of a square cell
};

/// Flow tuning shared by every grid of a bulk world.
struct RelaxationSettings {
  double min_excess_m = 1e-5;  ///< [m] slope excess below which material at rest stays at rest
  /// [m] slope excess over a neighbour pair beyond which material at rest starts to flow (the pair's pipe
  /// accelerates); smaller excesses are relaxed by the paper's critical-slope rule, moving
  /// `residual_fraction` of the excess per step (a heap built slowly stays at its angle of repose)
  double flow_start_excess_m = 0.05;
  double residual_fraction = 0.5;
  double tilt_quantum_rad = 8.7e-4;  ///< [rad] tilt change (0.05 deg) that re-examines a moving grid
  double gravity_mps2 = 9.81;
  double max_courant = 0.4;  ///< a step is cut into sub-steps so no pipe moves material further (cells/step)
};

/// Cell coordinates inside a grid.
struct CellIndex {
  int i = 0;
  int j = 0;
};

/// One active region of bulk material: a height field on square cells whose rest state is the critical-slope
/// rule of García-Fernández et al. §3.1 (every neighbour pair of a 16-neighbour stencil at most at the angle
/// of repose) and whose flow is physical: a depth-averaged Coulomb flow (Savage-Hutter) carried by "pipes"
/// between neighbour pairs, each with a velocity accelerated by the surface slope along it, slowed by the
/// material's flow friction, advected along its line (momentum: inertial runout) and started from rest only
/// where the slope exceeds the repose angle. docs/models/bulk.md.
class HeightGrid {
 public:
  HeightGrid(const GridSettings& settings, const Material& material, const RelaxationSettings& relaxation);

  int cells_x() const { return nx_; }
  int cells_y() const { return ny_; }
  double cell_size_m() const { return cell_m_; }
  double cell_area_m2() const { return cell_m_ * cell_m_; }

  /// World pose of the grid frame, and the grid's velocity for contact rates.
  const core::Pose& pose() const { return pose_; }
  const core::Vec3& linear_velocity() const { return linear_velocity_; }
  const core::Vec3& angular_velocity() const { return angular_velocity_; }
  /// Moves the grid (a vessel's hold). A tilt change beyond the quantum re-examines every loaded cell.
  void set_pose(const core::Pose& pose, const core::Vec3& linear_velocity = {},
                const core::Vec3& angular_velocity = {});

  /// Material height of a cell [m].
  double height(int i, int j) const { return h_[index(i, j)]; }
  /// Artificial compression height of a cell [m]; enters slopes only.
  double compression(int i, int j) const { return comp_[index(i, j)]; }
  /// Adds `volume_m3` of material to a cell (volume >= 0).
  void add_volume(int i, int j, double volume_m3);
  /// Removes up to `thickness_m` of material from a cell; returns the volume removed [m^3].
  double remove_layer(int i, int j, double thickness_m);
  /// Takes the same share of every cell's material (a hopper's outlet); returns the volume removed [m^3].
  /// Every height scaled down by one factor scales every slope down, so cells at rest stay at rest: only
  /// pressed cells are woken.
  double sink_evenly(double share);
  /// Sets the artificial compression height of a cell [m].
  void set_compression(int i, int j, double height_m);

  /// True when grid-frame point (x, y) lies over the grid.
  bool contains(double x, double y) const;
  /// The cell under grid-frame point (x, y), if any.
  std::optional<CellIndex> cell_at(double x, double y) const;
  /// Grid-frame centre of cell (i, j) at the floor.
  core::Vec3 cell_centre(int i, int j) const;
  /// Material surface height [m] at grid-frame (x, y), bilinear between cell centres.
  double surface_height(double x, double y) const;

  /// Sum of material over all cells [m^3].
  double total_volume_m3() const;
  /// Largest cell height [m].
  double max_height_m() const;

  /// Advances the flow by `dt_s` examining only the active cells (the paper's active list); cut into
  /// sub-steps where the fastest pipe would move material more than `max_courant` cells.
  void relax_active(double dt_s);
  /// The same step examining every cell: the reference for tests and the benchmark baseline.
  void relax_full_sweep(double dt_s);
  /// Velocity of the pipe from cell (i, j) to its stencil neighbour `pipe` (0-7: (1, 0), (0, 1), (1, 1),
  /// (1, -1), (2, 1), (1, 2), (-1, 2), (-2, 1)) [m/s], positive towards the neighbour.
  double pipe_velocity(int i, int j, int pipe) const { return vel_[index(i, j) * kPipes + pipe]; }
  /// Sub-steps the last step was cut into.
  int substeps() const { return substeps_; }
  /// Cells that changed in the last step or were edited since; the next step starts from them.
  std::size_t active_count() const { return active_.size(); }
  /// Cells examined by the last relaxation step.
  std::size_t examined_count() const { return examined_; }
  /// Marks every cell holding material active (after an external change of slope rules).
  void activate_loaded_cells();

  /// Relaxation updates rejected because they were not finite (a physics anomaly; should stay 0).
  std::uint32_t non_finite_count() const { return non_finite_; }

  /// Cells per side of a tile, the unit in which readers (the image generator) follow changes.
  static constexpr int kTileCells = 32;
  int tiles_x() const { return (nx_ + kTileCells - 1) / kTileCells; }
  int tiles_y() const { return (ny_ + kTileCells - 1) / kTileCells; }
  /// A counter per tile that moves on whenever a height or compression in it changes (not part of the
  /// state: readers compare it with the one they last saw).
  std::uint32_t tile_version(int ti, int tj) const {
    return tile_version_[static_cast<std::size_t>(tj * tiles_x() + ti)];
  }

  /// Adds heights, compression, tilt and active list to a determinism hash.
  void hash_into(core::StateHash& hash) const;
  /// The dynamic state (heights, compression, pipes, the active list, pose) for a keyframe; restoring it into
  /// a grid of the same settings continues bit for bit (another size throws core::StateError).
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  static constexpr int kPad = 2;  // stencil radius: knight moves reach two cells
  static constexpr int kStencil = 16;
  static constexpr int kPipes = kStencil / 2;  // one per neighbour pair, owned by the cell it leaves
  static constexpr double kWall = 1e30;        // compression of the padding ring: nothing flows in or out

  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j + kPad) * stride_ + (i + kPad); }
  void mark(std::size_t cell);      // changed (its tile's version moves on) and examined next
  void activate(std::size_t cell);  // examined next
  void update_slope_offsets();
  bool is_wall(std::size_t cell) const { return comp_[cell] == kWall; }
  template <bool kLevel, bool kStill>
  void update_pipes(std::size_t cell, double dt, float* velocities) const;
  double pipe_flux(std::size_t cell, int pipe, double dt) const;  // height moved along it this sub-step
  // the critical-slope rule over the pairs at rest; `may_start` set where an owned pair is steep enough for
  // its pipe to start
  template <bool kLevel, bool kStill>
  double residual_inflow(std::size_t cell, bool& may_start) const;
  void finish_sub_step(const std::vector<std::size_t>& cells, bool still);  // heights, the next active list
  void flow(const std::vector<std::size_t>& cells, double dt);
  void collect_examined();
  void advance(double dt_s, bool full_sweep);  // sub-steps over the active cells or every cell

  int nx_, ny_;
  double cell_m_;
  double tan_repose_, tan_flow_;
  RelaxationSettings relaxation_;
  std::size_t stride_;
  std::vector<std::uint32_t> tile_version_;

  core::Pose pose_;
  core::Vec3 linear_velocity_, angular_velocity_;
  core::Vec3 slope_up_{0, 0, 1};  // world up in grid coordinates, quantised; sets the slope rule

  std::array<std::ptrdiff_t, kStencil> neighbour_offset_{};
  bool level_ = true;                                // grid floor horizontal: the fast path
  std::array<double, kStencil> level_offset_{};      // minus the critical drop to neighbour k on a level grid
  std::array<double, kStencil> rise_{};              // world elevation gained moving to neighbour k (tilt)
  std::array<double, kStencil> squared_distance_{};  // [m^2] grid-plane distance to neighbour k
  std::array<double, kStencil> distance_{};          // [m] grid-plane distance to neighbour k
  // a pipe's width w = s / (4 n) over the cell's area s^2, n its length in cells [1/m]: height moved per
  // sub-step = u dt share h_up
  std::array<double, kPipes> pipe_share_{};

  std::vector<double> h_;         // material height per cell, padded
  std::vector<double> comp_;      // artificial compression height per cell, padded (walls: kWall)
  std::vector<float> vel_;        // pipe velocities, kPipes per cell, padded [m/s] (float: memory-bound)
  double fastest_mps_ = 0.0;      // the fastest pipe after the last sub-step: sets the next step's sub-steps
  std::size_t moving_pipes_ = 0;  // pipes moving after the last sub-step (0: the fast path)
  int substeps_ = 0;

  // active list: cells to examine next, deduplicated by stamp
  std::vector<std::size_t> active_;
  std::vector<std::uint32_t> active_stamp_;
  std::vector<std::uint64_t> examine_bits_;  // cells to examine in the next sub-step, a bit each
  std::uint32_t epoch_ = 1;
  std::uint32_t non_finite_ = 0;
  std::size_t examined_ = 0;

  // scratch buffers reused across steps (not state)
  std::vector<std::size_t> examine_;
  std::vector<double> deltas_, residual_;
  std::vector<float> new_vel_;     // per examined cell, kPipes
  std::vector<double> out_scale_;  // per cell (padded): outflow limiter of this sub-step
  std::vector<float> flux_;        // per pipe (padded): height it moves this sub-step
};

}  // namespace harbour::bulk
