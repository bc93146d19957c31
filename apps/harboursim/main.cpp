#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "BulkDemo.h"
#include "ReportCommand.h"
#include "RoutesTool.h"
#include "TraineesCommand.h"
#include "XapiCommand.h"
#include "harbour/console/Console.h"
#include "harbour/debrief/RenderVideo.h"
#include "harbour/debrief/Screenshot.h"
#include "harbour/records/HeadlessRun.h"
#include "harbour/records/XapiSender.h"
#include "harbour/station/ChannelProgram.h"
#include "harbour/station/DevicesTool.h"
#include "harbour/station/StationProgram.h"

namespace {

// --exercises and --routes: the centre's own folders, searched before the shipped ones
void add_centre_options(CLI::App* command, harbour::records::CentreFolders& centre,
                        const char* exercises_help) {
  command->add_option("--exercises", centre.exercises, exercises_help);
  command->add_option("--routes", centre.routes,
                      "the centre's route folder, beside the shipped routes (its stages name exercises of "
                      "--exercises or shipped ones)");
}
const char* kCentreExercises = "the centre's exercise folder, searched by name before the shipped exercises";
const char* kCentreIri =
    "the centre's IRI in its xAPI statements: its trainees' home page IRI/trainees, its exercises "
    "IRI/exercises/NAME (default: http://HOSTNAME/harboursim)";

// A subcommand: its options parsed into what it owns; run, it gives the exit status, or nothing when it was
// not the one chosen.
using Command = std::function<std::optional<int>()>;

// run, when it was chosen
std::optional<int> chosen_run(const CLI::App* run_cmd, harbour::records::RunOptions& options) {
  if (!*run_cmd) return std::nullopt;
  if (options.exercise.empty() == options.route.empty()) {
    std::fprintf(stderr, "harboursim: run needs --exercise or --route (one of them)\n");
    return 2;
  }
  return harbour::records::run_exercise(options);
}

Command add_run(CLI::App& app) {
  auto options = std::make_shared<harbour::records::RunOptions>();
  harbour::records::RunOptions& run = *options;
  CLI::App* run_cmd = app.add_subcommand("run", "run an exercise headless");
  run_cmd->add_option("--exercise", run.exercise,
                      "exercise file, or a shipped exercise's name (sts_discharge)");
  run_cmd->add_option(
      "--route", run.route,
      "a training route the trainee is enrolled in: run its next stage (harboursim routes list)");
  run_cmd->add_flag("--autopilot", run.autopilot, "let the scripted operator drive");
  run_cmd->add_option("--record", run.record, "write the run's recording (HSRC) to this file");
  run_cmd->add_option("--trainee", run.trainee, "trainee id to store the attempt under");
  run_cmd->add_option("--command", run.commands,
                      "instructor command at a time, AT:KIND[:VALUES], repeatable: 40:gust:8:3, "
                      "60:hoist-brake-fault, 60:landed-sensor-fault:2, 90:clear-faults, 0:wind:12:270:0.15, "
                      "0:visibility:300, 0:rain:8, 0:time-of-day:21.5");
  run_cmd->add_option("--db", run.database,
                      "records connection (default: SQLite file in the user's data directory)");
  add_centre_options(run_cmd, run.centre, kCentreExercises);
  return [run_cmd, options]() { return chosen_run(run_cmd, *options); };
}

struct TraineesArguments {
  std::string database, trainee_id, trainee_name, results_trainee;
};

// trainees, when it was chosen
std::optional<int> chosen_trainees(const CLI::App* add_cmd, const CLI::App* list_cmd,
                                   const CLI::App* results_cmd, TraineesArguments& options) {
  if (*add_cmd) return harbour::apps::add_trainee(options.database, options.trainee_id, options.trainee_name);
  if (*list_cmd) return harbour::apps::list_trainees(options.database);
  if (*results_cmd) return harbour::apps::list_results(options.database, options.results_trainee);
  return std::nullopt;
}

Command add_trainees(CLI::App& app) {
  auto options = std::make_shared<TraineesArguments>();
  auto& [database, trainee_id, trainee_name, results_trainee] = *options;
  CLI::App* trainees_cmd = app.add_subcommand("trainees", "manage trainees");
  trainees_cmd->require_subcommand(1);
  trainees_cmd->add_option("--db", database, "records connection");
  trainees_cmd->fallthrough();  // --db also after "add ..." or "list"
  CLI::App* add_cmd = trainees_cmd->add_subcommand("add", "add a trainee");
  add_cmd->add_option("id", trainee_id, "trainee id")->required();
  add_cmd->add_option("name", trainee_name, "full name")->required();
  CLI::App* list_cmd = trainees_cmd->add_subcommand("list", "list trainees");
  CLI::App* results_cmd = app.add_subcommand("results", "list attempts, newest first");
  results_cmd->add_option("--trainee", results_trainee, "only this trainee's attempts");
  results_cmd->add_option("--db", database, "records connection");
  return [add_cmd, list_cmd, results_cmd, options]() {
    return chosen_trainees(add_cmd, list_cmd, results_cmd, *options);
  };
}

struct ReplayArguments {
  std::string recording, replay_exercise, replay_centre;
  std::int64_t replay_attempt = 0;
  double take_over_s = -1.0;
  harbour::records::RunOptions branch;
};

// replay, when it was chosen
std::optional<int> chosen_replay(const CLI::App* replay_cmd, ReplayArguments& options) {
  if (!*replay_cmd) return std::nullopt;
  auto& [recording, replay_exercise, replay_centre, replay_attempt, take_over_s, branch] = options;
  // a take-over's options mean nothing without it; a time that is not a number is no time
  const bool taking_over = replay_cmd->count("--take-over") > 0;
  if (taking_over && !(std::isfinite(take_over_s) && take_over_s >= 0.0)) {
    std::fprintf(stderr, "harboursim: --take-over needs a time in seconds, 0 or more\n");
    return 2;
  }
  const bool by_attempt = replay_cmd->count("--attempt") > 0;
  if (by_attempt == !recording.empty() || by_attempt == (replay_cmd->count("--exercise") > 0)) {
    std::fprintf(stderr, "harboursim: replay needs a recording file and --exercise, or --attempt alone\n");
    return 2;
  }
  if (by_attempt && taking_over) {
    std::fprintf(stderr, "harboursim: a stored attempt is taken over at a station (the console's replay)\n");
    return 2;
  }
  if (!by_attempt && replay_cmd->count("--exercises") > 0) {
    std::fprintf(stderr, "harboursim: replay --exercises is only for --attempt\n");
    return 2;
  }
  for (const char* option : {"--record", "--trainee", "--db"})
    if (!taking_over && !(by_attempt && std::string(option) == "--db") && replay_cmd->count(option) > 0) {
      std::fprintf(stderr, "harboursim: replay %s is only for a take-over (add --take-over SECONDS)\n",
                   option);
      return 2;
    }
  if (take_over_s >= 0.0) {
    branch.exercise = replay_exercise;
    branch.autopilot = true;
    return harbour::records::take_over_recording(recording, branch, take_over_s);
  }
  if (by_attempt) return harbour::records::replay_attempt(replay_attempt, branch.database, replay_centre);
  return harbour::records::replay_recording(recording, replay_exercise);
}

Command add_replay(CLI::App& app) {
  auto options = std::make_shared<ReplayArguments>();
  auto& [recording, replay_exercise, replay_centre, replay_attempt, take_over_s, branch] = *options;
  CLI::App* replay_cmd = app.add_subcommand("replay", "re-simulate a recording and check it bit for bit");
  replay_cmd->add_option("recording", recording, "recording file (or --attempt)")->check(CLI::ExistingFile);
  replay_cmd->add_option("--exercise", replay_exercise, "the exercise it was recorded on (file or name)");
  replay_cmd
      ->add_option(
          "--attempt", replay_attempt,
          "a stored attempt instead of a file: its recording as the records keep it (else its file), "
          "on the exercise version it ran (with --db)")
      ->check(CLI::PositiveNumber);
  replay_cmd->add_option("--exercises", replay_centre, "with --attempt: " + std::string(kCentreExercises));
  replay_cmd
      ->add_option("--take-over", take_over_s,
                   "instructor take-over at this time [s]: continue live from the recorded state as a new "
                   "attempt")
      ->check(CLI::NonNegativeNumber);
  replay_cmd->add_option("--record", branch.record, "with --take-over: write the branch's recording here");
  replay_cmd->add_option("--trainee", branch.trainee, "with --take-over: trainee the branch is stored under");
  replay_cmd->add_option("--db", branch.database, "with --take-over or --attempt: records connection");
  return [replay_cmd, options]() { return chosen_replay(replay_cmd, *options); };
}

// station, when it was chosen
std::optional<int> chosen_station(const CLI::App* station_cmd, harbour::station::StationOptions& options) {
  if (!*station_cmd) return std::nullopt;
  const harbour::station::StationOptions& live = options;
  const int chosen = !live.exercise.empty() + !live.route.empty() + !live.team.empty();
  if (live.serve ? chosen != 0 : chosen != 1) {
    std::fprintf(stderr,
                 "harboursim: station needs one of --exercise, --route or --team --role, or "
                 "--serve (a console chooses it)\n");
    return 2;
  }
  if (live.team.empty() != live.role.empty()) {
    std::fprintf(stderr, "harboursim: station --team needs --role, and --role a --team\n");
    return 2;
  }
  if (live.serve && live.name.empty()) {
    std::fprintf(stderr, "harboursim: station --serve needs --name (the station's name on the network)\n");
    return 2;
  }
  return harbour::station::run_station(live);
}

Command add_station(CLI::App& app) {
  auto options = std::make_shared<harbour::station::StationOptions>();
  harbour::station::StationOptions& live = *options;
  CLI::App* station_cmd = app.add_subcommand("station", "a trainee runs an exercise live at the station");
  station_cmd->add_option("--exercise", live.exercise,
                          "exercise file, or a shipped exercise's name (not with --serve: the console "
                          "chooses)");
  station_cmd->add_option("--profile", live.profile, "desktop, medium, immersive, or a profile file");
  station_cmd->add_option("--trainee", live.trainee, "trainee id to store the attempt under");
  station_cmd->add_option("--route", live.route,
                          "a training route the trainee is enrolled in: the station runs its next stage");
  station_cmd->add_option("--record", live.record, "write the attempt's recording (HSRC) to this file");
  station_cmd->add_option("--db", live.database, "records connection");
  station_cmd->add_flag("--autopilot", live.autopilot,
                        "the scripted operator drives (no input devices needed)");
  station_cmd->add_option("--time-scale", live.time_scale, "simulated seconds per second (fast-forward)")
      ->check(CLI::Range(0.1, 50.0));
  station_cmd->add_option("--seconds", live.seconds, "stop after this many seconds (interrupted)")
      ->check(CLI::NonNegativeNumber);
  station_cmd->add_option("--window", live.window,
                          "the trainee's window: on, off, auto (where there is a display)");
  station_cmd->add_option("--sound", live.sound,
                          "the cab's sound on the profile's output: on, off, auto (with the window)");
  station_cmd->add_option("--name", live.name,
                          "the station's name on the centre's network: consoles see and command it");
  station_cmd->add_option("--domain", live.domain, "the centre's DDS domain (0-232)")
      ->check(CLI::Range(0, 232));
  add_centre_options(station_cmd, live.centre, kCentreExercises);
  station_cmd->add_option("--team", live.team,
                          "a team exercise (a file, or a shipped team's name): this station is one member, "
                          "the others' machines drawn where their stations have them");
  station_cmd->add_option("--role", live.role,
                          "this station's role in the --team (it runs the role's exercise)");
  station_cmd->add_flag("--serve", live.serve,
                        "wait for a console to start exercises, one after another (needs --name)");
  return [station_cmd, options]() { return chosen_station(station_cmd, *options); };
}

Command add_channel(CLI::App& app) {
  auto options = std::make_shared<harbour::station::ChannelOptions>();
  harbour::station::ChannelOptions& o = *options;
  CLI::App* cmd = app.add_subcommand(
      "channel", "one display of an immersive station drawn on this host, frame-locked with its others");
  cmd->add_option("--station", o.station, "the station's name on the centre's network")->required();
  cmd->add_option("--display", o.display, "the profile's display to draw (one marked remote)")->required();
  cmd->add_option("--profile", o.profile, "the station's profile: a shipped one's name or a file");
  cmd->add_option("--domain", o.domain, "the centre's DDS domain (0-232)")->check(CLI::Range(0, 232));
  cmd->add_option("--window", o.window, "on, off, auto (where there is a display)");
  cmd->add_option("--size", o.size, "WIDTHxHEIGHT: draw at this size, not the display's");
  cmd->add_option("--seconds", o.seconds, "stop after this many seconds")->check(CLI::NonNegativeNumber);
  cmd->add_option("--picture", o.picture, "at the end, write the last picture shown here (PNG)");
  cmd->add_option("--log", o.log, "write a CSV line per frame shown (frame, step, time, when, drawing time)");
  return [cmd, options]() -> std::optional<int> {
    if (!*cmd) return std::nullopt;
    return harbour::station::run_channel(*options);
  };
}

// devices, when it was chosen
std::optional<int> chosen_devices(const CLI::App* devices_cmd, harbour::station::DevicesOptions& options) {
  if (!*devices_cmd) return std::nullopt;
  return harbour::station::run_devices(options);
}

Command add_devices(CLI::App& app) {
  auto options = std::make_shared<harbour::station::DevicesOptions>();
  harbour::station::DevicesOptions& devices = *options;
  CLI::App* devices_cmd = app.add_subcommand("devices", "list, watch, bind and calibrate input devices");
  devices_cmd->add_flag("--watch", devices.watch, "show live values (q quits)");
  devices_cmd->add_option("--bind", devices.bind,
                          "walk through the machine's controls and write this mapping file");
  devices_cmd->add_option("--machine", devices.machine,
                          "machine file whose controls are bound (default: the STS)");
  devices.machine = harbour::records::shipped_data_folder() + "/machines/sts.yaml";
  devices_cmd->add_option("--name", devices.name, "the mapping's name");
  devices_cmd->add_option("--virtual", devices.virtual_device,
                          "NAME:AXES:BUTTONS:HATS: add a virtual joystick (testing without hardware)");
  devices_cmd->add_option(
      "--virtual-port", devices.virtual_port,
      "UDP port on loopback that moves the virtual joystick ('axis 1 -32768', 'button 0 1')");
  return [devices_cmd, options]() { return chosen_devices(devices_cmd, *options); };
}

struct ScreenshotArguments {
  harbour::debrief::ScreenshotOptions shot;
  double shot_time_of_day = -1.0, shot_visibility = -1.0, shot_rain = -1.0, shot_cloud = -1.0;
  std::string shot_size = "1280x720";
};

// screenshot, when it was chosen
std::optional<int> chosen_screenshot(const CLI::App* shot_cmd, ScreenshotArguments& options) {
  if (!*shot_cmd) return std::nullopt;
  auto& [shot, shot_time_of_day, shot_visibility, shot_rain, shot_cloud, shot_size] = options;
  if (std::sscanf(shot_size.c_str(), "%dx%d", &shot.width, &shot.height) != 2 || shot.width < 16 ||
      shot.height < 16 || shot.width > 8192 || shot.height > 8192) {
    std::fprintf(stderr, "harboursim: --size %s: WIDTHxHEIGHT, 16-8192 each\n", shot_size.c_str());
    return 2;
  }
  if (shot_time_of_day >= 0.0) shot.time_of_day_h = shot_time_of_day;
  if (shot_visibility > 0.0) shot.visibility_m = shot_visibility;
  if (shot_rain >= 0.0) shot.rain_mm_per_h = shot_rain;
  if (shot_cloud >= 0.0) shot.cloud_oktas = shot_cloud;
  return harbour::debrief::take_screenshot(shot);
}

Command add_screenshot(CLI::App& app) {
  auto options = std::make_shared<ScreenshotArguments>();
  auto& [shot, shot_time_of_day, shot_visibility, shot_rain, shot_cloud, shot_size] = *options;
  CLI::App* shot_cmd = app.add_subcommand("screenshot", "draw a moment of an exercise (headless) into a PNG");
  shot_cmd->add_option("--exercise", shot.exercise, "exercise file or shipped name")->required();
  shot_cmd->add_option("--at", shot.at_s, "seconds into the exercise (the autopilot drives there)")
      ->check(CLI::Range(0.0, 3600.0));
  shot_cmd->add_option("--view", shot.view, "cab, chase, free, spreader, boom_tip");
  shot_cmd->add_option("--size", shot_size, "WIDTHxHEIGHT");
  shot_cmd->add_option("--out", shot.out, "PNG file")->required();
  shot_cmd->add_option("--time-of-day", shot_time_of_day, "hours, 0-24")->check(CLI::Range(0.0, 23.999));
  shot_cmd->add_option("--visibility", shot_visibility, "metres")->check(CLI::Range(1.0, 1e5));
  shot_cmd->add_option("--rain", shot_rain, "mm/h")->check(CLI::Range(0.0, 500.0));
  shot_cmd->add_option("--cloud", shot_cloud, "oktas, 0-8")->check(CLI::Range(0.0, 8.0));
  shot_cmd->add_option("--command", shot.commands,
                       "instructor command on the way there, AT:KIND[:VALUES], repeatable (as for run): "
                       "30:power-failure");
  shot_cmd->add_option("--soft-shadows", shot.soft_shadows,
                       "filtered shadow edges, true or false (default: on, off on a software renderer)");
  shot_cmd->add_option(
      "--surface-detail", shot.surface_detail,
      "surfaces with detail (worn paint, stained concrete, grain, rust streaks), true or false "
      "(default: on, off on a software renderer)");
  shot_cmd
      ->add_option("--multisamples", shot.multisamples,
                   "anti-aliasing samples per pixel, 0-16 (default: 4, 0 on a software renderer)")
      ->check(CLI::Range(0, 16));
  shot_cmd->add_option("--looks", shot.looks, "look file to draw with (default: the shipped one)")
      ->check(CLI::ExistingFile);
  shot_cmd->add_option("--camera", shot.camera, "free view: X,Y,Z metres, YAW,PITCH degrees")
      ->delimiter(',')
      ->expected(5)
      ->check(CLI::Range(-1e4, 1e4));
  return [shot_cmd, options]() { return chosen_screenshot(shot_cmd, *options); };
}

struct RenderArguments {
  harbour::debrief::RenderOptions video;
  std::string video_size = "960x540";
};

// render, when it was chosen
std::optional<int> chosen_render(const CLI::App* render_cmd, RenderArguments& options) {
  if (!*render_cmd) return std::nullopt;
  auto& [video, video_size] = options;
  if (video.out.empty() && video.audio.empty()) {
    std::fprintf(stderr, "harboursim render: --out (a video) or --audio (its sound), or both\n");
    return 2;
  }
  if (std::sscanf(video_size.c_str(), "%dx%d", &video.width, &video.height) != 2 || video.width < 16 ||
      video.height < 16 || video.width > 3840 || video.height > 2160 || video.width % 2 || video.height % 2) {
    std::fprintf(stderr, "harboursim: --size %s: WIDTHxHEIGHT, even, 16-3840 by 16-2160\n",
                 video_size.c_str());
    return 2;
  }
  return harbour::debrief::render_video(video);
}

Command add_render(CLI::App& app) {
  auto options = std::make_shared<RenderArguments>();
  auto& [video, video_size] = *options;
  CLI::App* render_cmd =
      app.add_subcommand("render", "draw a recording into a debrief video (MP4, with ffmpeg)");
  render_cmd->add_option("recording", video.recording, "recording file")
      ->required()
      ->check(CLI::ExistingFile);
  render_cmd->add_option("--exercise", video.exercise, "the exercise it was recorded on")->required();
  render_cmd->add_option("--out", video.out, "MP4 file (the video, with its sound)");
  render_cmd->add_option("--audio", video.audio, "WAV file (the sound alone)");
  render_cmd->add_flag("!--no-sound", video.sound, "a silent video");
  render_cmd->add_flag("--headphones", video.headphones, "the sound through the HRTF, for headphones");
  render_cmd->add_option("--view", video.view, "cab, chase, free, spreader, boom_tip");
  render_cmd->add_option("--size", video_size, "WIDTHxHEIGHT (even numbers)");
  render_cmd->add_option("--fps", video.fps, "frames per second")->check(CLI::Range(1.0, 60.0));
  render_cmd->add_option("--from", video.from_s, "start [s]")->check(CLI::Range(0.0, 86400.0));
  render_cmd->add_option("--to", video.to_s, "end [s]")->check(CLI::Range(0.0, 86400.0));
  return [render_cmd, options]() { return chosen_render(render_cmd, *options); };
}

// console, when it was chosen
std::optional<int> chosen_console(const CLI::App* console_cmd, harbour::console::ConsoleOptions& options) {
  if (!*console_cmd) return std::nullopt;
  return harbour::console::run_console(options);
}

Command add_console(CLI::App& app) {
  auto options = std::make_shared<harbour::console::ConsoleOptions>();
  harbour::console::ConsoleOptions& console = *options;
  CLI::App* console_cmd = app.add_subcommand(
      "console", "the instructor console: a web application watching and commanding stations");
  console_cmd->add_option("--bind", console.bind, "the address to listen on (default: this machine only)");
  console_cmd->add_option("--port", console.port, "HTTP port (0: any free one)")->check(CLI::Range(0, 65535));
  console_cmd->add_option("--db", console.database,
                          "records connection (accounts, audit, trainees, attempts)");
  console_cmd->add_option("--domain", console.domain, "the centre's DDS domain (0-232)")
      ->check(CLI::Range(0, 232));
  console_cmd->add_option("--name", console.name, "the console's name on the network");
  console_cmd->add_option("--tls-cert", console.tls_certificate,
                          "serve HTTPS with this PEM certificate chain (required with a network --bind)");
  console_cmd->add_option("--tls-key", console.tls_key, "the certificate's PEM private key");
  console_cmd->add_option("--web", console.web_root, "the built pages (default: web/dist)");
  console_cmd->add_option("--allow-origin", console.allowed_origins,
                          "another origin whose pages may use the console (a reverse proxy's "
                          "https://HOST[:PORT]); repeatable");
  console_cmd->add_option("--lrs", console.lrs,
                          "send the attempts' xAPI statements to this LRS (http://HOST:PORT/xAPI/)");
  console_cmd->add_option("--lrs-auth-file", console.lrs_auth_file,
                          "the LRS's credentials: one line user:password");
  console_cmd->add_option("--centre-iri", console.centre_iri, kCentreIri);
  add_centre_options(console_cmd, console.centre,
                     "the centre's exercise folder the designer saves in (default: data/exercises)");
  console_cmd->add_option("--seconds", console.seconds, "stop after this long (default: Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  return [console_cmd, options]() { return chosen_console(console_cmd, *options); };
}

struct AccountsArguments {
  std::string account_name, account_role, account_trainee, account_db;
};

// accounts, when it was chosen
std::optional<int> chosen_accounts(const CLI::App* account_add_cmd, const CLI::App* account_list_cmd,
                                   AccountsArguments& options) {
  if (*account_list_cmd) return harbour::console::list_accounts(options.account_db);
  if (*account_add_cmd)
    return harbour::console::add_account(options.account_db, options.account_name, options.account_role,
                                         options.account_trainee);
  return std::nullopt;
}

Command add_accounts(CLI::App& app) {
  auto options = std::make_shared<AccountsArguments>();
  auto& [account_name, account_role, account_trainee, account_db] = *options;
  CLI::App* accounts_cmd = app.add_subcommand("accounts", "console accounts");
  accounts_cmd->require_subcommand(1);
  accounts_cmd->add_option("--db", account_db, "records connection");
  accounts_cmd->fallthrough();
  CLI::App* account_add_cmd =
      accounts_cmd->add_subcommand("add", "add an account; its password is read from standard input");
  account_add_cmd->add_option("name", account_name, "account name")->required();
  account_add_cmd->add_option("--role", account_role, "administrator, instructor, signaller or trainee")
      ->required();
  account_add_cmd->add_option("--trainee", account_trainee, "a trainee account's trainee id");
  CLI::App* account_list_cmd = accounts_cmd->add_subcommand("list", "list accounts (name and role)");
  return [account_add_cmd, account_list_cmd, options]() {
    return chosen_accounts(account_add_cmd, account_list_cmd, *options);
  };
}

struct RoutesArguments {
  std::string route_id, route_trainee, route_stage, route_reason, route_db;
  harbour::records::CentreFolders route_centre;
};

// routes, when it was chosen
std::optional<int> chosen_routes(const CLI::App* routes_list_cmd, const CLI::App* routes_show_cmd,
                                 const CLI::App* routes_enrol_cmd,
                                 const std::array<CLI::App*, 2>& decision_cmds, RoutesArguments& options) {
  auto& [route_id, route_trainee, route_stage, route_reason, route_db, route_centre] = options;
  if (*routes_list_cmd) return harbour::apps::list_routes(route_centre);
  if (*routes_show_cmd) return harbour::apps::show_route(route_db, route_centre, route_id, route_trainee);
  if (*routes_enrol_cmd) return harbour::apps::enrol_trainee(route_db, route_centre, route_trainee, route_id);
  for (int n = 0; n < 2; ++n)
    if (*decision_cmds[n])
      return harbour::apps::decide_stage(route_db, route_centre, route_trainee, route_id, route_stage,
                                         n == 0 ? "sign_off" : "retry", route_reason);
  return std::nullopt;
}

Command add_routes(CLI::App& app) {
  auto options = std::make_shared<RoutesArguments>();
  auto& [route_id, route_trainee, route_stage, route_reason, route_db, route_centre] = *options;
  CLI::App* routes_cmd = app.add_subcommand("routes", "training routes: stages, enrolment, progress");
  routes_cmd->require_subcommand(1);
  routes_cmd->add_option("--db", route_db, "records connection");
  add_centre_options(routes_cmd, route_centre, kCentreExercises);
  routes_cmd->fallthrough();
  CLI::App* routes_list_cmd =
      routes_cmd->add_subcommand("list", "the routes (the centre's and the shipped ones) and their stages");
  CLI::App* routes_show_cmd =
      routes_cmd->add_subcommand("show", "a route's stages, with a trainee's progress");
  routes_show_cmd->add_option("route", route_id, "route name")->required();
  routes_show_cmd->add_option("--trainee", route_trainee, "show this trainee's progress");
  CLI::App* routes_enrol_cmd = routes_cmd->add_subcommand("enrol", "enrol a trainee in a route");
  routes_enrol_cmd->add_option("trainee", route_trainee, "trainee id")->required();
  routes_enrol_cmd->add_option("route", route_id, "route name")->required();
  std::array<CLI::App*, 2> decision_cmds{};
  const char* decisions[2][2] = {{"sign-off", "count a stage as passed (an instructor's decision)"},
                                 {"retry", "grant a blocked stage another round of attempts"}};
  for (int n = 0; n < 2; ++n) {
    decision_cmds[n] = routes_cmd->add_subcommand(decisions[n][0], decisions[n][1]);
    decision_cmds[n]->add_option("trainee", route_trainee, "trainee id")->required();
    decision_cmds[n]->add_option("route", route_id, "route name")->required();
    decision_cmds[n]->add_option("stage", route_stage, "stage id")->required();
    decision_cmds[n]->add_option("--reason", route_reason, "why (stored with the decision)")->required();
  }
  return [routes_list_cmd, routes_show_cmd, routes_enrol_cmd, decision_cmds, options]() {
    return chosen_routes(routes_list_cmd, routes_show_cmd, routes_enrol_cmd, decision_cmds, *options);
  };
}

struct ReportArguments {
  std::string report_db, report_trainee, report_out;
  harbour::records::CentreFolders report_centre;
};

// report, when it was chosen
std::optional<int> chosen_report(const CLI::App* report_trainee_cmd, const CLI::App* report_class_cmd,
                                 ReportArguments& options) {
  auto& [report_db, report_trainee, report_out, report_centre] = options;
  if (*report_trainee_cmd && report_trainee.empty()) {
    std::fprintf(stderr, "harboursim: report trainee needs a trainee id\n");
    return 2;
  }
  if (*report_trainee_cmd)
    return harbour::apps::write_report(report_db, report_centre, report_trainee, report_out);
  if (*report_class_cmd) return harbour::apps::write_report(report_db, report_centre, "", report_out);
  return std::nullopt;
}

Command add_report(CLI::App& app) {
  auto options = std::make_shared<ReportArguments>();
  auto& [report_db, report_trainee, report_out, report_centre] = *options;
  CLI::App* report_cmd = app.add_subcommand("report", "a trainee's or the class's report, as PDF or HTML");
  report_cmd->require_subcommand(1);
  report_cmd->add_option("--db", report_db, "records connection");
  add_centre_options(report_cmd, report_centre, kCentreExercises);
  report_cmd->add_option("--out", report_out, "the file to write: .pdf (printed by chromium) or .html")
      ->required();
  report_cmd->fallthrough();
  CLI::App* report_trainee_cmd = report_cmd->add_subcommand(
      "trainee", "a trainee's evolution, routes, attempts and standing in the cohort");
  report_trainee_cmd->add_option("trainee", report_trainee, "trainee id")->required();
  CLI::App* report_class_cmd = report_cmd->add_subcommand("class", "every trainee side by side");
  return [report_trainee_cmd, report_class_cmd, options]() {
    return chosen_report(report_trainee_cmd, report_class_cmd, *options);
  };
}

struct XapiArguments {
  std::string xapi_db, xapi_lrs, xapi_auth_file, xapi_centre_iri;
  bool xapi_watch = false;
  harbour::records::CentreFolders xapi_folders;
};

// xapi, when it was chosen
std::optional<int> chosen_xapi(const CLI::App* xapi_status_cmd, const CLI::App* xapi_send_cmd,
                               XapiArguments& options) {
  auto& [xapi_db, xapi_lrs, xapi_auth_file, xapi_centre_iri, xapi_watch, xapi_folders] = options;
  if (*xapi_status_cmd) return harbour::apps::xapi_status(xapi_db);
  if (*xapi_send_cmd)
    return harbour::apps::xapi_send(xapi_db, xapi_lrs, xapi_auth_file, xapi_watch,
                                    harbour::records::xapi_centre(xapi_centre_iri, xapi_folders));
  return std::nullopt;
}

Command add_xapi(CLI::App& app) {
  auto options = std::make_shared<XapiArguments>();
  auto& [xapi_db, xapi_lrs, xapi_auth_file, xapi_centre_iri, xapi_watch, xapi_folders] = *options;
  CLI::App* xapi_cmd =
      app.add_subcommand("xapi", "the attempts' xAPI statements and the Learning Record Store");
  xapi_cmd->require_subcommand(1);
  xapi_cmd->add_option("--db", xapi_db, "records connection");
  xapi_cmd->fallthrough();
  CLI::App* xapi_status_cmd =
      xapi_cmd->add_subcommand("status", "the outbox: queued, sent, rejected, errors");
  CLI::App* xapi_send_cmd = xapi_cmd->add_subcommand("send", "send the due statements to an LRS");
  xapi_send_cmd->add_option("--lrs", xapi_lrs, "the LRS's xAPI endpoint (http://HOST:PORT/xAPI/)")
      ->required();
  xapi_send_cmd->add_option("--lrs-auth-file", xapi_auth_file, "a file holding one line user:password");
  xapi_send_cmd->add_flag("--watch", xapi_watch, "keep sending as statements come, until Ctrl-C");
  xapi_send_cmd->add_option("--centre-iri", xapi_centre_iri, kCentreIri);
  xapi_send_cmd->add_option("--exercises", xapi_folders.exercises, kCentreExercises);
  return [xapi_status_cmd, xapi_send_cmd, options]() {
    return chosen_xapi(xapi_status_cmd, xapi_send_cmd, *options);
  };
}

// bulk demo, when it was chosen
std::optional<int> chosen_bulk_demo(const CLI::App* demo_cmd, harbour::apps::BulkDemoOptions& options) {
  if (!*demo_cmd) return std::nullopt;
  return harbour::apps::run_bulk_demo(options);
}

Command add_bulk_demo(CLI::App& app) {
  auto options = std::make_shared<harbour::apps::BulkDemoOptions>();
  harbour::apps::BulkDemoOptions& demo = *options;
  CLI::App* demo_cmd =
      app.add_subcommand("bulk-demo", "a grab digs coal from a yard heap into a rolling hold");
  demo_cmd->add_option("--data", demo.data_dir, "data folder");
  demo_cmd->add_option("--out", demo.out_dir, "output folder");
  demo_cmd->add_option("--cycles", demo.cycles, "grab cycles")->check(CLI::PositiveNumber);
  return [demo_cmd, options]() { return chosen_bulk_demo(demo_cmd, *options); };
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"harboursim: harbour crane training simulator"};
  app.require_subcommand(1);
  const std::vector<Command> commands = {
      add_run(app),     add_trainees(app),   add_replay(app), add_station(app),  add_channel(app),
      add_devices(app), add_screenshot(app), add_render(app), add_console(app),  add_accounts(app),
      add_routes(app),  add_report(app),     add_xapi(app),   add_bulk_demo(app)};
  CLI11_PARSE(app, argc, argv);
  try {
    for (const Command& command : commands)
      if (const std::optional<int> status = command()) return *status;
    return 2;  // CLI11 asks for one subcommand: not reached
  } catch (const std::exception& e) {
    std::fprintf(stderr, "harboursim: %s\n", e.what());
    return 1;
  }
}
