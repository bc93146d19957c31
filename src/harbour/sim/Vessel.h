#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/scene/Surface.h"

namespace harbour::sim {

/// One harmonic of the moored vessel's response: amplitude * sin(2 pi t / period + phase).
struct Harmonic {
  double amplitude = 0.0;  ///< [m] heave, [rad] roll and pitch
  double period_s = 10.0;
  double phase_rad = 0.0;
};

/// Motion of the moored vessel (the sum of harmonics per degree of freedom): heave, roll (about the vessel's
/// length), pitch (about its beam), about the midship waterline point.
struct SeaState {
  std::vector<Harmonic> heave_m, roll_rad, pitch_rad;
};

/// What a vessel carries: containers in cell-guided holds, or bulk in open holds.
enum class VesselKind : std::uint8_t { kContainer, kBulk };

/// A vessel (settings, data/vessels/*.yaml). Vessel frame: origin at the keel, midship, on the centreline;
/// x to starboard, y forward, z up. A cellular container vessel: only 40 ft bays are modelled (even bay
/// numbers); the holds have cell guides, the hatches pontoon covers the crane lifts off like containers. A
/// bulk carrier: holds under open hatches of one breadth, each hold from side shell to side shell and between
/// its cross decks (hopper and topside tanks are not modelled).
struct VesselSettings {
  std::string name;
  VesselKind kind = VesselKind::kContainer;
  double length_m = 150.0;
  double beam_m = 23.0;
  double depth_m = 11.5;          ///< [m] keel to main deck
  double draught_m = 7.0;         ///< [m] keel to waterline
  double tank_top_m = 1.5;        ///< [m] keel to the hold floor
  double coaming_height_m = 1.5;  ///< [m] main deck to the top of the hatch coamings
  int rows = 8;                   ///< across the beam
  double row_pitch_m = 2.54;      ///< [m] row centre to row centre
  int hold_tiers = 4, deck_tiers = 3;
  double tier_height_m = 2.591;     ///< [m] 8 ft 6 in boxes
  double cell_clearance_m = 0.025;  ///< [m] container side to cell guide, each side
  double cell_guide_thickness_m = 0.02, cell_guide_leg_m = 0.15;  ///< [m] angle bar
  int hatch_panels = 2;                                           ///< pontoon covers across the beam (1 or 2)
  double hatch_cover_mass_kg = 20000.0;
  double hatch_cover_thickness_m = 0.8;
  struct Bay {
    int number = 0;         ///< even: a 40 ft bay
    double centre_m = 0.0;  ///< [m] along the vessel from midship, + forward
  };
  std::vector<Bay> bays;
  double hatch_breadth_m = 0.0;  ///< [m] a bulk carrier's hatch openings, across the beam
  struct Hold {
    int number = 0;
    double centre_m = 0.0;          ///< [m] along the vessel from midship, + forward
    double opening_length_m = 0.0;  ///< [m] its hatch opening along the vessel
    bool open = true;               ///< false: its hatch cover is on (a fixed lid on the coamings)
  };
  std::vector<Hold> holds;  ///< a bulk carrier's
};

/// Where a container sits on a vessel: ISO 9711 bay, row, tier (rows 01, 03, ... to starboard and 02,
/// 04, ... to port of the centreline; hold tiers 02, 04, ...; deck tiers 82, 84, ...).
struct SlotAddress {
  int bay = 0, row = 0, tier = 0;
};

/// The vessel as moored: where its keel midship point is when the sea is still and how the sea moves it.
struct VesselPlacement {
  VesselSettings vessel;
  core::Vec3 keel_midship_m;  ///< [m] world; the bow points along +y
  SeaState sea;
};

/// The vessel's geometry, independent of the physics (loaders place containers with it).
class VesselGeometry {
 public:
  explicit VesselGeometry(const VesselPlacement& placement) : p_(placement) {}

  /// The vessel frame in the world at time t (pose) and its velocities (of the frame origin).
  core::Pose pose_at(double t_s) const;
  void velocities_at(double t_s, core::Vec3& linear, core::Vec3& angular) const;
  /// World pose at time t of a box stowed lengthwise (its x along the vessel) with its centre at `centre_m`
  /// (vessel frame).
  core::Pose stowed_pose_at(double t_s, const core::Vec3& centre_m) const;
  /// Centre of a container of height `height_m` in `slot`, vessel frame; empty (with `why`) if no such slot.
  std::optional<core::Vec3> slot_centre(const SlotAddress& slot, double height_m, std::string& why) const;
  /// Row centre across the beam (vessel frame x) of a row number, if the vessel has that row.
  std::optional<double> row_x(int row) const;
  const VesselSettings::Bay* bay(int number) const;
  /// Hatch cover panels of a bay: centre (vessel frame) and half extents (x across, y along, z).
  struct Panel {
    std::string id;
    core::Vec3 centre_m, half_extents_m;
  };
  std::vector<Panel> hatch_panels() const;
  /// Hatch openings inside the coamings: one per bay (container vessel) or hold (bulk carrier).
  struct Opening {
    double centre_m = 0.0;  ///< [m] along the vessel
    double half_breadth_m = 0.0, half_length_m = 0.0;
  };
  std::vector<Opening> hatch_openings() const;
  const VesselSettings::Hold* hold(int number) const;
  /// A bulk hold's floor (vessel frame): the tank top from side shell to side shell and between the cross
  /// decks.
  struct Floor {
    core::Vec3 corner_m;  ///< [m] its aft port corner
    double breadth_m = 0.0, length_m = 0.0;
  };
  Floor hold_floor(const VesselSettings::Hold& hold) const;
  double coaming_top_m() const { return p_.vessel.depth_m + p_.vessel.coaming_height_m; }
  const VesselPlacement& placement() const { return p_; }

 private:
  // the waterline point about which the vessel rolls and pitches, vessel frame
  core::Vec3 centre() const { return {0, 0, p_.vessel.draught_m}; }
  VesselPlacement p_;
};

/// The vessel in the physics world: one kinematic body carrying the hull, coamings, cross decks and every
/// cell guide, moved each step along its sea-state motion (containers and hatch covers ride on it through
/// their contacts).
class Vessel {
 public:
  Vessel(physics::PhysicsWorld& world, const VesselPlacement& placement);

  /// Places the hull for the step that starts at `t_s`.
  void move_to(double t_s);
  /// The vessel frame (keel, midship, centreline) in the world as last placed, and the velocities of the
  /// body's origin (the midship waterline point, `waterline_centre()` in the world).
  const core::Pose& frame() const { return frame_; }
  const core::Vec3& velocity() const { return velocity_; }
  const core::Vec3& angular_velocity() const { return angular_velocity_; }
  core::Vec3 waterline_centre() const { return frame_.to_parent(origin()); }
  physics::BodyId body() const { return body_; }
  const VesselGeometry& geometry() const { return geometry_; }
  int cell_guide_shapes() const { return cell_guide_shapes_; }

 private:
  core::Vec3 origin() const { return {0, 0, geometry_.placement().vessel.draught_m}; }

  physics::PhysicsWorld& world_;
  VesselGeometry geometry_;
  physics::BodyId body_;
  int cell_guide_shapes_ = 0;
  core::Pose frame_;
  core::Vec3 velocity_, angular_velocity_;
};

}  // namespace harbour::sim
