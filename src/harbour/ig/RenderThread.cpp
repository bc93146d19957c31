#include "harbour/ig/RenderThread.h"

#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>

namespace harbour::ig {

RenderThread::RenderThread(scene::SceneDescription scene, Looks looks, int width, int height,
                           std::vector<View> views, Source source, FrameSink sink, double max_fps,
                           BulkSource bulk, Priority priority)
    : source_(std::move(source)),
      sink_(std::move(sink)),
      bulk_(std::move(bulk)),
      max_fps_(max_fps),
      priority_(priority) {
  thread_ = std::thread([this, scene = std::move(scene), looks = std::move(looks), width, height,
                         views = std::move(views)]() mutable {
    run(std::move(scene), std::move(looks), width, height, std::move(views));
  });
}

RenderThread::~RenderThread() {
  stop();
}

void RenderThread::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

double RenderThread::fps() const {
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return s > 0.0 ? static_cast<double>(frames_.load()) / s : 0.0;
}

void RenderThread::rename_entity(std::size_t index, std::string name) {
  const std::lock_guard lock(requests_mutex_);
  renames_.emplace_back(index, std::move(name));
}

void RenderThread::set_overlay(std::string text) {
  const std::lock_guard lock(requests_mutex_);
  overlay_ = std::move(text);
  overlay_changed_ = true;
}

std::string RenderThread::error() const {
  const std::lock_guard lock(error_mutex_);
  return error_;
}

void RenderThread::run(scene::SceneDescription scene, Looks looks, int width, int height,
                       std::vector<View> views) {
  // below the simulation: this thread and the renderer's workers it starts run only when the step and the
  // record keeper leave a core free (SCHED_IDLE; nice +10 where that is refused)
  const sched_param idle{0};
  if (priority_ == Priority::kBelowSimulation && sched_setscheduler(0, SCHED_IDLE, &idle) != 0)
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
  try {
    ImageGenerator generator(scene, std::move(looks.visuals), width, height);
    generator.use(looks);
    std::int64_t last_step = -1;
    start_ = std::chrono::steady_clock::now();
    auto next_frame = start_;
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(max_fps_ > 0.0 ? 1.0 / max_fps_ : 0.0));
    while (running_.load()) {
      if (max_fps_ > 0.0) {
        std::this_thread::sleep_until(next_frame);
        next_frame = std::max(next_frame + period, std::chrono::steady_clock::now() - period);
      }
      const scene::Snapshot* s = source_();
      if (!s || s->step == last_step) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      last_step = s->step;
      {
        const std::lock_guard lock(requests_mutex_);
        if (overlay_changed_) generator.set_overlay(overlay_);
        overlay_changed_ = false;
        for (const auto& [index, name] : renames_)
          generator.rename_entity(index, name);
        renames_.clear();
      }
      generator.update(*s);
      if (const scene::BulkView* material = bulk_ ? bulk_() : nullptr)
        generator.update_bulk(*material);               // meshes again only the tiles that changed
      for (std::size_t c = 0; c < views.size(); ++c) {  // every display channel of the same moment
        generator.set_view(views[c]);
        generator.render();
        if (sink_) sink_(generator, *s, static_cast<int>(c));
      }
      ++frames_;
    }
  } catch (const std::exception& e) {
    const std::lock_guard lock(error_mutex_);
    error_ = e.what();
  }
}

}  // namespace harbour::ig
