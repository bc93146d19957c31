#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <osg/Node>
#include <osg/ref_ptr>

#include "harbour/core/Vec3.h"
#include "harbour/ig/Materials.h"
#include "harbour/ig/Structures.h"

namespace harbour::ig {

/// One part of a look, in the entity's frame: a box; a lattice girder filling the box (four chords along its
/// longest side, verticals and Warren diagonals in its faces, a bay `bay_m` long, members `member_m` thick);
/// an ISO container filling the box (corrugated walls, castings, doors: ig/Models.h); a tyre on its rim
/// filling the box (its axle along the side that differs from the two equal ones, the rim `rim_color`); or
/// a clamshell grab's shell hanging from its pivot at the centre (ig/Models.h); a ship's hull filling the box
/// (bow at +y, `bottom_color` under `waterline_m`, a deck of `deck_color` or none); or a mesh read through
/// osgDB (OBJ, STL, PLY, .osgt, ...), placed at the centre, scaled by `scale`. Steelwork (ig/Structures.h): a
/// box girder filling the box (a stiffener at every diaphragm, `bay_m` apart), a walkway (grating deck at the
/// box's bottom, guard-rails its height on `rails`), a flight of stairs (climbing along +x), a cylinder (its
/// axis along the side that differs), or a member `from` one point `to` another of a `section_m` [width,
/// depth]. `repeat` copies of a part `step` apart are read as that many parts. Any part may be turned about z
/// by `yaw_rad` and turn with an indicator. A part that turns with one of the machine's indicators (its
/// published value, taken as 0-1 by `arcsine`): about `axis` (the part's frame, right hand) through its
/// centre, by `max_rad` times the value, or with `arcsine` by the angle whose sine is the value times
/// sin(max_rad) (the part's tip then moves across in proportion: a jaw's span). A linear turn takes the value
/// as published, sign and all (a steered wheel, left and right; an RTG's wheels turned by `degrees: -1` per
/// degree of its wheel turn). A tyre may also roll with an indicator of its machine's speed: about its axle,
/// by the distance the indicator's speed (`rolls_unit_mps` metres per second per unit) covers between
/// snapshots over its radius, forward along `rolls_along` (the part's own frame, level and across the axle).
struct PartTurn {
  std::string indicator;
  core::Vec3 axis{0.0, 1.0, 0.0};
  double max_rad = 0.0;
  bool arcsine = false;
  std::optional<core::Vec3> pivot_m;  ///< the point it turns about (entity frame); none: the part's centre
};

/// A part sliding with one of the machine's indicators: moved by (value - `from`) times `along` (metres per
/// unit, entity frame) after any turn: a telescopic spreader's ends with its published length.
struct PartSlide {
  std::string indicator;
  core::Vec3 along;
  double from = 0.0;
};

struct VisualPart {
  enum class Shape {
    kBox,
    kLattice,
    kContainer,
    kTyre,
    kShell,
    kHull,
    kMesh,
    kGirder,
    kWalkway,
    kStairs,
    kCylinder,
    kMember,
    kSpreader,
    kDeckhouse
  };
  Shape shape = Shape::kBox;
  std::optional<core::Vec3> size_m;  ///< full size; empty: the entity's own size
  core::Vec3 centre_m;
  core::Vec3 color{0.5, 0.5, 0.5};            ///< linear RGB
  Surface surface = Surface::kPaint;          ///< what it is made of (a tyre: its rim's)
  bool livery = false;                        ///< coloured by the entity's livery instead
  double bay_m = 3.0, member_m = 0.25;        ///< lattice; a girder's bay_m
  RailSides rails = RailSides::kBoth;         ///< walkway
  core::Vec3 along{1.0, 0.0, 0.0};            ///< member: its length's way (size_m: length, width, depth)
  core::Vec3 rim_color{0.72, 0.72, 0.70};     ///< tyre: its rim's paint
  double hinge_m = 0.0;                       ///< shell: from its pivot down to its lip, shut
  core::Vec3 bottom_color{0.55, 0.12, 0.10};  ///< hull: under its waterline
  double waterline_m = 0.0;                   ///< hull: from the keel
  std::optional<core::Vec3> deck_color;       ///< hull: its deck (none: open to the sky)
  double deck_open_from_m = 0.0, deck_open_to_m = 0.0;  ///< hull: its deck left open along y (the holds)
  double yaw_rad = 0.0;                                 ///< turned about the entity's z at its centre
  std::optional<PartTurn> turn;                         ///< turning with an indicator
  std::optional<PartSlide> slide;                       ///< sliding with an indicator
  /// Something another machine can hit: in a team session the other stations' simulations have it as an
  /// obstacle riding its entity (a fixed box with its size written out: an STS's legs).
  bool solid = false;
  std::string rolls_with;                 ///< tyre: rolling with this speed indicator
  double rolls_unit_mps = 1.0;            ///< tyre: m/s per unit of that indicator
  core::Vec3 rolls_along{1.0, 0.0, 0.0};  ///< tyre: the way it rolls at a positive speed
  std::string mesh;                       ///< mesh: its file (resolved against the look file's folder)
  double scale = 1.0;                     ///< mesh
  /// spreader: its length follows this indicator (empty: as its box), its four corners' flippers turn with
  /// these (in the twistlock corners' order: empty, none drawn), its twistlocks turn with `locks_with`
  std::string telescopes_with, locks_with;
  std::vector<std::string> flippers;
  double twistlock_track_m = 2.259;  ///< spreader: its twistlocks' centres across (ISO 1161)
};

/// A telescopic top-lift spreader filling a box of `size_m` (x across, y along its length, z up) as the parts
/// that draw it: a main frame of box girders with its power pack and junction box, and at each end a head
/// beam with its twistlock housings, twistlocks (heads turning a quarter turn as they lock) and the
/// telescopic beams running back into the main frame, sliding out with its `telescopes_with` length from the
/// box's; at each corner a flipper (an L of guide plates on its arm) turning 180 deg about its hinge, folded
/// up at 0 and down round the corner at 1 (the corners in the twistlocks' order: +y -x, -y -x, -y +x, +y +x).
/// The main frame is as long as fits inside a 20 ft spreader (ISO 668: 6.058 m).
std::vector<VisualPart> spreader_parts(const VisualPart& spreader, const core::Vec3& size_m);

/// A ship's deckhouse (its accommodation) filling a box of `size_m` (x across the ship, y along it, the bow
/// at +y) as the parts that draw it: the block, its decks kDeckHeight_m high (as many as its height holds), a
/// band of windows on each deck above the lowest across its front and along both sides, the wheelhouse on top
/// at its front (0.7 of its width, 3 m high) with its windows, bridge wings from the wheelhouse out to 1 m
/// past the block's sides, a mast on the wheelhouse with its radar scanner.
std::vector<VisualPart> deckhouse_parts(const VisualPart& house, const core::Vec3& size_m);
inline constexpr double kDeckHeight_m = 2.8;
/// The parts a spreader or a deckhouse is drawn as; any other part as itself.
std::vector<VisualPart> drawn_parts(const VisualPart& part, const core::Vec3& size_m);

/// What a visual key looks like (data/visuals/*.yaml).
struct Visual {
  std::vector<VisualPart> parts;
  std::vector<core::Vec3> liveries;  ///< colours picked by entity index
  /// the entity's name marked where ISO 6346 marks a container's code: both long sides, both ends, the roof
  bool name_marked = false;
};

/// One line of the trainee's heads-up display: an indicator by name (SceneDescription::indicators).
struct HudItem {
  std::string indicator;
  std::string label;
  std::string unit;
  int decimals = 1;
  bool lamp = false;   ///< shown as its label while the indicator is on (> 0.5), hidden while off
  double scale = 1.0;  ///< the value shown is the indicator's times this (a share as per cent: 100)
  /// Shown as a word: the value rounded, from `words_from` on, names it (a direction selector's R, N, D)
  std::vector<std::string> words;
  int words_from = 0;
  std::string shown_while;  ///< only while this indicator is on (> 0.5): a hitch angle while reversing
  /// only on these machines (SceneDescription::machine; a machine file's own lines); none: on every one
  std::vector<std::string> machines;
  /// not on these: machines whose own line shows the indicator in its place
  std::vector<std::string> except;
  bool shown_on(const std::string& machine) const;
};

/// A floodlight lit from dusk to dawn: on the quay (world frame) or on a machine (riding the first entity
/// with the look `entity`, in its frame: the machine's own lamps, dark while its supply has failed, and
/// only where the scene has that entity).
struct Floodlight {
  core::Vec3 position_m;
  core::Vec3 color{1.0, 0.9, 0.75};
  double range_m = 60.0;  ///< where its light has fallen to a tenth
  std::string entity;     ///< empty: on the quay
  bool mast = false;      ///< on the quay: drawn on a light mast standing under it (ig/Structures.h)
};

/// A festoon: cables hanging in loops from carriers that run on a level track between two ends riding
/// entities (a trolley's supply and control cables from the girder's end to the trolley): `carriers` spread
/// evenly between the ends (at least 0.2 m apart), each loop `loop_m` of cable, `cables` side by side.
struct Festoon {
  std::string from_entity, to_entity;  ///< the looks of the entities its ends ride (the first with each)
  core::Vec3 from_m, to_m;             ///< the ends in their entities' frames
  int carriers = 12;
  double loop_m = 5.0;
  int cables = 3;
};

/// A hydraulic jack between two of a machine's entities (a reach stacker's lift cylinders): a barrel
/// `barrel_m` long from its eye on one towards the other, a rod `rod_m` long from the other's eye back into
/// it, redrawn as they move: whole while its eyes are at least the rod's length and at most both lengths
/// apart.
struct Jack {
  std::string from_entity, to_entity;  ///< the looks of the entities its ends ride (the first with each)
  core::Vec3 from_m, to_m;             ///< its barrel's and its rod's eyes in their entities' frames
  double barrel_m = 2.0, rod_m = 2.0, diameter_m = 0.3;
  core::Vec3 color{0.5, 0.5, 0.5};
};

/// A camera riding an entity (by its visual key): the spreader's camera, the boom tip's.
struct EntityCamera {
  std::string name;    ///< the view's name: spreader, boom_tip, ...
  std::string entity;  ///< visual key of the entity it rides (the first with it)
  core::Vec3 at_m;     ///< in the entity's frame
  core::Vec3 look;     ///< direction, entity frame
  core::Vec3 up{1.0, 0.0, 0.0};
  double fov_vertical_rad = 1.0;
};

/// A camera's picture set into a view (a monitor in the cab, a mirror): where it sits in the picture, as
/// shares of its width and height from the bottom-left corner.
struct Inset {
  std::string camera;  ///< an EntityCamera's name
  double left = 0.0, bottom = 0.0, width = 0.25, height = 0.25;
  bool mirror = false;  ///< drawn left-right reversed, as a mirror shows what is behind
};

/// A fixed piece of the harbour (world frame): the quay wall, crane rails, bollards, markings. A box, or an
/// upright cylinder (diameter size.x, height size.z); `repeat` copies `step_m` apart.
struct SceneryPart {
  enum class Shape { kBox, kCylinder };
  Shape shape = Shape::kBox;
  core::Vec3 centre_m, size_m;
  core::Vec3 color{0.5, 0.5, 0.5};
  Surface surface = Surface::kPaint;
  int repeat = 1;
  core::Vec3 step_m;
};

/// A look file: the looks by key, the HUD's lines, the floodlights, the entity cameras, the scenery.
struct Looks {
  std::map<std::string, Visual> visuals;
  std::vector<HudItem> hud;
  std::vector<Floodlight> floodlights;
  std::vector<Festoon> festoons;
  std::vector<Jack> jacks;
  std::vector<EntityCamera> cameras;
  std::vector<Inset> insets;  ///< of the cameras whose entity is in the scene
  std::vector<SceneryPart> scenery;
};

/// A mesh part's model through osgDB, in the entity's frame as written (z up: the OBJ reader's y-up turn
/// off); nullptr where it cannot be read.
osg::ref_ptr<osg::Node> read_mesh(const std::string& path);

/// Reads a look file (data/visuals/*.yaml). Errors name file, line and field.
Looks load_looks(const std::string& path);
/// The harbour's look file with the looks of machine files (`looks` in data/machines/<kind>.yaml: a
/// machine's entities, lamps, cameras, camera insets and HUD lines, keyed by its kind). Of several files of
/// one kind the last is read. A machine's HUD lines come first on it, in place of the harbour file's for the
/// same indicators.
Looks load_looks(const std::string& path, const std::vector<std::string>& machine_files);
/// The shipped looks: `data_folder`/visuals/harbour.yaml with io::machine_data_files() (the registry's kinds
/// from the caller: the image generator names none).
Looks load_shipped_looks(const std::string& data_folder, std::span<const std::string_view> kinds,
                         const std::string& machine_file = "");
/// Its looks alone.
std::map<std::string, Visual> load_visuals(const std::string& path);

}  // namespace harbour::ig
