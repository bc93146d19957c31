#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <osg/Array>
#include <osg/Matrixd>
#include <osg/ref_ptr>

#include "harbour/ig/Ocean.h"
#include "harbour/ig/SignalPanel.h"
#include "harbour/ig/Visuals.h"
#include "harbour/scene/BulkView.h"
#include "harbour/scene/Snapshot.h"

namespace osg {
class Image;
class Group;
class MatrixTransform;
class Camera;
class Geometry;
class Fog;
class LightSource;
class Uniform;
class StateSet;
class Program;
class Geode;
class Texture2D;
}  // namespace osg
namespace osgShadow {
class ShadowedScene;
}
namespace osgParticle {
class PrecipitationEffect;
}
namespace osgText {
class Text;
}
namespace osgViewer {
class Viewer;
}

namespace harbour::ig {

struct SkyShade;  // the sky's colours for the sun and the weather (ImageGenerator.cpp)

class ModelCache;  // the procedural models built once per size and colour

class HeadlessContext;

/// Where a view looks from.
struct View {
  enum class Kind {
    kCab,     ///< from the operator's eye
    kChase,   ///< from behind and above the cab
    kEntity,  ///< a camera of the look file riding an entity (`camera`: spreader, boom_tip, ...)
    kFree,    ///< the instructor's: `position_m`, looking by yaw (from +x towards +y) and pitch
  };
  Kind kind = Kind::kCab;
  double yaw_rad = 0.0, pitch_rad = -1.3,
         roll_rad = 0.0;  ///< cab: offset from the cab's forward axis (down 75 deg), roll about it
  /// cab: yaw_rad and pitch_rad are from the machine's design line of sight (Snapshot::Cab::sight), not from
  /// the cab's x axis
  bool from_sight = false;
  double fov_vertical_rad = 0.75;  ///< the aspect ratio comes from the image
  bool fov_from_sight = false;     ///< cab: the machine's design field of view instead
  bool hud = true;                 ///< the heads-up display on this view (one channel of several carries it)
  bool insets = true;              ///< cab: the insets (set_insets) on this view
  /// cab: the picture is a window fixed in front of the design eye (a desktop monitor `screen_distance_m`
  /// away): the tracked head moves the eye and skews the frustum through that window (off-axis projection)
  /// instead of turning the view.
  bool off_axis = false;
  double screen_distance_m = 0.6;
  /// off_axis: the tracked head's yaw and pitch turn the view by this many times as much (a head turned 20
  /// degrees looks 50 to the side, the monitor staying in front of it)
  double head_turn_gain = 2.5;
  /// cab: an asymmetric frustum, the angles of its left, right, bottom, top edges from the view axis [rad]
  /// (a cabin's projection screen off the eye's axis); empty: symmetric from fov_vertical_rad and the image.
  std::optional<std::array<double, 4>> frustum_rad;
  /// A pixel's width over its height: 2 where each eye's half of a side-by-side stereo frame is stretched
  /// back to the whole screen.
  double pixel_aspect = 1.0;
  /// Stereo: the eye moved along the view's right axis (+ half the eye separation for the right eye), the
  /// axes parallel, the frustum skewed so that the picture has no parallax at `convergence_m` (the screen).
  double eye_offset_m = 0.0;
  double convergence_m = 3.0;
  /// chase: from behind and above the machine; 0: as far as frames the machine whole (in fog no further than
  /// it shows through), else this far
  double chase_distance_m = 0.0;
  std::string camera;                         ///< kEntity: the camera's name in the look file
  core::Vec3 position_m{-40.0, -60.0, 40.0};  ///< kFree
};

/// The sun seen at local solar time t_h on a day of the year from a latitude (declination after Cooper
/// 1969): the direction towards it (x east, y north, z up) and its elevation [rad].
core::Vec3 sun_direction(double t_h, double day_of_year, double latitude_deg, double& elevation);
/// The moon (on the ecliptic, a mean synodic month): the direction towards it and the lit fraction of its
/// disc.
core::Vec3 moon_direction(double t_h, double day_of_year, double latitude_deg, double& illuminated);

/// A view by name: cab, chase, free, or a camera of the look file (as View::Kind::kEntity).
View view_named(const std::string& name);

/// The image generator: reads only a SceneDescription (once) and Snapshots (every frame), and draws the
/// looks the visual data give each entity's key; no machine-specific code. Headless (EGL) for tests,
/// screenshots and videos.
/// Whether an OpenGL renderer string names a software rasterizer (Mesa's llvmpipe, softpipe, swrast).
bool software_renderer(const std::string& renderer);

class ImageGenerator {
 public:
  /// `multisamples`: anti-aliasing samples per pixel of the picture (a multisampled pbuffer, resolved as it
  /// is read; the platform's most up to it); unset, kDefaultMultisamples except on a software renderer,
  /// which draws each sample on the CPU.
  ImageGenerator(const scene::SceneDescription& scene, std::map<std::string, Visual> visuals, int width,
                 int height, std::optional<int> multisamples = std::nullopt);
  static constexpr int kDefaultMultisamples = 4;
  ~ImageGenerator();

