#include "harbour/audio/SoundThread.h"

#include <chrono>

namespace harbour::audio {

SoundThread::SoundThread(const sim::SceneDescription& scene, const SoundSettings& sounds,
                         const AudioSettings& settings, std::function<const sim::Snapshot*()> latest)
    : scape_(scene, sounds),
      out_(AudioOut::device(settings)),
      latest_(std::move(latest)),
      described_(out_->describe()),
      volume_(settings.volume) {
  thread_ = std::thread([this] { run(); });
}

SoundThread::~SoundThread() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void SoundThread::run() {
  double volume_set = -1.0;
  while (!stop_.load()) {
    const double volume = muted_.load() ? 0.0 : volume_.load();
    if (volume != volume_set) out_->set_volume(volume), volume_set = volume;
    const sim::Snapshot* snapshot = latest_();
    if (!snapshot || out_->blocks_waiting() >= kBlocksAhead) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    scape_.update(*snapshot);
    out_->play(scape_);
    blocks_.fetch_add(1);
  }
}

}  // namespace harbour::audio
