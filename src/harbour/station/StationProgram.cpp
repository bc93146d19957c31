#include "harbour/station/StationProgram.h"

#include <SDL.h>

#include <osg/Image>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "harbour/audio/SoundFile.h"
#include "harbour/audio/SoundThread.h"
#include "harbour/core/Text.h"
#include "harbour/ig/Jpeg.h"
#include "harbour/ig/RenderThread.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/MotionFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/records/CentreRoutes.h"
#include "harbour/records/HeadlessRun.h"
#include "harbour/sim/Pilot.h"
#include "harbour/station/ConsolePresence.h"
#include "harbour/station/DeviceMappingFile.h"
#include "harbour/station/DisplayDrawing.h"
#include "harbour/station/DisplayLayout.h"
#include "harbour/station/HeadTracker.h"
#include "harbour/station/LookAround.h"
#include "harbour/station/MotionLink.h"
#include "harbour/station/Profile.h"
#include "harbour/station/RemoteChannels.h"
#include "harbour/station/Station.h"
#include "harbour/station/StationWindow.h"
#include "harbour/station/TeamMembership.h"

namespace harbour::station {
namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_stop_signal(int) {
  g_stop = 1;
}

// the value of a named indicator in a snapshot (machine-blind: names come from the scene description)
std::optional<double> indicator(const scene::SceneDescription& scene, const scene::Snapshot& s,
                                const char* name) {
  for (std::size_t n = 0; n < scene.indicators.size() && static_cast<int>(n) < s.indicator_count; ++n)
    if (scene.indicators[n] == name) return s.indicators[n];
  return std::nullopt;
}

// the first mapping of the profile that fits the machine's controls and whose devices are all here
std::unique_ptr<station::DeviceInput> open_devices(const station::Profile& profile,
                                                   const scene::ControlTable& table, bool window) {
  station::init_sdl_joysticks();
  std::string tried;
  for (const std::string& file : profile.mappings) {
    if (const std::string why = station::why_mapping_does_not_fit(file, table); !why.empty()) {
      tried += "\n  " + file + ": for another machine (" + why + ")";
      continue;
    }
    station::DeviceMapping mapping = station::load_device_mapping(file, table);
    if (station::DeviceInput::all_present(mapping, window)) {
      std::printf("input: %s (%s)\n", mapping.name.c_str(), file.c_str());
      station::quit_sdl_joysticks();
      return std::make_unique<station::DeviceInput>(table, std::move(mapping));
    }
    tried += "\n  " + mapping.name + " (" + file + "): ";
    for (const station::DeviceMatch& d : mapping.devices)
      tried += d.window_device() ? (d.keyboard ? "the keyboard (needs the station's window) "
                                               : "the mouse (needs the station's window) ")
                                 : "'" + d.name + "' ";
  }
  station::quit_sdl_joysticks();
  std::string present;
  for (const station::DeviceInfo& d : station::DeviceInput::list())
    present += "\n  " + d.name + " (" + d.guid + ")";
  throw std::runtime_error("no input devices for profile '" + profile.name + "'; it tried:" + tried +
                           "\ndevices present:" + (present.empty() ? std::string(" none") : present) +
                           "\n(bind yours with: harboursim devices --bind FILE; or, for a container "
                           "exercise, run with --autopilot)");
}

// The exercise a taken-over attempt ran (none when it is not taken over or the records hold no such
// attempt): the branch goes on in the world the attempt was made in, even when the exercise changed since.
std::optional<io::ExerciseSource> taken_over_exercise(const std::string& database,
                                                      const StationOptions& options) {
  if (options.take_over_recording.empty()) return std::nullopt;
  records::RecordsStore db(database);
  const std::optional<records::AttemptRow> taken = db.attempt_recorded_at(options.take_over_recording);
  if (!taken) return std::nullopt;
  std::string inexact;
  io::ExerciseSource source = records::attempt_exercise(db, *taken, options.centre.exercises, inexact);
  if (!inexact.empty()) std::printf("NOTE: %s\n", inexact.c_str());
  return source;
}

// a headless station under the autopilot wakes every 5 ms, not every millisecond (a fifth of the wake-ups);
// an instructor's command then waits at most that much more
constexpr int kHeadlessTicksPerWake = 5;

// The exercise an attempt runs, into `session`: a route's next stage, an attempt taken over, a team role's,
// or the one named; `team`: the team session it is a member of (none when it is not)
void choose_exercise(const StationOptions& options, const std::string& database,
                     station::SessionOptions& session, std::optional<io::Team>& team) {
  // a member of a team session runs its role's exercise
  if (!options.team.empty()) {
    std::vector<std::string> exercise_folders{records::shipped_data_folder() + "/exercises"};
    if (!options.centre.exercises.empty())
      exercise_folders.insert(exercise_folders.begin(), options.centre.exercises);
    team = io::load_team(station::resolve_team(options.team, options.centre.exercises), exercise_folders);
    if (!team->find(options.role))
      throw std::runtime_error("team " + team->name + " has no role '" + options.role +
                               "' (its roles: " + team->role_list() + ")");
  }
  if (!options.route.empty()) {
    records::RecordsStore db(database);
    const records::RouteStage next =
        records::next_route_stage(db, options.centre, options.trainee, options.route);
    session.source = io::read_exercise_source(next.stage.exercise_file);
    session.route = next.route.id;
    session.stage = next.stage.id;
    std::printf("route %s, stage %s (%s)\n", next.route.id.c_str(), next.stage.id.c_str(),
                next.stage.goal.c_str());
  } else if (std::optional<io::ExerciseSource> taken = taken_over_exercise(database, options)) {
    session.source = std::move(*taken);
  } else if (team) {
    session.source = io::read_exercise_source(team->find(options.role)->exercise_file);
  } else {
    session.source =
        io::read_exercise_source(records::resolve_exercise(options.exercise, options.centre.exercises));
  }
}

// The trainee's windows' pictures: one image generator drawing every display channel's picture (each eye's in
// stereo) from the newest snapshot and handing each to its window
std::unique_ptr<ig::RenderThread> render_windows(
    const station::Profile& profile, const station::DisplayLayout& layout,
    const std::vector<std::unique_ptr<station::StationWindow>>& windows, const scene::SceneDescription& scene,
    const ig::Looks& looks, station::Session& session) {
  std::vector<station::StationWindow*> shown;
  for (const auto& w : windows)
    shown.push_back(w.get());
  auto render = station::draw_displays(
      profile, layout, scene, looks,
      [&session] { return session.loop().latest_snapshot(station::kImageGeneratorReader); },
      [&session] { return session.loop().latest_bulk(station::kImageGeneratorReader); },
      [shown](int window, const osg::Image& image, int x0, std::uint8_t colours, bool last) {
        shown[static_cast<std::size_t>(window)]->hand_over(image.data(), image.s(), image.t(),
                                                           static_cast<int>(image.getPixelSizeInBits() / 8),
                                                           image.getRowStepInBytes(), x0, colours, last);
      });
  const int channels = static_cast<int>(profile.displays.size());
  const std::string stereo = !profile.stereo ? ""
                             : profile.stereo->mode == station::Profile::Stereo::Mode::kAnaglyph
                                 ? ", stereo: anaglyph"
                                 : ", stereo: side by side";
  if (windows.size() == 1)
    std::printf("window: %dx%d, the cab view (%s, %d channel%s%s)\n", layout.windows[0].width,
                layout.windows[0].height, profile.name.c_str(), channels, channels == 1 ? "" : "s",
                stereo.c_str());
  else
    std::printf("windows: %zu of %dx%d, one per display, the cab view (%s%s)\n", windows.size(),
                layout.windows[0].width, layout.windows[0].height, profile.name.c_str(), stereo.c_str());

  return render;
}

// The cab's sound on the profile's output, or none (no device, or a sound file in error: the station runs on)
std::unique_ptr<audio::SoundThread> start_sound(const station::Profile& profile,
                                                const scene::SceneDescription& scene,
                                                const sim::ExerciseSettings& exercise,
                                                station::Session& session) {
  audio::AudioSettings settings;
  settings.speakers =
      profile.sound->output == station::Profile::Sound::Output::kHeadphones   ? audio::Speakers::kHeadphones
      : profile.sound->output == station::Profile::Sound::Output::kSurround51 ? audio::Speakers::kSurround51
                                                                              : audio::Speakers::kStereo;
  settings.volume = profile.sound->volume;
  try {
    auto sound = std::make_unique<audio::SoundThread>(
        scene,
        audio::load_shipped_sounds(records::shipped_data_folder(), sim::machine_kinds(),
                                   exercise.machine_file),
        settings, exercise.radio,
        [&session] { return session.loop().latest_snapshot(station::kSoundReader); });
    std::printf("sound: %s\n", sound->describe().c_str());
    if (!sound->radio_problem().empty()) std::printf("no radio: %s\n", sound->radio_problem().c_str());
    return sound;
  } catch (const std::exception& e) {  // no device, or a sound file in error: the station runs on
    std::printf("no sound: %s\n", e.what());
  }

  return nullptr;
}

// What the instructor sees of the trainee's view: the cab view drawn small a few times a second, as JPEG,
// only while a console shows this station
std::unique_ptr<ig::RenderThread> draw_for_instructor(const station::Profile& profile,
                                                      const scene::SceneDescription& scene,
                                                      const ig::Looks& looks, station::Session& session,
                                                      station::AttemptPresence& presence) {
  ig::View view = ig::view_named("cab");
  if (!profile.displays.empty()) {
    const station::DisplayChannel& c = profile.displays.front();
    view.yaw_rad = c.yaw_rad;
    view.pitch_rad = c.pitch_rad;
    view.from_sight = c.from_sight;
    view.fov_from_sight = c.fov_from_sight;
    view.fov_vertical_rad = c.fov_vertical_rad;
  }
  return std::make_unique<ig::RenderThread>(
      scene, looks, station::kPictureWidth, station::kPictureHeight, std::vector<ig::View>{view},
      // drawn only while a console shows this station
      [&session, &presence]() -> const scene::Snapshot* {
        return presence.watched() ? session.loop().latest_snapshot(station::kPictureReader) : nullptr;
      },
      [&presence](ig::ImageGenerator& generator, const scene::Snapshot& s, int) {
        presence.offer_picture(ig::encode_jpeg(generator.render_result()), station::kPictureWidth,
                               station::kPictureHeight, s.time_s);
      },
      station::kPicturesPerSecond,
      [&session] { return session.loop().latest_bulk(station::kPictureReader); });
}

// The attempt's progress on the terminal: the machine's first indicators, its load, the moves done, the loop
void print_progress(const scene::SceneDescription& scene, const scene::Snapshot& s,
                    const sim::ExerciseSettings& exercise, station::Session& session) {
  const station::LoopStats stats = session.loop().stats();
  const sim::Metrics m = session.metrics();
  // the machine's first indicators (whatever the machine: names as it publishes them), then the goals
  std::string shown;
  for (std::size_t n = 0; n < scene.indicators.size() && n < 3 && static_cast<int>(n) < s.indicator_count;
       ++n)
    shown += "  " + scene.indicators[n] + " " + std::to_string(s.indicators[n]).substr(0, 7);
  if (const auto load = indicator(scene, s, "load_t"))
    shown += "  load_t " + std::to_string(*load).substr(0, 5);
  if (!exercise.moves.empty())
    shown += "  moves " + std::to_string(m.moves_completed) + "/" + std::to_string(exercise.moves.size());
  std::printf("  t=%6.1f s%s  | %.3fx real time, %lld late, longest %.1f ms%s%s\n", s.time_s, shown.c_str(),
              stats.real_time_factor, static_cast<long long>(stats.late_ticks), stats.longest_tick_s * 1e3,
              s.held ? "  HELD" : "",
              s.devices_missing ? "  INPUT DEVICE MISSING: its controls are neutral" : "");
  std::fflush(stdout);
}

// The trainee's windows (before the devices: the keyboard and mouse need them): the profile's displays side
// by side in one window or a window each, where there is a display or they are asked for
std::vector<std::unique_ptr<station::StationWindow>> open_windows(const StationOptions& options,
                                                                  const station::Profile& profile,
                                                                  const station::DisplayLayout& layout,
                                                                  const sim::ExerciseSettings& exercise) {
  const bool display = std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY");
  if (options.window != "on" && options.window != "off" && options.window != "auto")
    throw std::runtime_error("--window " + options.window + ": on, off or auto");
  std::vector<std::unique_ptr<station::StationWindow>> windows;
  if (options.window == "on" || (options.window == "auto" && display))
    for (const station::DisplayLayout::Window& w : layout.windows) {
      const station::DisplayChannel& d = profile.displays[static_cast<std::size_t>(w.display)];
      const std::string title = "harboursim: " + exercise.name + " (" + profile.name +
                                (layout.windows.size() > 1 ? ", " + d.name : std::string()) + ")";
      windows.push_back(std::make_unique<station::StationWindow>(
          w.width, w.height, title, layout.windows.size() > 1 && d.fullscreen, w.display));
    }
  return windows;
}

// The profile's head tracker (it moves only a drawn view) and motion platform, where it has them
void use_head_and_platform(station::Station& station, const station::Profile& profile, bool drawn,
                           const sim::ExerciseSettings& exercise, station::Session& session) {
  if (profile.opentrack_port && drawn) {
    // without its tracker (its port taken by another station on this PC) the view stays at the design eye
    try {
      station.use_head_tracking(std::make_unique<station::HeadTracker>(*profile.opentrack_port));
      std::printf("head tracking: OpenTrack UDP on port %u\n",
                  static_cast<unsigned>(*profile.opentrack_port));
    } catch (const std::runtime_error& e) {
      std::printf("%s: the view stays at the design eye point\n", e.what());
    }
  }
  if (profile.motion) {
    station.use_motion(std::make_unique<station::MotionLink>(
        io::load_platform(profile.motion->platform),
        io::load_washout(profile.motion->washout, exercise.machine_file), profile.motion->driver,
        session.simulation().scene()));
    std::printf("motion platform: %s:%u\n", profile.motion->driver.host.c_str(),
                static_cast<unsigned>(profile.motion->driver.port));
  }
}

// What the machines' looks say another machine can hit, by look key (read whether or not this station draws:
// what its simulation collides with does not depend on its windows)
station::SolidParts solid_parts() {
  station::SolidParts solid;
  const ig::Looks looks = ig::load_shipped_looks(records::shipped_data_folder(), sim::machine_kinds());
  for (const auto& [key, visual] : looks.visuals)
    for (const ig::VisualPart& part : visual.parts)
      if (part.solid && part.size_m)
        solid[key].push_back({core::Pose{core::Mat3::identity(), part.centre_m}, 0.5 * *part.size_m});
  return solid;
}

// This station as a member of a team session: the other members' machines in its scene and in every snapshot
// it publishes (the loop's addition holds the membership as long as the loop may run)
std::shared_ptr<station::TeamMembership> join_team(const io::Team& team, const StationOptions& options,
                                                   const sim::ExerciseSettings& exercise,
                                                   station::Session& session) {
  auto membership = std::make_shared<station::TeamMembership>(
      team, options.role, options.name.empty() ? options.role : options.name, options.domain, exercise,
      session.simulation().scene(), options.time_scale, solid_parts());
  // for the readers that draw: the windows, the console's 3D view, the instructor's picture
  session.loop().set_addition(
      [membership](scene::Snapshot& s) { membership->add_to(s); },
      1u << station::kImageGeneratorReader | 1u << station::kConsoleReader | 1u << station::kPictureReader);
  std::string others;
  for (const io::TeamRole& r : team.roles)
    if (r.role != options.role) others += (others.empty() ? "" : ", ") + r.role;
  std::printf("team %s: %s (%s), with %s\n", team.name.c_str(), options.role.c_str(), exercise.name.c_str(),
              others.c_str());

  return membership;
}

// The image generators stopped, with what they drew
void stop_drawing(ig::RenderThread* render,
                  const std::vector<std::unique_ptr<station::StationWindow>>& windows,
                  ig::RenderThread* pictures, station::RemoteChannels* channels) {
  if (channels) {
    channels->stop();
    std::printf("%s\n", channels->summary().c_str());
  }
  if (render) {
    long shown = windows.front()->frames_shown();
    for (const auto& w : windows)
      shown = std::min(shown, w->frames_shown());
    std::printf("window: %ld frames drawn (%.1f fps), %ld shown%s\n", render->frames(), render->fps(), shown,
                windows.size() > 1 ? " in every window" : "");
    if (!render->error().empty()) std::printf("image generator stopped: %s\n", render->error().c_str());
    render->stop();
  }
  if (pictures) {
    std::printf("instructor's picture: %ld frames (%.1f fps, %dx%d)%s\n", pictures->frames(), pictures->fps(),
                station::kPictureWidth, station::kPictureHeight,
                pictures->error().empty() ? "" : (": stopped: " + pictures->error()).c_str());
    pictures->stop();
  }
}

// How the attempt went: its loop's timing, its evaluation, where it is stored
void print_result(const station::SessionResult& result, const StationOptions& options) {
  const station::LoopStats& l = result.loop;
  std::printf(
      "\nloop: %lld ticks, %lld late, %lld given up, longest %.2f ms, mean %.1f us, %.3fx real time%s\n",
      static_cast<long long>(l.ticks), static_cast<long long>(l.late_ticks),
      static_cast<long long>(l.skipped_ticks), l.longest_tick_s * 1e3, l.mean_tick_s * 1e6,
      l.real_time_factor, l.keeping_real_time ? "" : " (COULD NOT KEEP REAL TIME)");
  records::print_evaluation(result.metrics, result.score);
  std::printf("stored as attempt %lld of trainee %s (%s)\n", static_cast<long long>(result.attempt),
              options.trainee.c_str(), result.status.c_str());
  if (!options.record.empty()) std::printf("recording %s\n", options.record.c_str());
}

// Whether the cab's sound plays (by default none for a headless run)
bool wants_sound(const StationOptions& options, const station::Profile& profile, bool drawn) {
  if (options.sound != "on" && options.sound != "off" && options.sound != "auto")
    throw std::runtime_error("--sound " + options.sound + ": on, off or auto");
  return profile.sound && (options.sound == "on" || (options.sound == "auto" && drawn));
}

// Snapshots only for the readers there are (writing one for nobody costs the step thread); nobody in the loop
// to feel a millisecond (the scripted operator, no window, no platform): woken less often
void skip_unread_snapshots(station::LoopSettings& loop, const StationOptions& options,
                           const station::Profile& profile, bool drawn, bool hearing, bool watched, bool team,
                           bool channels) {
  if (!drawn) loop.snapshot_every_steps[station::kImageGeneratorReader] = 0;
  if (!channels) loop.snapshot_every_steps[station::kChannelReader] = 0;
  if (!hearing) loop.snapshot_every_steps[station::kSoundReader] = 0;
  if (!watched) loop.snapshot_every_steps[station::kPictureReader] = 0;
  if (!profile.motion) loop.snapshot_every_steps[station::kMotionReader] = 0;
  if (!team) loop.snapshot_every_steps[station::kTeamReader] = 0;
  if (options.autopilot && !drawn && !channels && !profile.motion)
    loop.ticks_per_wake = kHeadlessTicksPerWake;
}

// The windows' input since the last pump: keys to the devices, looking round, F1's list of keys; false when
// one was closed
bool pump_windows(const std::vector<std::unique_ptr<station::StationWindow>>& windows,
                  station::Station& station, station::LookAround& look, ig::RenderThread* render,
                  const std::string& keys, bool& help, double dt_s) {
  bool open = true;
  for (const auto& w : windows) {
    const station::WindowInput in = w->pump();
    open = in.open && open;
    if (station.devices())
      for (const int key : in.keys_went_down)
        station.devices()->key_went_down(key);
    if (in.recentre) look.recentre();
    look.update(dt_s, in.look_yaw_keys, in.look_pitch_keys, in.drag_right_px, in.drag_down_px, in.dragging);
    if (in.help_toggled && render) {
      help = !help;
      render->set_overlay(help ? keys : "");
    }
  }
  return open;
}

// What a team's thread says, and the entities it renames (a box handed over onto the load), kept until the
// station's thread prints them and tells the consoles
class TeamSaid {
 public:
  using Renamed = std::pair<std::size_t, std::string>;
  void add(std::string line) {
    const std::lock_guard lock(mutex_);
    lines_.push_back(std::move(line));
  }
  void renamed(std::size_t entity, std::string name) {
    const std::lock_guard lock(mutex_);
    renamed_.emplace_back(entity, std::move(name));
  }
  std::pair<std::vector<std::string>, std::vector<Renamed>> take() {
    const std::lock_guard lock(mutex_);
    std::pair<std::vector<std::string>, std::vector<Renamed>> taken;
    taken.first.swap(lines_);
    taken.second.swap(renamed_);
    return taken;
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> lines_;
  std::vector<Renamed> renamed_;
};

// The membership started: the others' states taken, its team inputs posted to the loop, what it says kept
// in `said`, a box handed over onto this station's load named so in every picture drawn
void start_membership(station::TeamMembership& membership, station::Session& session, TeamSaid& said,
                      ig::RenderThread* render, ig::RenderThread* pictures) {
  membership.start([&session] { return session.loop().latest_snapshot(station::kTeamReader); },
                   [&said](const std::string& line) { said.add(line); },
                   [&session](const sim::TeamInput& input) {
                     station::LoopCommand c;
                     c.kind = station::LoopCommand::Kind::kTeam;
                     c.team = input;
                     return session.loop().post(c);
                   },
                   [render, pictures, &said](int entity, const std::string& id) {
                     for (ig::RenderThread* drawing : {render, pictures})
                       if (drawing) drawing->rename_entity(static_cast<std::size_t>(entity), id);
                     said.renamed(static_cast<std::size_t>(entity), id);  // for the consoles' 3D views
                   });
}

// The station's and the team's messages since last asked, printed and told to the consoles
void tell(station::Station& station, station::AttemptPresence* presence, TeamSaid& said,
          station::RemoteChannels* channels) {
  if (channels)
    for (const std::string& m : channels->take_said()) {
      std::printf("  %s\n", core::printable(m).c_str());
      if (presence) presence->note("station", m);
    }
  for (const std::string& m : station.take_messages()) {
    std::printf("  %s\n", core::printable(m).c_str());
    if (presence) presence->note("station", m);
  }
  const auto [lines, renamed] = said.take();
  for (const std::string& m : lines) {
    std::printf("  team: %s\n", core::printable(m).c_str());
    if (presence) presence->note("team", m);
  }
  if (presence)
    for (const auto& [entity, name] : renamed)
      presence->rename_entity(entity, name);
}

// The profile's displays drawn by `harboursim channel` processes on their own hosts, fed over the network
std::vector<std::string> remote_displays(const station::Profile& profile, bool on_network) {
  std::vector<std::string> names;
  for (const station::DisplayChannel& display : profile.displays)
    if (display.remote) names.push_back(display.name);
  if (!names.empty() && !on_network)
    throw std::runtime_error(
        "profile " + profile.name + ": display '" + names.front() +
        "' is drawn by a channel process over the network (remote: true): give the station "
        "a name on it (--name)");
  return names;
}

// Frames of the newest snapshot for the remote displays' channels, frame-locked
std::unique_ptr<station::RemoteChannels> feed_channels(const std::vector<std::string>& displays,
                                                       const StationOptions& options,
                                                       station::Session& session) {
  if (displays.empty()) return nullptr;
  std::string names;
  for (const std::string& d : displays)
    names += (names.empty() ? "" : ", ") + d;
  std::printf("remote channels: %s (harboursim channel --station %s --display NAME), DDS domain %d\n",
              names.c_str(), options.name.c_str(), options.domain);
  return std::make_unique<station::RemoteChannels>(
      std::make_unique<net::ChannelServerLink>(options.name, options.domain), displays, session.attempt(),
      [&session] { return session.loop().latest_snapshot(station::kChannelReader); },
      [&session] { return session.loop().latest_bulk(station::kChannelReader); },
      station::RemoteChannels::Settings{});
}

// This station leaves its team session: the team's figures and the session's id go with the attempt
void leave_team(station::TeamMembership& membership, station::Session& session, const std::string& team,
                const std::string& role) {
  membership.stop();
  membership.leave();
  for (const std::string& line : membership.report())
    std::printf("%s\n", line.c_str());
  session.set_team_figures(membership.figures());
  session.set_team(team, role, membership.session());
  std::printf("team session %s\n", membership.session().c_str());
}

// The harbour's looks and every machine's (a team's others drawn too), the exercise's machine file last;
// none where nothing is drawn
ig::Looks looks_to_draw(const sim::ExerciseSettings& exercise, bool drawn) {
  if (!drawn) return {};
  return ig::load_shipped_looks(records::shipped_data_folder(), sim::machine_kinds(), exercise.machine_file);
}

// What F1 shows the trainee: the machine's controls and the keys (or whatever else) that work them
std::string keys_to_show(station::Station& station, station::Session& session) {
  return station.devices()
             ? station::key_list(station.devices()->mapping(), session.simulation().control_table())
             : "the scripted operator drives: no keys\nF1 this list   F11 full screen";
}

// What the station runs, on the terminal
void print_banner(const station::Profile& profile, const sim::ExerciseSettings& exercise,
                  const StationOptions& options, const station::Session& session) {
  std::printf("station (%s): exercise %s, %zu move(s), %s, attempt %lld of trainee %s%s\n",
              profile.name.c_str(), exercise.name.c_str(), exercise.moves.size(),
              options.autopilot ? "autopilot" : "trainee at the controls",
              static_cast<long long>(session.attempt()), options.trainee.c_str(),
              options.record.empty() ? "" : (", recording " + options.record).c_str());
  std::printf("Ctrl-C ends the attempt (stored as interrupted)\n");
  std::fflush(stdout);
}

// One attempt at the station, start to end; with a link, seen and commanded from the centre's consoles
// (`reset`: a console asked for the attempt again; `outcome`, when given: how the attempt ended, in the
// console's words).
int run_attempt(const StationOptions& given, net::StationLink* link, bool& reset,
                std::string* outcome = nullptr) {
  reset = false;
  StationOptions options = given;
  if (options.trainee.empty()) options.trainee = options.autopilot ? "autopilot" : "guest";
  records::RunOptions outputs;
  outputs.record = options.record;
  outputs.trainee = options.trainee;
  records::check_outputs(outputs);
  const std::string database = options.database.empty() ? records::default_database() : options.database;
  station::SessionOptions session_options;
  session_options.autopilot = options.autopilot;
  std::optional<io::Team> team;
  choose_exercise(options, database, session_options, team);
  const sim::ExerciseSettings exercise = io::load_exercise_source(session_options.source);
  if (options.autopilot)
    if (const std::string why = sim::why_no_pilot(exercise); !why.empty())
      throw std::runtime_error(exercise.name + ": " + why + " (drive it yourself: no --autopilot)");
  const station::Profile profile =
      station::load_profile(station::resolve_profile(options.profile, records::shipped_data_folder()));
  if (options.trainee == "autopilot")
    records::RecordsStore(database).ensure_trainee("autopilot", "Scripted operator");
  if (options.trainee == "guest")
    records::RecordsStore(database).ensure_trainee("guest", "Guest at the station");

  session_options.trainee = options.trainee;
  session_options.record = options.record;
  session_options.database = database;
  session_options.loop.time_scale = options.time_scale;
  if (!options.take_over_recording.empty())
    session_options.take_over = station::TakeOverFrom{options.take_over_recording, options.take_over_step};
  // the profile's displays: side by side in one window or a window each, two eyes each in stereo
  const station::Profile own =
      station::with_displays(profile, [](const station::DisplayChannel& d) { return !d.remote; });
  const std::vector<std::string> remote = remote_displays(profile, link != nullptr);
  const station::DisplayLayout layout = station::layout_displays(own);
  const std::vector<std::unique_ptr<station::StationWindow>> windows =
      open_windows(options, own, layout, exercise);
  const bool hearing = wants_sound(options, profile, !windows.empty());
  skip_unread_snapshots(session_options.loop, options, profile, !windows.empty(), hearing, link != nullptr,
                        team.has_value(), !remote.empty());
  station::Session session(exercise, session_options);
  station::Station station(session);
  // the other members' machines, in this station's scene and in every snapshot it publishes
  std::shared_ptr<station::TeamMembership> membership;
  if (team) membership = join_team(*team, options, exercise, session);
  std::unique_ptr<sim::Pilot> pilot;
  if (options.autopilot) {
    pilot = sim::make_pilot(exercise);
    if (session_options.take_over)
      pilot->resume(session.simulation(), session.moves_before_start(), session.levers_before_start());
    session.loop().set_pilot([&](const sim::Simulation& s) { return pilot->next(s); });
  } else {
    station.use_devices(open_devices(profile, session.simulation().control_table(), !windows.empty()));
  }
  use_head_and_platform(station, profile, !windows.empty(), exercise, session);
  print_banner(profile, exercise, options, session);

  const scene::SceneDescription scene = membership ? membership->scene() : session.simulation().scene();
  const ig::Looks looks = looks_to_draw(exercise, !windows.empty() || link);
  std::unique_ptr<ig::RenderThread> render;
  if (!windows.empty()) render = render_windows(own, layout, windows, scene, looks, session);
  std::unique_ptr<audio::SoundThread> sound;
  if (hearing) sound = start_sound(profile, scene, exercise, session);
  std::optional<station::AttemptPresence> presence;
  if (link) presence.emplace(*link, session, exercise, options.trainee, scene);
  if (presence) presence->use_sound(sound.get());
  if (presence && team) presence->member_of(team->name, options.role);
  // the instructor sees what the trainee sees: the cab view drawn small a few times a second, as JPEG
  std::unique_ptr<ig::RenderThread> pictures;
  if (presence) pictures = draw_for_instructor(profile, scene, looks, session, *presence);
  const auto start = std::chrono::steady_clock::now();
  session.start();
  station.start();
  const std::unique_ptr<station::RemoteChannels> channels = feed_channels(remote, options, session);
  TeamSaid team_said;
  if (membership) start_membership(*membership, session, team_said, render.get(), pictures.get());
  const auto tell_what_was_said = [&] {
    tell(station, presence ? &*presence : nullptr, team_said, channels.get());
  };
  station::AttemptPresence::Next next = station::AttemptPresence::Next::kRun;
  int next_line = 0;
  bool window_open = true;
  // looking round at the window (keys, a mouse drag) within the cab's limits; F1 the machine's keys
  const scene::CabSight sight = session.simulation().machine().cab_sight();
  station::LookAround look({sight.look_yaw_rad, sight.look_pitch_rad});
  const std::string keys = keys_to_show(station, session);
  bool help = false;
  auto last_pump = std::chrono::steady_clock::now();
  while (!session.over() && !g_stop && session.loop().running() && window_open &&
         next == station::AttemptPresence::Next::kRun) {
    // a console's command waits at most this long (its round trip's share)
    std::this_thread::sleep_for(std::chrono::milliseconds(presence ? 5 : windows.empty() ? 100 : 15));
    if (presence) next = presence->service();
    const auto now = std::chrono::steady_clock::now();
    const double dt_s = std::chrono::duration<double>(now - last_pump).count();
    last_pump = now;
    window_open = pump_windows(windows, station, look, render.get(), keys, help, dt_s) && window_open;
    if (!windows.empty()) session.loop().set_look(look.yaw_rad(), look.pitch_rad());
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (options.seconds > 0.0 && wall >= options.seconds) break;
    tell_what_was_said();
    if (wall < next_line * 2.0) continue;
    ++next_line;
    const scene::Snapshot* s = session.loop().latest_snapshot(station::kConsoleReader);
    if (!s) continue;
    print_progress(scene, *s, exercise, session);
  }
  const bool interrupted = g_stop || !window_open || next != station::AttemptPresence::Next::kRun ||
                           (!session.over() && options.seconds > 0.0);
  reset = next == station::AttemptPresence::Next::kReset;
  stop_drawing(render.get(), windows, pictures.get(), channels.get());
  if (membership) leave_team(*membership, session, team->name, options.role);
  tell_what_was_said();  // what came with the last steps (a box handed over as the last move ended)
  station.stop_monitoring();
  const station::SessionResult result =
      session.finish(g_stop || !window_open || (next == station::AttemptPresence::Next::kRun && interrupted)
                         ? station::SessionEnd::kInterrupted
                     : interrupted ? station::SessionEnd::kStoppedByInstructor
                                   : station::SessionEnd::kRan);
  station.stop();  // the platform parks with the simulation stopped
  if (presence) presence->publish_end(result);
  if (outcome) *outcome = station::attempt_outcome(result);
  print_result(result, options);
  if (result.status == "diverged") return 3;
  return interrupted ? 130 : 0;
}

// Where a served station keeps its attempts' recordings: beside its SQLite records file, else (a records
// server) beside the default records.
std::string recording_for(const std::string& station, const std::string& exercise,
                          const std::string& database) {
  const std::string sqlite_prefix = "sqlite3://db=";
  const std::string records = database.rfind(sqlite_prefix, 0) == 0 ? database : records::default_database();
  const std::filesystem::path folder =
      std::filesystem::path(records.substr(sqlite_prefix.size())).parent_path() / "recordings";
  std::filesystem::create_directories(folder);
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
  return (folder / (station + "-" + stamp + "-" + exercise + ".hsrc")).string();
}

// An exercise a console names: a shipped one, by name (no paths from the network).
std::string why_bad_exercise_name(const std::string& name) {
  if (const std::string why = net::why_bad_node_name(name); !why.empty()) return why;
  if (name.find("..") != std::string::npos) return "a shipped exercise's name, not a path";
  return "";
}

}  // namespace

int run_station(const StationOptions& options) {
  g_stop = 0;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  struct RestoreSignals {
    ~RestoreSignals() {
      std::signal(SIGINT, SIG_DFL);
      std::signal(SIGTERM, SIG_DFL);
    }
  } restore;
  std::unique_ptr<net::StationLink> link;
  if (!options.name.empty()) {
    link = std::make_unique<net::StationLink>(options.name, options.domain);
    std::printf("on the network as station %s (DDS domain %d)\n", options.name.c_str(), options.domain);
  }
  bool reset = false;
  if (!options.serve) {
    int status = run_attempt(options, link.get(), reset);
    while (reset && !g_stop)
      status = run_attempt(options, link.get(), reset);
    return status;
  }
  if (!link) throw std::runtime_error("--serve needs --name: the station's name on the network");
  std::printf("station %s waits for a console to start an exercise (Ctrl-C ends it)\n", options.name.c_str());
  std::fflush(stdout);
  std::string message = "ready", outcome;
  while (!g_stop) {
    station::IdlePresence idle(*link, message);
    std::optional<station::StartRequest> start;
    while (!g_stop && !(start = idle.service()))
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (!start) break;
    StationOptions attempt = options;
    attempt.exercise = start->exercise;
    attempt.route = start->route;  // run_attempt takes the trainee's next stage of it from the records
    attempt.team = start->team;    // a team's member runs its role's exercise
    attempt.role = start->role;
    attempt.trainee = start->trainee;
    attempt.autopilot = options.autopilot || start->autopilot;
    attempt.seconds = 0.0;
    attempt.take_over_recording = start->take_over ? start->take_over->recording : "";
    attempt.take_over_step = start->take_over ? start->take_over->step : 0;
    const std::string what = start->team.empty() ? start->exercise : start->role + " of team " + start->team;
    std::printf("%s starts %s for trainee %s%s\n", start->user.c_str(), what.c_str(),
                start->trainee.empty() ? "(none)" : start->trainee.c_str(),
                attempt.autopilot ? " (autopilot)" : "");
    std::fflush(stdout);
    try {
      if (!attempt.team.empty()) {
        if (const std::string why = why_bad_exercise_name(attempt.team); !why.empty())
          throw std::runtime_error("team '" + core::printable(attempt.team) + "': " + why);
      } else if (const std::string why = why_bad_exercise_name(attempt.exercise); !why.empty()) {
        throw std::runtime_error("exercise '" + core::printable(attempt.exercise) + "': " + why);
      }
      do {
        attempt.record = recording_for(
            options.name, attempt.team.empty() ? attempt.exercise : attempt.team + "-" + attempt.role,
            options.database);  // each attempt its own
        run_attempt(attempt, link.get(), reset, &outcome);
        attempt.take_over_recording.clear();  // a reset starts the exercise anew
      } while (reset && !g_stop);
      message = "ready; last: " + outcome + " (" + (attempt.team.empty() ? attempt.exercise : what) + ")";
    } catch (const std::exception& e) {
      message = std::string("could not run ") + what + ": " + e.what();
      std::printf("%s\n", core::printable(message).c_str());
      std::fflush(stdout);
      net::StationEvent event;
      event.kind("start_failed");
      event.text(message.substr(0, 255));
      link->publish(event);
    }
  }
  return 0;
}

}  // namespace harbour::station