  /// Floodlights lit while the sun is below the horizon: the quay's, and the lamps on entities in the scene
  /// while the machine's supply is on (not in a power failure); the first kFloodlightSlots of those, in
  /// order.
  void set_floodlights(const std::vector<Floodlight>& lights);
  /// Cables hanging in loops between entities (a trolley's festoon), redrawn as they move; replaces those
  /// set before.
  void set_festoons(const std::vector<Festoon>& festoons);
  /// Hydraulic jacks between entities (a reach stacker's lift cylinders), redrawn as they move; replaces
  /// those set before.
  void set_jacks(const std::vector<Jack>& jacks);
  static constexpr std::size_t kFloodlightSlots = 7;  ///< OpenGL's eight lights, one of them the sun
  /// Everything a look file gives beyond the looks: the HUD and the floodlights.
  void use(const Looks& looks) {
    set_hud(looks.hud);
    set_floodlights(looks.floodlights);
    set_festoons(looks.festoons);
    set_jacks(looks.jacks);
    set_scenery(looks.scenery);
    cameras_ = looks.cameras;
    set_insets(looks.insets);
  }
  /// Cameras' pictures set into the view (a cab's monitors and mirrors): those whose camera rides an entity
  /// of this scene, each drawn every frame into its rectangle (replaces those set before; none: no insets).
  void set_insets(const std::vector<Inset>& insets);
  /// The insets drawn (those of set_insets() that this scene has).
  std::vector<Inset> insets() const;
  /// Where a world point shows in inset `n` (pixels of the whole picture from its top-left, mirrored as the
  /// inset is), if it is in front of that camera and within the inset.
  std::optional<std::pair<double, double>> project_inset(std::size_t n, const core::Vec3& world) const;
  /// The harbour's fixed parts (replaces those set before).
  void set_scenery(const std::vector<SceneryPart>& parts);
  /// The names of the views it can take: cab, chase, free and the look file's cameras.
  std::vector<std::string> view_names() const;
  /// The heads-up display's lines (none by default).
  void set_hud(std::vector<HudItem> items) { hud_items_ = std::move(items); }
  /// Text over the middle of the picture on a dark panel (the station's key list); "" for none.
  void set_overlay(const std::string& text);
  /// Entity `index` is now `name` (a box handed over onto this station's load: its livery and the code on its
  /// sides follow its id); a part that turns or rolls with the machine keeps its name.
  void rename_entity(std::size_t index, const std::string& name);
  /// A caption under the HUD, set by the application (a debrief's latest events); "" for none.
  void set_caption(const std::string& caption) { caption_ = caption; }
  /// A moment on the timeline bar, in its colour.
  struct TimelineMark {
    double time_s = 0.0;
    core::Vec3 color{1.0, 0.2, 0.2};
  };
  /// A bar along the foot of the picture (debrief videos): the span from..to, filled up to the published
  /// time, a tick at each mark. Empty span: no bar.
  void set_timeline(double from_s, double to_s, std::vector<TimelineMark> marks);
  /// The HUD's text as last drawn (tests).
  const std::string& hud_text() const { return hud_line_; }
  /// Entity poses, ropes and the environment (sun, sky, fog) from the published state.
  void update(const scene::Snapshot& snapshot);
  /// Bulk material from its published view: re-meshes only the tiles whose version moved on (the first
  /// call meshes them all) and draws the material in flight as points. The look key "bulk" colours it.
  void update_bulk(const scene::BulkView& view);
  /// Bulk tiles meshed so far (tests, the benchmark).
  long bulk_tiles_meshed() const { return bulk_tiles_meshed_; }
  void set_view(const View& view);
  /// Draws one frame and returns it (RGB, bottom row first as OpenGL reads it).
  /// The rain streaks over the last picture (pixels, y up from the bottom): from where each fades in to where
  /// it is brightest, pointing the way the drops fall across the picture.
  std::vector<std::pair<osg::Vec3, osg::Vec3>> rain_streaks() const;
  const osg::Image& render();
  /// The last frame drawn.
  const osg::Image& render_result() const { return *image_; }
  /// Writes the last frame as a PNG; false if it could not be written.
  bool write_png(const std::string& path) const;
  /// Places the camera for the view and the published state as the next frame will (project() then answers
  /// for that frame without drawing it).
  void aim() {
    place_camera();
    place_insets();
  }
  /// Where a world point lands in the image (pixels from the top-left), if in front of the camera.
  std::optional<std::pair<double, double>> project(const core::Vec3& world) const;
  std::string renderer() const;
  /// Shadow edges filtered (3x3 percentage-closer taps) rather than one lookup: on by default except on a
  /// software renderer (software_renderer()), where the nine taps cost a 1280x720 frame ~40 % more.
  void set_soft_shadows(bool on);
  bool soft_shadows() const;
  /// Surfaces with detail (ig/Materials.h: blotches, grain, streaks from a noise texture) rather than plain:
  /// on by default except on a software renderer, where they cost a 1280x720 cab frame ~35 % more.
  void set_surface_detail(bool on);
  bool surface_detail() const;
  /// Samples per pixel the picture is drawn with (0: one, aliased).
  int multisamples() const;
  /// How far each rolling tyre has turned about its axle [rad, within one turn], in the order of the scene's
  /// entities and their looks' parts.
  std::vector<double> tyre_angles() const;

