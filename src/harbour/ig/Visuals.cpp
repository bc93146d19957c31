#include "harbour/ig/Visuals.h"

#include <osgDB/ReadFile>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "harbour/ig/Models.h"
#include "harbour/io/MachineDataFiles.h"
#include "harbour/io/YamlFile.h"

namespace harbour::ig {

namespace {
core::Vec3 color_of(const io::YamlFile& f, const YAML::Node& node, const std::string& field) {
  const core::Vec3 c = f.vector3(node, field, 1e3);  // read wide, then said as a colour
  for (const double v : {c.x, c.y, c.z})
    if (!(v >= 0.0 && v <= 1.0)) f.fail(node, field, "colour components are 0-1 (linear RGB)");
  return c;
}
}  // namespace

osg::ref_ptr<osg::Node> read_mesh(const std::string& path) {
  osg::ref_ptr<osgDB::Options> options = new osgDB::Options("noRotation");
  return osgDB::readRefNodeFile(path, options.get());
}

bool HudItem::shown_on(const std::string& machine) const {
  return (machines.empty() || std::find(machines.begin(), machines.end(), machine) != machines.end()) &&
         std::find(except.begin(), except.end(), machine) == except.end();
}

std::map<std::string, Visual> load_visuals(const std::string& path) {
  return load_looks(path).visuals;
}

namespace {

// a part's `material` (ig/Materials.h), paint where it names none
Surface read_surface(const io::YamlFile& f, const YAML::Node& p, const std::string& at) {
  if (!f.optional(p, "material", at)) return Surface::kPaint;
  const std::string name = f.text(p, "material", at);
  const std::optional<Surface> surface = surface_named(name);
  if (!surface)
    f.fail(p["material"], at + ".material",
           "'" + name + "' is not a material: " + std::string(surface_names()));
  return *surface;
}

// one part of a look (`path`: the look file, where a mesh is found)
VisualPart read_part(const io::YamlFile& f, const YAML::Node& p, const std::string& pat,
                     const std::string& path, const Visual& visual) {
  VisualPart part;
  if (f.optional(p, "shape", pat)) {
    const std::string shape = f.text(p, "shape", pat);
    if (shape == "lattice")
      part.shape = VisualPart::Shape::kLattice;
    else if (shape == "container")
      part.shape = VisualPart::Shape::kContainer;
    else if (shape == "tyre")
      part.shape = VisualPart::Shape::kTyre;
    else if (shape == "shell")
      part.shape = VisualPart::Shape::kShell;
    else if (shape == "hull")
      part.shape = VisualPart::Shape::kHull;
    else if (shape == "mesh")
      part.shape = VisualPart::Shape::kMesh;
    else if (shape == "girder")
      part.shape = VisualPart::Shape::kGirder;
    else if (shape == "walkway")
      part.shape = VisualPart::Shape::kWalkway;
    else if (shape == "stairs")
      part.shape = VisualPart::Shape::kStairs;
    else if (shape == "cylinder")
      part.shape = VisualPart::Shape::kCylinder;
    else if (shape == "member")
      part.shape = VisualPart::Shape::kMember;
    else if (shape == "spreader")
      part.shape = VisualPart::Shape::kSpreader;
    else if (shape == "deckhouse")
      part.shape = VisualPart::Shape::kDeckhouse;
    else if (shape != "box")
      f.fail(
          p["shape"], pat + ".shape",
          "'" + shape +
              "' is not a shape: box, lattice, container, tyre, shell, hull, mesh, girder, walkway, stairs, "
              "cylinder, member, spreader or deckhouse");
  }
  if (part.shape == VisualPart::Shape::kMember) {
    // from one point to another, of a section [width, depth]: its centre and size follow
    const core::Vec3 from = f.vector3(f.required(p, "from", pat), pat + ".from", 1000.0);
    const core::Vec3 to = f.vector3(f.required(p, "to", pat), pat + ".to", 1000.0);
    const YAML::Node section = f.required(p, "section_m", pat);
    if (!section.IsSequence() || section.size() != 2)
      f.fail(section, pat + ".section_m", "expected [width, depth]");
    const double width = f.number_at(section[0], pat + ".section_m[0]"),
                 depth = f.number_at(section[1], pat + ".section_m[1]");
    const double length = core::length(to - from);
    if (!(width > 0.0 && depth > 0.0 && width < 10.0 && depth < 10.0))
      f.fail(section, pat + ".section_m", "width and depth are positive (under 10 m)");
    if (!(length > 1e-3)) f.fail(p["to"], pat + ".to", "a member's ends are apart");
    part.size_m = core::Vec3{length, width, depth};
    part.along = (to - from) * (1.0 / length);
    part.centre_m = (from + to) * 0.5;
  } else if (part.shape == VisualPart::Shape::kMesh) {
    const std::string file = f.text(p, "file", pat);
    part.mesh = (std::filesystem::path(path).parent_path() / file).lexically_normal().string();
    if (!std::filesystem::is_regular_file(part.mesh))
      f.fail(p["file"], pat + ".file", "no such file: " + part.mesh);
    if (!read_mesh(part.mesh))
      f.fail(p["file"], pat + ".file", "osgDB could not read a model from " + part.mesh);
    part.scale = f.number_or(p, "scale", pat, 1.0, 1e-3, 1e3);
  } else {
    const YAML::Node size = f.required(p, "size", pat);
    if (!(size.IsScalar() && size.Scalar() == "entity")) part.size_m = f.vector3(size, pat + ".size", 1000.0);
    if (part.size_m && (part.size_m->x <= 0 || part.size_m->y <= 0 || part.size_m->z <= 0))
      f.fail(size, pat + ".size", "every side must be positive");
  }
  if (part.shape == VisualPart::Shape::kTyre) {
    if (!part.size_m)
      f.fail(p["size"], pat + ".size", "a tyre's size is written out: its diameter twice and its width");
    if (tyre_axis(*part.size_m) < 0)
      f.fail(p["size"], pat + ".size", "a tyre has two equal sides (its diameter) and its width");
    if (f.optional(p, "rim_color", pat)) part.rim_color = color_of(f, p["rim_color"], pat + ".rim_color");
  }
  if (part.shape == VisualPart::Shape::kShell) {
    if (!part.size_m)
      f.fail(p["size"], pat + ".size", "a shell's size is written out: its reach, width and height");
    part.hinge_m = f.number_or(p, "hinge_m", pat, part.size_m->z, part.size_m->z, 100.0);
  }
  if (part.shape == VisualPart::Shape::kHull) {
    if (!part.size_m)
      f.fail(p["size"], pat + ".size", "a hull's size is written out: its beam, length and depth");
    part.waterline_m = f.number(p, "waterline_m", pat, 0.0, part.size_m->z);
    part.bottom_color = color_of(f, f.required(p, "bottom_color", pat), pat + ".bottom_color");
    if (f.optional(p, "deck_color", pat)) part.deck_color = color_of(f, p["deck_color"], pat + ".deck_color");
    if (f.optional(p, "deck_open_m", pat)) {
      const YAML::Node open = p["deck_open_m"];
      if (!open.IsSequence() || open.size() != 2)
        f.fail(open, pat + ".deck_open_m", "expected [from, to] along the hull's length");
      part.deck_open_from_m = f.number_at(open[0], pat + ".deck_open_m[0]");
      part.deck_open_to_m = f.number_at(open[1], pat + ".deck_open_m[1]");
      if (!(part.deck_open_from_m < part.deck_open_to_m))
        f.fail(open, pat + ".deck_open_m", "from lies before to");
    }
  }
  part.yaw_rad = f.number_or(p, "yaw_deg", pat, 0.0, -360.0, 360.0) * std::numbers::pi / 180.0;
  if (const auto turns = f.optional_map(p, "turns", pat)) {
    const std::string tat = pat + ".turns";
    PartTurn turn;
    turn.indicator = f.text(*turns, "with", tat);
    turn.axis = f.vector3(f.required(*turns, "axis", tat), tat + ".axis", 1.0);
    const double axis_length = core::length(turn.axis);
    if (!(axis_length > 1e-6)) f.fail((*turns)["axis"], tat + ".axis", "a direction, not zero");
    turn.axis = turn.axis * (1.0 / axis_length);
    turn.max_rad = f.number(*turns, "degrees", tat, -180.0, 180.0) * std::numbers::pi / 180.0;
    if (f.optional(*turns, "about", tat)) turn.pivot_m = f.vector3((*turns)["about"], tat + ".about", 1000.0);
    if (f.optional(*turns, "law", tat)) {
      const std::string law = f.text(*turns, "law", tat);
      if (law != "linear" && law != "arcsine")
        f.fail((*turns)["law"], tat + ".law", "'" + law + "' is not a law: linear or arcsine");
      turn.arcsine = law == "arcsine";
    }
    part.turn = turn;
  }
  if (const auto slides = f.optional_map(p, "slides", pat)) {
    const std::string sat = pat + ".slides";
    PartSlide slide;
    slide.indicator = f.text(*slides, "with", sat);
    slide.along = f.vector3(f.required(*slides, "along", sat), sat + ".along", 100.0);
    slide.from = f.number_or(*slides, "from", sat, 0.0, -1e6, 1e6);
    part.slide = slide;
  }
  if (part.shape == VisualPart::Shape::kSpreader) {
    if (f.optional(p, "telescopes_with", pat)) part.telescopes_with = f.text(p, "telescopes_with", pat);
    if (f.optional(p, "locks_with", pat)) part.locks_with = f.text(p, "locks_with", pat);
    if (f.optional(p, "flippers", pat)) {
      const YAML::Node flippers = f.sequence(p, "flippers", pat, 4);
      if (flippers.size() != 4)
        f.fail(flippers, pat + ".flippers", "four indicators, one a corner in the twistlocks' order");
      for (std::size_t c = 0; c < 4; ++c) {
        if (!flippers[c].IsScalar() || flippers[c].Scalar().empty())
          f.fail(flippers[c], pat + ".flippers[" + std::to_string(c) + "]", "expected an indicator's name");
        part.flippers.push_back(flippers[c].Scalar());
      }
    }
    part.twistlock_track_m = f.number_or(p, "twistlock_track_m", pat, 2.259, 0.5, 5.0);
    if (part.size_m && (part.size_m->y < 2.0 * part.size_m->x || part.twistlock_track_m > part.size_m->x))
      f.fail(p["size"], pat + ".size",
             "a spreader is longer (y) than twice its width (x), its twistlocks' track within its width");
    if (part.turn || part.slide || part.yaw_rad != 0.0)
      f.fail(p, pat, "a spreader's parts move by its own indicators: no turns, slides or yaw of its own");
  }
  if (part.shape == VisualPart::Shape::kDeckhouse &&
      (!part.size_m || part.size_m->z < 2.0 * kDeckHeight_m || part.size_m->x < 6.0 || part.size_m->y < 4.0))
    f.fail(p["size"], pat + ".size",
           "a deckhouse's size is written out: at least 6 m across (x), 4 m along (y) and two decks (5.6 m) "
           "high");
  if (const auto rolls = f.optional_map(p, "rolls", pat)) {
    if (part.shape != VisualPart::Shape::kTyre)
      f.fail(p["rolls"], pat + ".rolls", "only a tyre rolls (about its axle, by its radius)");
    part.rolls_with = f.text(*rolls, "with", pat + ".rolls");
    part.rolls_unit_mps = f.number_or(*rolls, "unit_mps", pat + ".rolls", 1.0, 1e-6, 1e3);
    if (f.optional(*rolls, "along", pat + ".rolls"))
      part.rolls_along = f.vector3((*rolls)["along"], pat + ".rolls.along", 1.0);
    const int axle = tyre_axis(*part.size_m);
    const core::Vec3 axle_direction{axle == 0 ? 1.0 : 0.0, axle == 1 ? 1.0 : 0.0, axle == 2 ? 1.0 : 0.0};
    const double along = core::length(part.rolls_along);
    if (axle == 2 || !(along > 1e-6) ||
        std::abs(core::dot(part.rolls_along, axle_direction)) > 1e-6 * along ||
        std::abs(part.rolls_along.z) > 1e-6 * along)
      f.fail(*rolls, pat + ".rolls.along", "a level direction across the tyre's axle (default [1, 0, 0])");
    part.rolls_along = part.rolls_along * (1.0 / along);
  }
  if (part.shape == VisualPart::Shape::kLattice) {
    part.bay_m = f.number_or(p, "bay_m", pat, 3.0, 0.2, 50.0);
    part.member_m = f.number_or(p, "member_m", pat, 0.25, 0.01, 2.0);
  }
  if (part.shape == VisualPart::Shape::kGirder) part.bay_m = f.number_or(p, "bay_m", pat, 3.0, 0.5, 50.0);
  if ((part.shape == VisualPart::Shape::kCylinder) && (!part.size_m || tyre_axis(*part.size_m) < 0))
    f.fail(p["size"], pat + ".size",
           "a cylinder's size is written out: two equal sides (its diameter), its length");
  if (part.shape == VisualPart::Shape::kWalkway) {
    if (!part.size_m)
      f.fail(p["size"], pat + ".size",
             "a walkway's size is written out: its deck and its guard-rails' height");
    if (f.optional(p, "rails", pat)) {
      const std::string rails = f.text(p, "rails", pat);
      if (rails == "positive")
        part.rails = RailSides::kPlus;
      else if (rails == "negative")
        part.rails = RailSides::kMinus;
      else if (rails == "none")
        part.rails = RailSides::kNone;
      else if (rails != "both")
        f.fail(p["rails"], pat + ".rails",
               "'" + rails + "' is not a side: both, positive, negative or none (across the walkway)");
    }
  }
  if (part.shape == VisualPart::Shape::kStairs) {
    if (!part.size_m)
      f.fail(p["size"], pat + ".size", "a flight's size is written out: its run, width and height");
    const double run = part.size_m->x, height = part.size_m->z;
    const double pitch_deg = std::atan2(height, run) * 180.0 / std::numbers::pi;
    const int rises = stair_rises(run, height);
    const double stride = (run + 2.0 * height) / rises;
    if (pitch_deg > access::kSteepestStair_deg || pitch_deg < access::kFlattestStair_deg ||
        stride < access::kStepLengthLow_m - 1e-9 || stride > access::kStepLengthHigh_m + 1e-9) {
      std::ostringstream what;
      what << std::setprecision(3) << "a flight " << run << " m long and " << height << " m high ("
           << pitch_deg
           << " deg) has no steps of EN ISO 14122-3 (pitch 20-45 deg, rise at most 0.25 m, going "
           << "+ 2 rises 0.60-0.66 m)";
      f.fail(p["size"], pat + ".size", what.str());
    }
  }
  if (part.shape != VisualPart::Shape::kMember)
    part.centre_m = f.vector3(f.required(p, "at", pat), pat + ".at", 1000.0);
  part.solid = f.flag(p, "solid", pat, false);
  if (part.solid &&
      (part.shape != VisualPart::Shape::kBox || !part.size_m || part.turn || part.yaw_rad != 0.0))
    f.fail(p["solid"], pat + ".solid", "only a fixed box with its size written out is solid");
  part.surface = read_surface(f, p, pat);
  const YAML::Node color = f.required(p, "color", pat);
  if (color.IsScalar() && color.Scalar() == "livery") {
    if (visual.liveries.empty()) f.fail(color, pat + ".color", "a livery colour needs the look's liveries");
    part.livery = true;
  } else {
    part.color = color_of(f, color, pat + ".color");
  }
  return part;
}

// "hud[3]" at the file's root, "looks.hud[3]" in a machine file's looks
std::string item_path(const std::string& section, const char* list, std::size_t n) {
  return (section.empty() ? std::string(list) : section + "." + list) + "[" + std::to_string(n) + "]";
}

// the heads-up display's lines
std::vector<HudItem> read_hud(const io::YamlFile& f, const YAML::Node& section, const std::string& path) {
  std::vector<HudItem> lines;
  if (f.optional(section, "hud", path)) {
    const YAML::Node hud = f.sequence(section, "hud", path, 32);
    for (std::size_t n = 0; n < hud.size(); ++n) {
      const std::string at = item_path(path, "hud", n);
      HudItem item;
      item.indicator = f.text(hud[n], "indicator", at);
      item.label = f.text(hud[n], "label", at);
      if (f.optional(hud[n], "unit", at)) item.unit = f.text(hud[n], "unit", at);
      item.decimals = f.optional(hud[n], "decimals", at) ? f.integer(hud[n], "decimals", at, 0, 6) : 1;
      item.lamp = f.flag(hud[n], "lamp", at, false);
      item.scale = f.number_or(hud[n], "scale", at, 1.0, -1e6, 1e6);
      if (f.optional(hud[n], "words", at)) {
        const YAML::Node words = f.sequence(hud[n], "words", at, 16);
        for (std::size_t k = 0; k < words.size(); ++k) {
          if (!words[k].IsScalar()) f.fail(words[k], at + ".words", "expected a word");
          item.words.push_back(words[k].Scalar());
        }
        item.words_from =
            f.optional(hud[n], "words_from", at) ? f.integer(hud[n], "words_from", at, -100, 100) : 0;
      }
      if (f.optional(hud[n], "shown_while", at)) item.shown_while = f.text(hud[n], "shown_while", at);
      lines.push_back(item);
    }
  }
  return lines;
}

// floodlights and the machines' lamps
void read_floodlights(const io::YamlFile& f, const YAML::Node& section, const std::string& path,
                      Looks& looks) {
  if (f.optional(section, "floodlights", path)) {
    // any number: the image generator lights the first seven that are in the scene (OpenGL's eight lights)
    const YAML::Node lights = f.sequence(section, "floodlights", path, 64);
    for (std::size_t n = 0; n < lights.size(); ++n) {
      const std::string at = item_path(path, "floodlights", n);
      Floodlight light;
      light.position_m = f.vector3(f.required(lights[n], "at", at), at + ".at", 2000.0);
      if (f.optional(lights[n], "entity", at)) light.entity = f.text(lights[n], "entity", at);
      light.color = color_of(f, f.required(lights[n], "color", at), at + ".color");
      light.range_m = f.number(lights[n], "range_m", at, 5.0, 500.0);
      light.mast = f.flag(lights[n], "mast", at, false);
      if (light.mast && (!light.entity.empty() || light.position_m.z < 5.0))
        f.fail(lights[n]["mast"], at + ".mast",
               "a light mast stands on the quay under a lamp at least 5 m up");
      looks.floodlights.push_back(light);
    }
  }
}

// cameras riding entities
void read_cameras(const io::YamlFile& f, const YAML::Node& section, const std::string& path, Looks& looks) {
  if (f.optional(section, "cameras", path)) {
    const YAML::Node cameras = f.sequence(section, "cameras", path, 16);
    for (std::size_t n = 0; n < cameras.size(); ++n) {
      const std::string at = item_path(path, "cameras", n);
      EntityCamera c;
      c.name = f.text(cameras[n], "name", at);
      if (std::any_of(looks.cameras.begin(), looks.cameras.end(),
                      [&](const EntityCamera& other) { return other.name == c.name; }))
        f.fail(cameras[n]["name"], at + ".name", "a camera '" + c.name + "' is declared already");
      c.entity = f.text(cameras[n], "entity", at);
      c.at_m = f.vector3(f.required(cameras[n], "at", at), at + ".at", 1000.0);
      c.look = f.vector3(f.required(cameras[n], "look", at), at + ".look", 1.0);
      if (f.optional(cameras[n], "up", at)) c.up = f.vector3(cameras[n]["up"], at + ".up", 1.0);
      c.fov_vertical_rad =
          f.number(cameras[n], "fov_vertical_deg", at, 5.0, 150.0) * 3.141592653589793 / 180.0;
      if (std::abs(c.look.x) + std::abs(c.look.y) + std::abs(c.look.z) < 1e-6)
        f.fail(cameras[n]["look"], at + ".look", "a direction, not zero");
      looks.cameras.push_back(c);
    }
  }
}

// camera pictures set into the cab view (after the cameras)
void read_insets(const io::YamlFile& f, const YAML::Node& section, const std::string& path, Looks& looks) {
  if (f.optional(section, "insets", path)) {
    const YAML::Node insets = f.sequence(section, "insets", path, 32);
    for (std::size_t n = 0; n < insets.size(); ++n) {
      const std::string at = item_path(path, "insets", n);
      Inset inset;
      inset.camera = f.text(insets[n], "camera", at);
      if (std::none_of(looks.cameras.begin(), looks.cameras.end(),
                       [&](const EntityCamera& c) { return c.name == inset.camera; }))
        f.fail(insets[n]["camera"], at + ".camera", "no camera '" + inset.camera + "' in cameras");
      const YAML::Node rect = f.required(insets[n], "rect", at);
      if (!rect.IsSequence() || rect.size() != 4)
        f.fail(rect, at + ".rect", "expected [left, bottom, width, height] as shares of the picture");
      inset.left = f.number_at(rect[0], at + ".rect[0]");
      inset.bottom = f.number_at(rect[1], at + ".rect[1]");
      inset.width = f.number_at(rect[2], at + ".rect[2]");
      inset.height = f.number_at(rect[3], at + ".rect[3]");
      if (!(inset.left >= 0.0 && inset.bottom >= 0.0 && inset.width >= 0.05 && inset.height >= 0.05 &&
            inset.left + inset.width <= 1.0 && inset.bottom + inset.height <= 1.0))
        f.fail(rect, at + ".rect", "an inset lies within the picture and spans at least 0.05 of it each way");
      inset.mirror = f.flag(insets[n], "mirror", at, false);
      looks.insets.push_back(inset);
    }
  }
}

// the harbour's fixed parts
void read_scenery(const io::YamlFile& f, Looks& looks) {
  if (f.optional(f.root(), "scenery", "")) {
    const YAML::Node parts = f.sequence(f.root(), "scenery", "", 256);
    for (std::size_t n = 0; n < parts.size(); ++n) {
      const std::string at = "scenery[" + std::to_string(n) + "]";
      const YAML::Node p = parts[n];
      SceneryPart part;
      if (f.optional(p, "shape", at)) {
        const std::string shape = f.text(p, "shape", at);
        if (shape == "cylinder")
          part.shape = SceneryPart::Shape::kCylinder;
        else if (shape != "box")
          f.fail(p["shape"], at + ".shape", "'" + shape + "' is not a shape: box or cylinder");
      }
      part.centre_m = f.vector3(f.required(p, "at", at), at + ".at", 5000.0);
      part.size_m = f.vector3(f.required(p, "size", at), at + ".size", 5000.0);
      if (part.size_m.x <= 0 || part.size_m.y <= 0 || part.size_m.z <= 0)
        f.fail(p["size"], at + ".size", "sizes are positive");
      part.color = color_of(f, f.required(p, "color", at), at + ".color");
      part.surface = read_surface(f, p, at);
      if (f.optional(p, "repeat", at)) {
        part.repeat = f.integer(p, "repeat", at, 1, 500);
        part.step_m = f.vector3(f.required(p, "step", at), at + ".step", 1000.0);
      }
      looks.scenery.push_back(part);
    }
  }
}

// the looks by key (`path`: the look file, where meshes are found); `owner`: a machine file's kind, whose
// looks are its own entities' ("sts.gantry"), or "" for the harbour's file
void read_visuals(const io::YamlFile& f, const YAML::Node& section, const std::string& section_path,
                  const std::string& path, const std::string& owner, Looks& looks) {
  if (!owner.empty() && !f.optional(section, "visuals", section_path)) return;  // a machine's are optional
  std::map<std::string, Visual>& out = looks.visuals;
  const YAML::Node list = f.sequence(section, "visuals", section_path, 1000);
  for (std::size_t n = 0; n < list.size(); ++n) {
    const std::string at = item_path(section_path, "visuals", n);
    const YAML::Node v = list[n];
    const std::string key = f.text(v, "key", at);
    if (!owner.empty() && key.rfind(owner + ".", 0) != 0)
      f.fail(v["key"], at + ".key",
             "a " + owner + "'s file gives its own looks: '" + owner + ".<part>', not '" + key + "'");
    if (out.count(key)) f.fail(v["key"], at + ".key", "'" + key + "' is declared twice");
    Visual visual;
    if (f.optional(v, "liveries", at)) {
      const YAML::Node liveries = f.sequence(v, "liveries", at, 64);
      for (std::size_t k = 0; k < liveries.size(); ++k)
        visual.liveries.push_back(color_of(f, liveries[k], at + ".liveries[" + std::to_string(k) + "]"));
    }
    visual.name_marked = f.flag(v, "name_marked", at, false);
    const YAML::Node parts = f.sequence(v, "parts", at, 256);
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const std::string pat = at + ".parts[" + std::to_string(k) + "]";
      const VisualPart part = read_part(f, parts[k], pat, path, visual);
      // `repeat` copies `step` apart
      const bool repeated = f.optional(parts[k], "repeat", pat).has_value();
      const int copies = repeated ? f.integer(parts[k], "repeat", pat, 1, 200) : 1;
      const core::Vec3 step =
          repeated ? f.vector3(f.required(parts[k], "step", pat), pat + ".step", 1000.0) : core::Vec3{};
      for (int copy = 0; copy < copies; ++copy) {  // each copy with its own pivot
        VisualPart& placed = visual.parts.emplace_back(part);
        placed.centre_m = part.centre_m + step * static_cast<double>(copy);
        if (placed.turn && placed.turn->pivot_m) *placed.turn->pivot_m += step * static_cast<double>(copy);
      }
    }
    out[key] = visual;
  }
}

// an end of a festoon or a jack (`key`: from or to) riding one of the machine's own entities (`what`: the
// thing and its verb, for the error)
void read_end(const io::YamlFile& f, const YAML::Node& item, const std::string& at, const char* key,
              const std::string& kind, const std::string& what, std::string& entity, core::Vec3& position) {
  const std::string eat = at + "." + key;
  const YAML::Node node = f.required(item, key, at);
  entity = f.text(node, "entity", eat);
  if (entity.rfind(kind + ".", 0) != 0)
    f.fail(node["entity"], eat + ".entity",
           "a " + kind + "'s " + what + " its own entities ('" + kind + ".<part>')");
  position = f.vector3(f.required(node, "at", eat), eat + ".at", 1000.0);
}

// a machine's festoons (`looks.festoons`), each end riding one of its own entities
void read_festoons(const io::YamlFile& f, const YAML::Node& section, const std::string& kind, Looks& looks) {
  if (!f.optional(section, "festoons", "looks")) return;
  const YAML::Node festoons = f.sequence(section, "festoons", "looks", 16);
  for (std::size_t n = 0; n < festoons.size(); ++n) {
    const std::string at = item_path("looks", "festoons", n);
    Festoon festoon;
    read_end(f, festoons[n], at, "from", kind, "festoon hangs from", festoon.from_entity, festoon.from_m);
    read_end(f, festoons[n], at, "to", kind, "festoon hangs from", festoon.to_entity, festoon.to_m);
    festoon.carriers = f.integer(festoons[n], "carriers", at, 1, 100);
    festoon.loop_m = f.number(festoons[n], "loop_m", at, 0.2, 50.0);
    festoon.cables = f.optional(festoons[n], "cables", at) ? f.integer(festoons[n], "cables", at, 1, 8) : 1;
    looks.festoons.push_back(festoon);
  }
}

// a machine's hydraulic jacks (`looks.jacks`), each end riding one of its own entities
void read_jacks(const io::YamlFile& f, const YAML::Node& section, const std::string& kind, Looks& looks) {
  if (!f.optional(section, "jacks", "looks")) return;
  const YAML::Node jacks = f.sequence(section, "jacks", "looks", 16);
  for (std::size_t n = 0; n < jacks.size(); ++n) {
    const std::string at = item_path("looks", "jacks", n);
    Jack jack;
    read_end(f, jacks[n], at, "from", kind, "jack joins", jack.from_entity, jack.from_m);
    read_end(f, jacks[n], at, "to", kind, "jack joins", jack.to_entity, jack.to_m);
    jack.barrel_m = f.number(jacks[n], "barrel_m", at, 0.1, 50.0);
    jack.rod_m = f.number(jacks[n], "rod_m", at, 0.1, 50.0);
    if (jack.rod_m > jack.barrel_m + 0.2)
      f.fail(jacks[n]["rod_m"], at + ".rod_m", "a jack's rod retracts into its barrel: at most 0.2 m longer");
    jack.diameter_m = f.number(jacks[n], "diameter_m", at, 0.02, 2.0);
    jack.color = color_of(f, f.required(jacks[n], "color", at), at + ".color");
    looks.jacks.push_back(jack);
  }
}

// A machine file's looks (`looks`: its entities' looks, its lamps, cameras, camera insets and HUD lines)
// into `looks`; the HUD lines its own, shown before the harbour's and in place of one for the same indicator.
void read_machine_looks(const io::YamlFile& f, const std::string& kind, Looks& looks) {
  const std::optional<YAML::Node> section = f.optional_map(f.root(), "looks", "");
  if (!section) return;
  read_visuals(f, *section, "looks", f.name(), kind, looks);
  const std::size_t lights = looks.floodlights.size(), cameras = looks.cameras.size();
  read_floodlights(f, *section, "looks", looks);
  read_cameras(f, *section, "looks", looks);
  const auto owned = [&](const std::string& entity) { return entity.rfind(kind + ".", 0) == 0; };
  for (std::size_t n = lights; n < looks.floodlights.size(); ++n)
    if (!owned(looks.floodlights[n].entity))
      f.fail((*section)["floodlights"][n - lights], item_path("looks", "floodlights", n - lights) + ".entity",
             "a " + kind + "'s lamp rides one of its own entities ('" + kind + ".<part>')");
  for (std::size_t n = cameras; n < looks.cameras.size(); ++n)
    if (!owned(looks.cameras[n].entity))
      f.fail((*section)["cameras"][n - cameras], item_path("looks", "cameras", n - cameras) + ".entity",
             "a " + kind + "'s camera rides one of its own entities ('" + kind + ".<part>')");
  read_insets(f, *section, "looks", looks);
  read_festoons(f, *section, kind, looks);
  read_jacks(f, *section, kind, looks);
  std::vector<HudItem> own = read_hud(f, *section, "looks");
  for (HudItem& line : own) {
    line.machines = {kind};
    for (HudItem& shared : looks.hud)
      if (shared.machines.empty() && shared.indicator == line.indicator) shared.except.push_back(kind);
  }
  looks.hud.insert(looks.hud.begin(), own.begin(), own.end());
  f.check_unknown_keys(*section, "looks");
}

}  // namespace

