#pragma once

#include <cstdint>
#include <vector>

#include "harbour/bulk/Contact.h"
#include "harbour/bulk/Grab.h"
#include "harbour/bulk/HeightGrid.h"
#include "harbour/bulk/Material.h"
#include "harbour/core/Units.h"
#include "harbour/core/Warnings.h"

namespace harbour::bulk {

/// Settings of a bulk world.
struct BulkWorldSettings {
  RelaxationSettings relaxation;
  ContactSettings contact;
  double spill_level_m = 0.0;  ///< [m] world z below which falling material outside every grid is spilled
  double gravity_mps2 = core::kStandardGravity;  ///< [m/s^2]
};

/// Where every cubic metre is: the balance is exact up to rounding.
struct VolumeBalance {
  double in_grids_m3 = 0.0;
  double in_grabs_m3 = 0.0;
  double in_flight_m3 = 0.0;
  double spilled_m3 = 0.0;
  double delivered_m3 = 0.0;  ///< left through a hopper's outlet
  double added_m3 = 0.0;      ///< everything ever poured in
  /// in_grids + in_grabs + in_flight + spilled + delivered - added: zero up to rounding.
  double discrepancy_m3() const {
    return in_grids_m3 + in_grabs_m3 + in_flight_m3 + spilled_m3 + delivered_m3 - added_m3;
  }
};

/// Material falling from a grab: a point parcel in free flight.
struct Parcel {
  core::Vec3 position;  ///< [m] world
  core::Vec3 velocity;  ///< [m/s] world
  double volume_m3 = 0.0;
  double footprint_m = 0.0;  ///< [m] side of the square it spreads over when it lands
};

/// One material's bulk simulation: its grids (active regions), grabs and falling material.
class BulkWorld {
 public:
  /// Room kept for falling parcels, here and in every reader's copy (a grab spills one a step while it
  /// opens; more than this in the air at once grows the list, allocating).
  static constexpr std::size_t kParcelsReserved = 4096;

  BulkWorld(const Material& material, const BulkWorldSettings& settings);

  const Material& material() const { return material_; }
  const BulkWorldSettings& settings() const { return settings_; }

  /// Adds an active region and returns its index.
  int add_grid(const GridSettings& grid, const core::Pose& pose);
  HeightGrid& grid(int id) { return grids_[static_cast<std::size_t>(id)]; }
  const HeightGrid& grid(int id) const { return grids_[static_cast<std::size_t>(id)]; }
  int grid_count() const { return static_cast<int>(grids_.size()); }

  /// Makes grid `id` a hopper: material in it leaves through its outlet at up to `m3_per_s` (delivered).
  void set_outflow(int id, double m3_per_s);
  /// Adds a grab and returns its index.
  int add_grab(const GrabSettings& grab);
  const GrabState& grab(int id) const { return grabs_[static_cast<std::size_t>(id)]; }
  const GrabSettings& grab_settings(int id) const { return grab_settings_[static_cast<std::size_t>(id)]; }

  /// Pours `volume_m3` into the cell under grid-frame (x, y) of grid `grid_id` (a conveyor or an initial
  /// pile). Returns false, adding nothing, when the point is off the grid.
  bool pour(int grid_id, double x, double y, double volume_m3);

  /// Fills grid `grid_id` level to `depth_m` (a loaded hold).
  void fill_level(int grid_id, double depth_m);

  /// Builds a relaxed cone of about `volume_m3` at the angle of repose centred at grid-frame (x, y),
  /// clipped by the grid's walls; returns the volume added [m^3].
  double add_heap(int grid_id, double x, double y, double volume_m3);

  /// Penalty contact of one body against every grid; sets compression of pressed cells for this step.
  ContactResult contact(const ContactBody& body);

  /// Advances grabs, falling material and relaxation by `dt_s`; compression is cleared afterwards.
  void step(double dt_s, std::span<const GrabCommand> grab_commands);

  /// Where the material is now (sums every cell: O(cells), for checks and reports).
  VolumeBalance balance() const;
  /// Mass of a volume of this material [kg].
  double mass_kg(double volume_m3) const { return volume_m3 * material_.bulk_density_kg_m3; }
  /// Total volume unloaded from grabs so far [m^3] (tonnes handled, for evaluation).
  double unloaded_m3() const { return unloaded_m3_; }
  /// Total volume loaded into grabs so far [m^3].
  double loaded_m3() const { return loaded_m3_; }
  const std::vector<Parcel>& parcels() const { return parcels_; }
  /// Falling material that has landed on grid `id` so far [m^3] (dropped into a hopper: delivered).
  double landed_m3(int id) const { return landed_m3_[static_cast<std::size_t>(id)]; }
  /// Falling material lost below the spill level outside every grid so far [m^3].
  double spilled_m3() const { return spilled_m3_; }

  /// Selects the relaxation used by step(): the active list (default) or the full-sweep reference.
  void use_full_sweep(bool on) { full_sweep_ = on; }

  const core::Warnings& warnings() const { return warnings_; }
  std::uint64_t state_hash() const;
  /// The dynamic state (grids, grabs, falling parcels, pressed cells, the balance's counters) for a keyframe;
  /// restoring it into a world with the same grids and grabs continues bit for bit; another world throws
  /// core::StateError.
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar);
  void step_grab(GrabSettings const& settings, GrabState& state, const GrabCommand& command, double dt_s);
  double dig(const GrabSettings& settings, GrabState& state, double dt_s);
  void step_parcels(double dt_s);
  void drain_hoppers(double dt_s);
  bool land(const Parcel& parcel);

  Material material_;
  BulkWorldSettings settings_;
  std::vector<HeightGrid> grids_;
  std::vector<double> outflow_m3_per_s_;  // per grid: a hopper's outlet (0: none)
  std::vector<double> landed_m3_;         // per grid: falling material landed on it
  std::vector<GrabSettings> grab_settings_;
  std::vector<GrabState> grabs_;
  std::vector<Parcel> parcels_;
  struct PressedCell {
    int grid, i, j;
    double height_m;
  };
  void update_compression();
  std::vector<PressedCell> pressed_;   // cells compressed during the last step
  std::vector<PressedCell> pressing_;  // cells the contacts of this step press
  std::vector<CellIndex> footprint_;   // scratch
  double added_m3_ = 0.0;
  double spilled_m3_ = 0.0;
  double delivered_m3_ = 0.0;
  double loaded_m3_ = 0.0;
  double unloaded_m3_ = 0.0;
  bool full_sweep_ = false;
  core::Warnings warnings_;
};

}  // namespace harbour::bulk