 private:
  void build(const scene::SceneDescription& scene);
  void build_lighting();
  void build_sky();
  void build_quay_and_water();
  void build_entities(const scene::SceneDescription& scene);
  void draw_entity(osg::MatrixTransform& transform, const scene::SceneDescription::Entity& e,
                   const std::vector<std::string>& indicators);
  void build_ropes(const scene::SceneDescription& scene);
  void build_hud(const scene::SceneDescription& scene);
  void build_near_rain();
  void build_spray();
  void build_lamp_glows();
  void update_entities(const scene::Snapshot& s);
  void update_ropes(const scene::Snapshot& s);
  void update_festoons();
  void update_jacks();
  void update_sky_and_weather(const scene::Snapshot& s);
  void update_floodlights(const scene::Snapshot& s);
  void update_hud(const scene::Snapshot& s);
  void place_camera();
  /// The pose of camera `camera` (of cameras_) on its entity: its eye, look and up, world frame; nullopt when
  /// the scene has no such entity.
  struct CameraPose {
    core::Vec3 eye, look, up;
  };
  std::optional<CameraPose> camera_pose(const EntityCamera& camera) const;
  void place_insets();
  // the water round the eye: swell plus the wind sea, shaded by its Fresnel reflection of the sky
  void update_water(const osg::Vec3d& eye);
  void update_night_sky(const scene::Snapshot& s, const SkyShade& shade);
  void build_clouds();
  // the cloud deck's density (its shader's two octaves of the noise texture) at a deck point [m]
  double cloud_density(double x_m, double y_m) const;
  osg::ref_ptr<osg::Geode> clouds_;
  // threshold, deck shift, light, dark, horizon, edge, depth, to the sun, rim light
  std::array<osg::ref_ptr<osg::Uniform>, 9> cloud_uniforms_;
  std::pair<double, double> cloud_drift_m_{0.0, 0.0};
  osg::ref_ptr<osg::Texture2D> cloud_texture_;  // the deck's density: the clouds' and their shade's
  osg::ref_ptr<osg::Uniform> cloud_deck_;       // the lit shaders': threshold, half opaque, drift
  std::vector<double> cloud_densities_;         // the deck's densities over a tile, sorted: cover's threshold
  double sun_clouded_ = 0.0;                    // how much a cloud hides the sun over the cab
  void mesh_bulk_tile(const scene::BulkView::Grid& grid, int ti, int tj, osg::Geometry& tile);

