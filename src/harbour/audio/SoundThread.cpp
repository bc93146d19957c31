#include "harbour/audio/SoundThread.h"

#include <chrono>

#include "harbour/audio/Radio.h"

namespace harbour::audio {

SoundThread::SoundThread(const scene::SceneDescription& scene, const SoundSettings& sounds,
                         const AudioSettings& settings, const scene::RadioScript& radio,
                         std::function<const scene::Snapshot*()> latest)
    : scape_(scene, sounds),
      out_(AudioOut::device(settings)),
      latest_(std::move(latest)),
      described_(out_->describe()),
      volume_(settings.volume) {
  try {
    scape_.set_radio_script(radio);
  } catch (const AudioError& e) {
    radio_problem_ = e.what();
  }
  thread_ = std::thread([this] { run(); });
}

void SoundThread::say(const std::string& text) {
  if (!scape_.has_radio()) throw AudioError("this station's sounds have no radio");
  auto call = std::make_shared<const std::vector<float>>(
      speak_on_radio(text, scape_.radio_language(), scape_.radio_level()));
  const std::lock_guard lock(said_mutex_);
  said_.push_back(std::move(call));
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
    const scene::Snapshot* snapshot = latest_();
    // (a scene with no sounds at all has nothing to play and no source to pace it by: it only waits)
    if (!snapshot || scape_.source_count() == 0 || out_->blocks_waiting() >= kBlocksAhead) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    {
      const std::lock_guard lock(said_mutex_);
      for (auto& call : said_)
        scape_.hear(std::move(call));
      said_.clear();
    }
    scape_.update(*snapshot);
    out_->play(scape_);
    blocks_.fetch_add(1);
  }
}

}  // namespace harbour::audio
