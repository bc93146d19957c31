#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "harbour/audio/SoundScape.h"

namespace harbour::audio {

/// What the station's sound plays on (the profile's `audio.output`).
enum class Speakers : std::uint8_t {
  kStereo,      ///< two speakers (panned)
  kHeadphones,  ///< stereo through a head-related transfer function (HRTF): sounds from all round
  kSurround51,  ///< 5.1 speakers round the cabin
};

/// The station's sound settings.
struct AudioSettings {
  Speakers speakers = Speakers::kStereo;
  double volume = 1.0;  ///< [0, 2] master gain
};

/// A sound output could not be opened (no sound card, no OpenAL extension).
class AudioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// OpenAL Soft playing a SoundScape in 3-D: one streaming source per sound, placed where it sits, heard from
/// the operator's head. Either a real output device (the station) or OpenAL Soft's loopback device, which
/// mixes into memory on demand with no sound card (tests, and a recording's sound track).
class AudioOut {
 public:
  static constexpr int kSampleRate_hz = 48000;

  /// The system's default output device; throws AudioError where there is none.
  static std::unique_ptr<AudioOut> device(const AudioSettings& settings);
  /// The loopback device (float samples, interleaved): render() pulls its mix.
  static std::unique_ptr<AudioOut> loopback(const AudioSettings& settings);
  ~AudioOut();
  AudioOut(const AudioOut&) = delete;
  AudioOut& operator=(const AudioOut&) = delete;

  int channels() const { return channels_; }
  /// Whether the HRTF is in use (asked for with headphones; OpenAL Soft may refuse it).
  bool hrtf() const { return hrtf_; }
  /// The device's name and mode, for the station's log.
  std::string describe() const;

  /// Queues the scape's latest block on each of its sources, placed where they sit now, the listener where
  /// the operator's head is. The first call starts them all together, one block of silence ahead.
  void play(const SoundScape& scape);
  /// Loopback: mixes the next out.size() / channels() frames into `out` (interleaved).
  void render(std::span<float> out);
  /// The blocks queued on the sources that have not been played yet (a live station keeps a few ahead).
  int blocks_waiting() const;
  void set_volume(double volume);

 private:
  struct Impl;
  explicit AudioOut(std::unique_ptr<Impl> impl, int channels, bool hrtf);
  static std::unique_ptr<AudioOut> open(std::unique_ptr<Impl> impl, const int* attributes,
                                        const AudioSettings& settings);
  std::unique_ptr<Impl> impl_;
  int channels_ = 2;
  bool hrtf_ = false;
};

/// Writes interleaved float samples as a 16-bit PCM WAV file (clipped to full scale); throws
/// std::runtime_error naming the file when it cannot.
void write_wav(const std::string& path, std::span<const float> samples, int channels, int sample_rate_hz);

/// Renders a run of snapshots' sound offline: each block's snapshot into the scape, the mix through the
/// loopback device, appended to the samples. Holds the two together for a recording's sound track.
class OfflineMix {
 public:
  OfflineMix(const scene::SceneDescription& scene, const SoundSettings& sounds, const AudioSettings& audio,
             bool ambience = true);
  /// One block (10 ms) ending at `snapshot`.
  void add_block(const scene::Snapshot& snapshot);
  const std::vector<float>& samples() const { return samples_; }
  int channels() const { return out_->channels(); }
  SoundScape& scape() { return scape_; }

 private:
  SoundScape scape_;
  std::unique_ptr<AudioOut> out_;
  std::vector<float> samples_;
};

}  // namespace harbour::audio