  std::map<std::string, Visual> visuals_;
  int width_, height_;
  std::unique_ptr<HeadlessContext> context_;
  std::unique_ptr<osgViewer::Viewer> viewer_;
  osg::ref_ptr<osg::Group> root_;
  osg::ref_ptr<osgShadow::ShadowedScene> shadowed_;  // the quay and the entities, in the sun's shadows
  osg::ref_ptr<osg::Uniform> soft_shadows_;
  // the multisampled framebuffer drawn into and the plain one it is resolved into, and their renderbuffers
  // (colour and depth, colour): 0 when the picture is drawn straight into the pbuffer
  int multisamples_ = 0;
  std::array<unsigned, 2> framebuffers_{};
  std::array<unsigned, 3> renderbuffers_{};
  void draw_multisampled(int samples);
  void read_multisampled();
  osg::ref_ptr<osg::Group> unshadowed_;  // the same nodes without them: the insets draw these
  void add_lit(osg::Node* node);         // to both
  void remove_lit(osg::Node* node);
  struct BulkGridNode {
    osg::ref_ptr<osg::MatrixTransform> frame;
    std::vector<osg::ref_ptr<osg::Geometry>> tiles;
    std::vector<std::uint32_t> versions;  // as last meshed
  };
  std::vector<BulkGridNode> bulk_grids_;
  osg::ref_ptr<osg::Geometry> parcels_;
  long bulk_tiles_meshed_ = 0;
  osg::ref_ptr<osg::Uniform> floodlights_on_;
  std::vector<osg::ref_ptr<osg::MatrixTransform>> entities_;
  std::unique_ptr<ModelCache> models_;
  scene::SceneDescription description_;  // as built, with the entities renamed since
  std::vector<osg::ref_ptr<osg::Geometry>> ropes_;
  osg::ref_ptr<osg::Fog> fog_;
  osg::ref_ptr<osg::MatrixTransform> sky_;       // the dome, centred on the eye
  osg::ref_ptr<osg::Vec3Array> sky_directions_;  // unit directions of its vertices
  osg::ref_ptr<osg::Vec4Array> sky_colors_;
  static constexpr int kMoonRings = 6, kMoonSegments = 24;
  std::vector<std::array<double, 3>> star_positions_;  // right ascension, declination, brightness
  osg::ref_ptr<osg::Geometry> stars_, moon_;
  osg::ref_ptr<osgParticle::PrecipitationEffect> rain_;
  // the rain falling close past the eye, drawn over the picture as streaks towards where the drops fall
  osg::ref_ptr<osg::Camera> near_rain_;
  osg::ref_ptr<osg::Geometry> streaks_;
  osg::ref_ptr<osg::Geode> spray_;       // puffs blown off the crests in a gale
  osg::ref_ptr<osg::Geode> lamp_glows_;  // the lit lamps seen at night
  double rain_mm_per_h_ = 0.0;
  void update_near_rain(const osg::Vec3d& eye);
  osg::ref_ptr<osg::Uniform> wetness_;   // rain's water on the lit surfaces (the quay's film too)
  osg::ref_ptr<osg::Uniform> sun_seen_;  // the share of the sun's disc that shows: its glint
  /// the lit scene's programs by [wet][detail]: the water film (the quay takes it while wet), surface detail
  // by wet film, surface detail, clouds' shade
  std::array<std::array<std::array<osg::ref_ptr<osg::Program>, 2>, 2>, 2> lit_programs_;
  bool cloud_shade_ = false;  // fair-weather cloud in the sky: the lit programs shade under it
  bool surface_detail_ = false;
  std::vector<osg::ref_ptr<osg::StateSet>> quay_states_;  // take it while the quay is wet
  std::array<osg::ref_ptr<osg::Uniform>, 4> film_;        // splash rate, time, the sky's horizon and zenith
  osg::ref_ptr<osg::Geometry> water_;
  osg::ref_ptr<osg::StateSet> water_shading_;  // its shader's uniforms
  osg::ref_ptr<osg::MatrixTransform> far_water_;
  std::unique_ptr<OceanPatch> wind_sea_;
  double wind_sea_speed_mps_ = -1.0;                   // the wind the patch was synthesised for
  std::vector<std::pair<double, double>> water_base_;  // the water grid's points on the still level
  scene::Snapshot::Sea sea_{};
  core::Vec3 wind_mps_, to_sun_{0.0, 0.0, 1.0};
  double time_s_ = 0.0, daylight_ = 1.0;
  std::vector<osg::ref_ptr<osg::LightSource>> floodlights_;  // the slots, lit in update()
  std::vector<Floodlight> floodlight_settings_;
  osg::ref_ptr<osg::Group> scenery_;
  osg::ref_ptr<osg::Group> masts_;  // the quay floodlights' masts
  osg::ref_ptr<osg::LightSource> sun_;
  osg::ref_ptr<osg::Image> image_;
  osg::ref_ptr<osgText::Text> hud_, alarm_, overlay_;
  osg::ref_ptr<osg::Camera> hud_camera_;
  osg::ref_ptr<osg::Group> frame_;  // what is drawn: the world (root_), the insets' cameras, the HUD
  struct InsetView {
    Inset inset;
    EntityCamera camera;
    int width = 0, height = 0;         // its picture [pixels]
    osg::ref_ptr<osg::Camera> render;  // draws the world into its texture before the frame
  };
  std::vector<InsetView> insets_;
  osg::ref_ptr<osg::Geode> inset_quads_;  // the insets' pictures, under the HUD's lines
  std::vector<HudItem> hud_items_;
  std::vector<std::string> indicators_;
  struct TurningPart {  // a look's part turning with an indicator (VisualPart::turn), or a tyre rolling
    osg::ref_ptr<osg::MatrixTransform> transform;
    osg::Matrixd placed;  // where it stands unturned, in its entity's frame
    PartTurn turn;
    int indicator = -1;        // its index among the scene's indicators (-1: it does not turn)
    int speed_indicator = -1;  // rolling: the speed's index (-1: it does not roll)
    double rolls_unit_mps = 1.0;
    osg::Vec3d roll_axis;  // about which a positive speed rolls it (its frame)
    double radius_m = 1.0;
    double rolled_rad = 0.0;   // the wheel's angle so far, within a turn
    osg::Vec3d pivot;          // where it turns about, from its origin (its frame)
    int slide_indicator = -1;  // sliding: the indicator's index (-1: it does not slide)
    PartSlide slide;
  };
  std::vector<TurningPart> turning_parts_;
  double rolled_at_s_ = -1.0;                // the snapshot time the tyres last rolled to
  std::string machine_;                      // the scene's machine (its kind)
  std::vector<std::string> entity_visuals_;  // visual key by entity index
  std::vector<core::Pose> entity_poses_;     // as last published
  std::vector<Festoon> festoon_settings_;
  osg::ref_ptr<osg::Geode> ropes_geode_;               // the ropes and the festoons (lines, unlit, fogged)
  std::vector<osg::ref_ptr<osg::Geometry>> festoons_;  // by festoon_settings_, built with the ropes
  struct DrawnJack {
    Jack jack;
    std::size_t from = 0, to = 0;  // its ends' entities
    osg::ref_ptr<osg::MatrixTransform> barrel, rod;
  };
  std::vector<DrawnJack> jacks_;
  osg::ref_ptr<osg::Group> jacks_group_;
  // the machine's entities' boxes in their frames (from their looks' parts), a chase view frames them
  std::vector<std::pair<core::Vec3, core::Vec3>> machine_boxes_;  // centre, half size
  double visibility_m_ = 20000.0;
  std::vector<EntityCamera> cameras_;
  std::string hud_line_;
  std::string caption_;
  double timeline_from_s_ = 0.0, timeline_to_s_ = 0.0;
  std::vector<TimelineMark> timeline_marks_;
  osg::ref_ptr<osg::Geometry> timeline_;
  std::unique_ptr<SignalPanel> signal_panel_;
  void update_timeline(double now_s);
  View view_;
  scene::Snapshot::Cab cab_{};
  double sun_elevation_ = 1.0;
  double overcast_ = 0.0, grey_ = 0.0;  // rain cloud over the sun; the sky's greying by cloud and fog
  double foam_slope_ = 0.0;             // the wind sea's slope past which it breaks (whitecaps)
  std::vector<double> foam_samples_;    // the patch's slopes, to find it
};

}  // namespace harbour::ig