Looks load_looks(const std::string& path) {
  const io::YamlFile f = io::YamlFile::load(path);
  Looks looks;
  read_visuals(f, f.root(), "", path, "", looks);
  looks.hud = read_hud(f, f.root(), "");
  read_floodlights(f, f.root(), "", looks);
  read_cameras(f, f.root(), "", looks);
  read_insets(f, f.root(), "", looks);
  read_scenery(f, looks);
  f.check_unknown_keys();
  return looks;
}

Looks load_looks(const std::string& path, const std::vector<std::string>& machine_files) {
  Looks looks = load_looks(path);
  for (const io::MachineDataFile& machine : io::load_machine_data_files(machine_files))
    read_machine_looks(machine.file, machine.kind, looks);
  return looks;
}

Looks load_shipped_looks(const std::string& data_folder, std::span<const std::string_view> kinds,
                         const std::string& machine_file) {
  return load_looks(data_folder + "/visuals/harbour.yaml",
                    io::machine_data_files(data_folder, kinds, machine_file));
}

}  // namespace harbour::ig

namespace harbour::ig {

namespace {
constexpr double kTwentyFoot_m = 6.058;       // ISO 668: the shortest a telescopic spreader closes to
constexpr double kCastingFromEnd_m = 0.1035;  // ISO 1161: a casting's aperture centre from the box's end
constexpr double kHeadBeamAlong_m = 0.5;      // an end's head beam, along the spreader
constexpr double kFlipperArm_m = 0.5, kFlipperDepth_m = 0.4, kFlipperPlate_m = 0.05, kFlipperGap_m = 0.015;
}  // namespace

std::vector<VisualPart> spreader_parts(const VisualPart& spreader, const core::Vec3& size_m) {
  const double w = size_m.x, length = size_m.y, h = size_m.z;
  const double bottom = spreader.centre_m.z - h / 2.0;
  const core::Vec3 centre = spreader.centre_m;
  std::vector<VisualPart> parts;
  const auto part = [&](VisualPart::Shape shape, const core::Vec3& size,
                        const core::Vec3& at) -> VisualPart& {
    VisualPart p;
    p.shape = shape;
    p.size_m = size;
    p.centre_m = at;
    p.color = spreader.color;
    p.livery = spreader.livery;
    p.surface = spreader.surface;
    parts.push_back(p);
    return parts.back();
  };
  // the main frame: a box girder along it between the head beams closed to 20 ft, its power pack and junction
  // box on top
  const double main_length = std::min(length, kTwentyFoot_m) - 2.0 * kHeadBeamAlong_m - 0.1;
  VisualPart& frame = part(VisualPart::Shape::kGirder, {w - 0.3, main_length, 0.8 * h},
                           centre + core::Vec3{0.0, 0.0, 0.1 * h});
  frame.bay_m = 1.0;
  part(VisualPart::Shape::kBox, {0.8, 0.7, 0.35},
       centre + core::Vec3{0.45, 0.5 * main_length - 0.45, 0.5 * h + 0.175});
  part(VisualPart::Shape::kBox, {0.6, 0.4, 0.3},
       centre + core::Vec3{-0.5, -0.5 * main_length + 0.3, 0.5 * h + 0.15});
  // a part of the end at `end` (+1 or -1 along y): it slides out with the published length, half of its
  // change each way
  const auto sliding = [&](VisualPart& p, double end) -> VisualPart& {
    if (!spreader.telescopes_with.empty())
      p.slide = PartSlide{spreader.telescopes_with, {0.0, 0.5 * end, 0.0}, length};
    return p;
  };
  const auto bare_steel = [](VisualPart& p) -> VisualPart& {  // a twistlock's cone and head
    p.surface = Surface::kSteel;
    p.color = {0.55, 0.55, 0.55};
    p.livery = false;
    return p;
  };
  // two telescopic beams an end, staggered across from the other end's, back into the main frame
  const double beam_length = kTwentyFoot_m / 2.0 - kHeadBeamAlong_m + main_length / 2.0 - 0.05;
  const double beam_inner = length / 2.0 - kHeadBeamAlong_m - beam_length;
  for (const double end : {1.0, -1.0}) {
    const double head_y = end * (length / 2.0 - kHeadBeamAlong_m / 2.0);
    sliding(part(VisualPart::Shape::kGirder, {w, kHeadBeamAlong_m, 0.6 * h},
                 {centre.x, centre.y + head_y, bottom + 0.3 * h}),
            end)
        .bay_m = 0.6;
    for (const double across : {end > 0 ? -0.75 : -0.35, end > 0 ? 0.35 : 0.75})
      sliding(part(VisualPart::Shape::kBox, {0.32, beam_length, 0.3 * h},
                   {centre.x + across, centre.y + end * (beam_inner + beam_length / 2.0), bottom + 0.4 * h}),
              end);
    for (const double side : {1.0, -1.0}) {
      const double corner_x = side * spreader.twistlock_track_m / 2.0,
                   corner_y = end * (length / 2.0 - kCastingFromEnd_m);
      // the twistlock housing over its casting, the twistlock's cone under it and its head turning as it
      // locks
      sliding(part(VisualPart::Shape::kBox, {0.42, 0.55, 0.8 * h},
                   {centre.x + side * (w / 2.0 - 0.21), centre.y + end * (length / 2.0 - 0.275),
                    bottom + 0.4 * h}),
              end);
      bare_steel(sliding(part(VisualPart::Shape::kCylinder, {0.11, 0.11, 0.1},
                              {centre.x + corner_x, centre.y + corner_y, bottom - 0.05}),
                         end));
      VisualPart& head = bare_steel(sliding(part(VisualPart::Shape::kBox, {0.06, 0.13, 0.05},
                                                 {centre.x + corner_x, centre.y + corner_y, bottom - 0.125}),
                                            end));
      if (!spreader.locks_with.empty())
        head.turn =
            PartTurn{spreader.locks_with, {0.0, 0.0, 1.0}, std::numbers::pi / 2.0, false, std::nullopt};
    }
  }
  // the flippers: an L of guide plates round the corner, on an arm from a hinge along the spreader at the
  // corner's outer lower edge; drawn folded up (outboard, standing), turned 180 deg down round the corner
  if (spreader.flippers.size() == 4) {
    constexpr double kCorner[4][2] = {{1, -1}, {-1, -1}, {-1, 1}, {1, 1}};  // (along, across) signs
    const double a = kFlipperArm_m, d = kFlipperDepth_m, t = kFlipperPlate_m, g = kFlipperGap_m;
    for (std::size_t c = 0; c < 4; ++c) {
      const double ys = kCorner[c][0], xs = kCorner[c][1];
      const core::Vec3 hinge = centre + core::Vec3{xs * (w / 2.0 + g + t), ys * (length / 2.0), -h / 2.0};
      // folded up: mirrored about the hinge of where they hang down
      const auto up = [&](double x_in, double y_out, double z_down) {
        return hinge + core::Vec3{xs * x_in, ys * y_out, z_down};
      };
      const PartTurn swing{spreader.flippers[c], {0.0, 1.0, 0.0}, xs * std::numbers::pi, false, hinge};
      for (const auto& [size, at] :
           {std::pair{core::Vec3{a, t, d}, up(a / 2.0, g + t / 2.0, d / 2.0)},      // end plate
            std::pair{core::Vec3{t, a, d}, up(t / 2.0, g + t - a / 2.0, d / 2.0)},  // side plate
            std::pair{core::Vec3{0.3, 0.12, 0.12}, up(0.15, -0.1, 0.06)}}) {        // arm
        sliding(part(VisualPart::Shape::kBox, size, at), ys).turn = swing;
      }
    }
  }
  return parts;
}

std::vector<VisualPart> deckhouse_parts(const VisualPart& house, const core::Vec3& size_m) {
  const double w = size_m.x, d = size_m.y, h = size_m.z;
  const core::Vec3 c = house.centre_m;
  const core::Vec3 kGlass{0.12, 0.16, 0.20}, kRadar{0.20, 0.20, 0.22};
  std::vector<VisualPart> parts;
  const auto part = [&](VisualPart::Shape shape, const core::Vec3& size, const core::Vec3& at,
                        const core::Vec3& colour, Surface surface) -> VisualPart& {
    VisualPart p;
    p.shape = shape;
    p.size_m = size;
    p.centre_m = at;
    p.color = colour;
    p.livery = house.livery && colour == house.color;
    p.surface = surface;
    parts.push_back(p);
    return parts.back();
  };
  const auto glass = [&](const core::Vec3& size, const core::Vec3& at) {
    part(VisualPart::Shape::kBox, size, at, kGlass, Surface::kGlass);
  };
  part(VisualPart::Shape::kBox, size_m, c, house.color, house.surface);
  // a band of windows on each deck above the lowest: across the front, along both sides
  const int decks = std::max(1, static_cast<int>(h / kDeckHeight_m));
  const double deck = h / decks, bottom = c.z - h / 2.0, front = c.y + d / 2.0;
  for (int k = 1; k < decks; ++k) {
    const double z = bottom + deck * (k + 0.55);
    glass({0.9 * w, 0.1, 0.9}, {c.x, front + 0.05, z});
    for (const double side : {1.0, -1.0})
      glass({0.1, 0.7 * d, 0.9}, {c.x + side * (w / 2.0 + 0.05), c.y, z});
  }
  // the wheelhouse on top at the front, its windows; the bridge wings out past the sides
  const double wheelhouse_w = 0.7 * w, wheelhouse_d = std::min(6.0, 0.6 * d), top = c.z + h / 2.0;
  const core::Vec3 wheelhouse{c.x, front - wheelhouse_d / 2.0, top + 1.5};
  part(VisualPart::Shape::kBox, {wheelhouse_w, wheelhouse_d, 3.0}, wheelhouse, house.color, house.surface);
  glass({0.93 * wheelhouse_w, 0.1, 1.3}, {c.x, front + 0.05, top + 1.8});
  for (const double side : {1.0, -1.0}) {
    glass({0.1, 0.8 * wheelhouse_d, 1.1},
          {c.x + side * (wheelhouse_w / 2.0 + 0.05), wheelhouse.y, top + 1.8});
    const double wing = (w - wheelhouse_w) / 2.0 + 1.0;
    part(VisualPart::Shape::kWalkway, {wing, 2.0, 1.1},
         {c.x + side * (wheelhouse_w / 2.0 + wing / 2.0), front - 1.0, top + 0.55}, house.color,
         house.surface);
  }
  // the mast on the wheelhouse's roof, its radar scanner
  const core::Vec3 foot{c.x, wheelhouse.y - wheelhouse_d / 6.0, top + 3.0};
  VisualPart& mast = part(VisualPart::Shape::kMember, {5.5, 0.3, 0.3}, foot + core::Vec3{0.0, 0.0, 2.75},
                          house.color, house.surface);
  mast.along = {0.0, 0.0, 1.0};
  part(VisualPart::Shape::kBox, {3.0, 0.25, 0.3}, foot + core::Vec3{0.0, 0.0, 4.0}, kRadar, Surface::kPaint);
  return parts;
}

std::vector<VisualPart> drawn_parts(const VisualPart& part, const core::Vec3& size_m) {
  switch (part.shape) {
    case VisualPart::Shape::kSpreader:
      return spreader_parts(part, size_m);
    case VisualPart::Shape::kDeckhouse:
      return deckhouse_parts(part, size_m);
    default:
      return {part};
  }
}

}  // namespace harbour::ig
