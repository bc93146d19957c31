#include "harbour/debrief/RenderVideo.h"

#include <osg/Image>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "harbour/audio/AudioOut.h"
#include "harbour/audio/SoundFile.h"
#include "harbour/bulk/BulkPublish.h"
#include "harbour/ig/ImageGenerator.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/records/Centre.h"
#include "harbour/records/HeadlessRun.h"
#include "harbour/sim/Recording.h"

namespace harbour::debrief {

namespace {

/// ffmpeg reading raw RGB frames on its standard input (started without a shell: a file name is never a
/// command).
class Encoder {
 public:
  Encoder(const std::string& out, int width, int height, double fps) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("render: no pipe to ffmpeg");
    pid_ = fork();
    if (pid_ == 0) {
      dup2(fds[0], STDIN_FILENO);
      close(fds[0]);
      close(fds[1]);
      const std::string size = std::to_string(width) + "x" + std::to_string(height),
                        rate = std::to_string(fps);
      execlp("ffmpeg", "ffmpeg", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
             size.c_str(), "-r", rate.c_str(), "-i", "-", "-pix_fmt", "yuv420p", "-c:v", "libx264", "-preset",
             "veryfast", out.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[0]);
    if (pid_ < 0) throw std::runtime_error("render: cannot start ffmpeg");
    pipe_ = fdopen(fds[1], "wb");
  }
  ~Encoder() { finish(); }
  void frame(const osg::Image& image) {
    // OpenGL's rows bottom first; a video's top first
    const std::size_t row = static_cast<std::size_t>(image.s()) * 3;
    const int bytes = static_cast<int>(image.getPixelSizeInBits() / 8);
    row_.resize(row);
    for (int y = image.t() - 1; y >= 0; --y) {
      const unsigned char* from = image.data(0, y);
      for (int x = 0; x < image.s(); ++x)
        for (int c = 0; c < 3; ++c)
          row_[static_cast<std::size_t>(3 * x + c)] = from[bytes * x + c];
      if (std::fwrite(row_.data(), 1, row, pipe_) != row)
        throw std::runtime_error("render: ffmpeg stopped reading");
    }
  }
  /// Closes the stream and waits; true if ffmpeg wrote the file.
  bool finish() {
    if (!pipe_) return status_ == 0;
    std::fclose(pipe_);
    pipe_ = nullptr;
    int status = 0;
    waitpid(pid_, &status, 0);
    status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 1;
    return status_ == 0;
  }

 private:
  pid_t pid_ = -1;
  std::FILE* pipe_ = nullptr;
  int status_ = 1;
  std::vector<unsigned char> row_;
};

/// Runs ffmpeg with `arguments` (no shell) and waits; true when it succeeded.
bool run_ffmpeg(std::vector<std::string> arguments) {
  arguments.insert(arguments.begin(), {"ffmpeg", "-y", "-loglevel", "error"});
  std::vector<char*> argv;
  for (std::string& a : arguments)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    execvp("ffmpeg", argv.data());
    _exit(127);
  }
  if (pid < 0) return false;
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace

int render_video(const RenderOptions& options) {
  for (const auto& [flag, path] : {std::pair{"--out", options.out}, std::pair{"--audio", options.audio}})
    if (!path.empty())
      if (const std::string why = io::why_not_writable(path); !why.empty())
        throw std::runtime_error(std::string(flag) + " " + path + ": " + why);
  const bool drawing = !options.out.empty(), hearing = !options.audio.empty() || (drawing && options.sound);
  const sim::Recording recording = io::read_recording(options.recording);
  const sim::ExerciseSettings exercise =
      records::load_resolved_exercise(records::resolve_exercise(options.exercise));
  if (recording.scenario != exercise.name)
    throw std::runtime_error(options.recording + " was recorded on exercise '" + recording.scenario +
                             "', not '" + exercise.name + "'");
  const double end_s = options.to_s >= 0.0
                           ? options.to_s
                           : static_cast<double>(recording.total_steps) * sim::Simulation::kStep_s;
  const auto stop_step = static_cast<std::int64_t>(end_s / sim::Simulation::kStep_s);
  ig::Looks looks =
      ig::load_shipped_looks(records::shipped_data_folder(), sim::machine_kinds(), exercise.machine_file);
  std::unique_ptr<ig::ImageGenerator> generator;
  const ig::View view = ig::view_named(options.view);
  // first the attempt's events, for the timeline bar and the captions: a replay without drawing
  struct Event {
    double time_s;
    std::string text;
    core::Vec3 color;
  };
  std::vector<Event> events;
  sim::Evaluator evaluator(exercise);
  sim::replay(exercise.scenario, recording, stop_step,
              [&](const sim::Simulation& s, const scene::Controls& controls) {
                const sim::Metrics before = evaluator.metrics();
                evaluator.observe(s, controls);
                const sim::Metrics& now = evaluator.metrics();
                const auto note = [&](int was, int is, const char* what, const core::Vec3& color) {
                  for (int n = was; n < is; ++n) {
                    char text[96];
                    std::snprintf(text, sizeof text, "%.1f s: %s", s.time_s(), what);
                    events.push_back({s.time_s(), text, color});
                  }
                };
                const core::Vec3 good{0.3, 0.9, 0.3}, bad{1.0, 0.2, 0.15}, warning{1.0, 0.75, 0.1};
                note(before.moves_completed, now.moves_completed, "move completed", good);
                note(before.collisions, now.collisions, "COLLISION", bad);
                note(before.hard_landings, now.hard_landings, "hard landing", warning);
                note(before.twistlock_misuse, now.twistlock_misuse, "twistlock misuse", bad);
                note(before.overloads, now.overloads, "rope overload", bad);
                note(before.emergency_stops, now.emergency_stops, "emergency stop", warning);
                note(before.load_drops, now.load_drops, "LOAD DROPPED", bad);
                note(before.lifts_under_fault, now.lifts_under_fault, "lift with the brake failed", bad);
              });
  std::vector<ig::ImageGenerator::TimelineMark> marks;
  for (const Event& e : events)
    if (e.time_s >= options.from_s && e.time_s <= end_s) marks.push_back({e.time_s, e.color});

  // the video without its sound first (ffmpeg then muxes the two)
  const std::string silent_video = options.out + ".silent.mp4";
  std::unique_ptr<Encoder> encoder;
  if (drawing)
    encoder = std::make_unique<Encoder>(hearing ? silent_video : options.out, options.width, options.height,
                                        options.fps);
  auto snapshot = std::make_unique<scene::Snapshot>();
  double next_frame_s = options.from_s;
  long frames = 0;
  scene::BulkView bulk_view;  // the material's heights, copied tile by tile as they change
  // the sound: a 10 ms block ending at every tenth step from the start of the span
  std::unique_ptr<audio::OfflineMix> sound;
  const audio::SoundSettings sounds =
      hearing ? audio::load_shipped_sounds(records::shipped_data_folder(), sim::machine_kinds(),
                                           exercise.machine_file)
              : audio::SoundSettings{};
  audio::AudioSettings listening;
  listening.speakers = options.headphones ? audio::Speakers::kHeadphones : audio::Speakers::kStereo;
  const auto from_step =
      static_cast<std::int64_t>(std::ceil(options.from_s / sim::Simulation::kStep_s - 1e-9));
  auto heard = std::make_unique<scene::Snapshot>();
  std::ptrdiff_t load_entity = 0;  // the truck's "load" (past the scene's end: none)
  std::string load_name;           // the name it is drawn by ("" : "load")
  const sim::ReplayResult result = sim::replay(
      exercise.scenario, recording, stop_step, [&](const sim::Simulation& s, const scene::Controls&) {
        const std::int64_t step = s.steps();
        if (hearing && step >= from_step && (step - from_step) % 10 == 0) {
          if (!sound) {
            sound = std::make_unique<audio::OfflineMix>(s.scene(), sounds, listening);
            try {
              sound->scape().set_radio_script(exercise.radio);
            } catch (const audio::AudioError& e) {
              std::printf("no radio: %s\n", e.what());
            }
          }
          s.write_snapshot(*heard);
          sound->add_block(*heard);
        }
        if (!drawing || s.time_s() + 1e-9 < next_frame_s) return;
        next_frame_s += 1.0 / options.fps;
        if (!generator) {
          generator =
              std::make_unique<ig::ImageGenerator>(s.scene(), looks.visuals, options.width, options.height);
          generator->use(looks);
          const std::vector<std::string> names = generator->view_names();
          if (std::find(names.begin(), names.end(), options.view) == names.end())
            throw std::runtime_error("--view " + options.view + ": not a view of this scene");
          generator->set_view(view);
          generator->set_timeline(options.from_s, end_s, marks);
          const auto& entities = s.scene().entities;
          load_entity = std::find_if(entities.begin(), entities.end(),
                                     [](const scene::SceneDescription::Entity& e) {
                                       return e.name == scene::kTrailerLoad;
                                     }) -
                        entities.begin();
        }
        // a box handed onto this truck in a team session: drawn by its name from then on
        if (load_entity < static_cast<std::ptrdiff_t>(s.scene().entities.size())) {
          const std::string handed = sim::handed_load_name(recording, s.steps());
          if (handed != load_name) {
            load_name = handed;
            generator->rename_entity(static_cast<std::size_t>(load_entity),
                                     handed.empty() ? scene::kTrailerLoad : handed);
          }
        }
        std::string caption;  // the events of the last 6 s
        for (const Event& e : events)
          if (e.time_s <= s.time_s() && e.time_s > s.time_s() - 6.0) caption += e.text + "   ";
        generator->set_caption(caption);
        s.write_snapshot(*snapshot);
        generator->update(*snapshot);
        if (const bulk::BulkWorld* material = s.bulk()) {
          bulk::publish(*material, bulk_view);
          generator->update_bulk(bulk_view);
        }
        encoder->frame(generator->render());
        ++frames;
      });
  if (encoder && !encoder->finish())
    throw std::runtime_error(options.out + ": ffmpeg could not write the video");
  const char* diverged =
      result.first_mismatch ? " -- the replay diverged from the recording (another build?)" : "";
  if (sound) {
    const std::string wav = options.audio.empty() ? options.out + ".sound.wav" : options.audio;
    audio::write_wav(wav, sound->samples(), sound->channels(), audio::AudioOut::kSampleRate_hz);
    if (!options.audio.empty())
      std::printf(
          "%s: %.1f s of sound (%s)%s\n", wav.c_str(),
          static_cast<double>(sound->samples().size()) / sound->channels() / audio::AudioOut::kSampleRate_hz,
          options.headphones ? "headphones" : "speakers", diverged);
    if (drawing) {
      const bool muxed = run_ffmpeg({"-i", silent_video, "-i", wav, "-c:v", "copy", "-c:a", "aac", "-b:a",
                                     "192k", "-shortest", options.out});
      std::remove(silent_video.c_str());
      if (options.audio.empty()) std::remove(wav.c_str());
      if (!muxed) throw std::runtime_error(options.out + ": ffmpeg could not add the sound to the video");
    }
  }
  if (drawing)
    std::printf("%s: %ld frames (%.1f-%.1f s at %.0f fps, %s view, %dx%d%s)%s\n", options.out.c_str(), frames,
                options.from_s, end_s, options.fps, options.view.c_str(), options.width, options.height,
                hearing ? ", with sound" : "", diverged);
  records::print_evaluation(evaluator.metrics(), evaluator.score());
  return result.first_mismatch ? 1 : 0;
}

}  // namespace harbour::debrief
