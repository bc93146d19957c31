#define AL_ALEXT_PROTOTYPES
#include "harbour/audio/AudioOut.h"

#include <AL/al.h>
#include <AL/alc.h>
#include <AL/alext.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

namespace harbour::audio {

namespace {
constexpr int kPoolBuffers = 16;  // per source: far more than a station keeps queued

ALCint channel_layout(Speakers speakers) {
  return speakers == Speakers::kSurround51 ? ALC_5POINT1_SOFT : ALC_STEREO_SOFT;
}

int channel_count(Speakers speakers) {
  return speakers == Speakers::kSurround51 ? 6 : 2;
}
}  // namespace

struct AudioOut::Impl {
  ALCdevice* device = nullptr;
  ALCcontext* context = nullptr;
  bool loopback = false;
  struct Source {
    ALuint id = 0;
    std::vector<ALuint> free;
  };
  std::vector<Source> sources;
  std::vector<float> silence = std::vector<float>(SoundScape::kBlockFrames, 0.0f);

  ~Impl() {
    if (context) {
      alcMakeContextCurrent(context);
      for (Source& s : sources) {
        alSourceStop(s.id);
        alSourcei(s.id, AL_BUFFER, 0);
        alDeleteSources(1, &s.id);
        alDeleteBuffers(static_cast<ALsizei>(s.free.size()), s.free.data());
      }
      alcMakeContextCurrent(nullptr);
      alcDestroyContext(context);
    }
    if (device) alcCloseDevice(device);
  }

  void make_current() const { alcMakeContextCurrent(context); }

  // the source's processed buffers back to its pool; a buffer from it for the next block
  ALuint take_buffer(Source& s) {
    ALint processed = 0;
    alGetSourcei(s.id, AL_BUFFERS_PROCESSED, &processed);
    while (processed-- > 0) {
      ALuint done = 0;
      alSourceUnqueueBuffers(s.id, 1, &done);
      s.free.push_back(done);
    }
    if (s.free.empty()) {
      ALuint fresh = 0;
      alGenBuffers(1, &fresh);
      return fresh;
    }
    const ALuint b = s.free.back();
    s.free.pop_back();
    return b;
  }

  void queue(Source& s, std::span<const float> block) {
    const ALuint b = take_buffer(s);
    alBufferData(b, AL_FORMAT_MONO_FLOAT32, block.data(), static_cast<ALsizei>(block.size_bytes()),
                 kSampleRate_hz);
    alSourceQueueBuffers(s.id, 1, &b);
  }
};

AudioOut::AudioOut(std::unique_ptr<Impl> impl, int channels, bool hrtf)
    : impl_(std::move(impl)), channels_(channels), hrtf_(hrtf) {}

AudioOut::~AudioOut() = default;

std::unique_ptr<AudioOut> AudioOut::open(std::unique_ptr<Impl> impl, const int* attributes,
                                         const AudioSettings& settings) {
  impl->context = alcCreateContext(impl->device, attributes);
  if (!impl->context) throw AudioError("the sound device refused a context");
  impl->make_current();
  if (!alIsExtensionPresent("AL_EXT_FLOAT32")) throw AudioError("OpenAL lacks AL_EXT_FLOAT32");
  ALCint hrtf = ALC_FALSE;
  alcGetIntegerv(impl->device, ALC_HRTF_SOFT, 1, &hrtf);
  alDistanceModel(AL_INVERSE_DISTANCE_CLAMPED);
  alDopplerFactor(0.0f);
  std::unique_ptr<AudioOut> out(
      new AudioOut(std::move(impl), channel_count(settings.speakers), hrtf == ALC_TRUE));
  out->set_volume(settings.volume);
  return out;
}

std::unique_ptr<AudioOut> AudioOut::device(const AudioSettings& settings) {
  ALCdevice* device = alcOpenDevice(nullptr);
  if (!device) throw AudioError("no sound output device (OpenAL found none)");
  auto impl = std::make_unique<Impl>();
  impl->device = device;
  const ALCint attributes[] = {ALC_FREQUENCY, kSampleRate_hz, ALC_HRTF_SOFT,
                               settings.speakers == Speakers::kHeadphones ? ALC_TRUE : ALC_FALSE, 0};
  return open(std::move(impl), attributes, settings);
}

std::unique_ptr<AudioOut> AudioOut::loopback(const AudioSettings& settings) {
  if (!alcIsExtensionPresent(nullptr, "ALC_SOFT_loopback"))
    throw AudioError("OpenAL lacks ALC_SOFT_loopback");
  ALCdevice* device = alcLoopbackOpenDeviceSOFT(nullptr);
  if (!device) throw AudioError("OpenAL's loopback device did not open");
  auto impl = std::make_unique<Impl>();
  impl->device = device;
  impl->loopback = true;
  const ALCint attributes[] = {ALC_FORMAT_CHANNELS_SOFT,
                               channel_layout(settings.speakers),
                               ALC_FORMAT_TYPE_SOFT,
                               ALC_FLOAT_SOFT,
                               ALC_FREQUENCY,
                               kSampleRate_hz,
                               ALC_HRTF_SOFT,
                               settings.speakers == Speakers::kHeadphones ? ALC_TRUE : ALC_FALSE,
                               ALC_OUTPUT_LIMITER_SOFT,
                               ALC_FALSE,
                               0};
  if (!alcIsRenderFormatSupportedSOFT(device, kSampleRate_hz, channel_layout(settings.speakers),
                                      ALC_FLOAT_SOFT))
    throw AudioError("OpenAL's loopback device cannot mix float samples in this layout");
  return open(std::move(impl), attributes, settings);
}

std::string AudioOut::describe() const {
  const ALCchar* name = alcGetString(impl_->device, ALC_DEVICE_SPECIFIER);
  return std::string(impl_->loopback ? "loopback" : (name ? name : "?")) + ", " + std::to_string(channels_) +
         " channels" + (hrtf_ ? ", HRTF" : "");
}

void AudioOut::set_volume(double volume) {
  impl_->make_current();
  alListenerf(AL_GAIN, static_cast<float>(std::clamp(volume, 0.0, 2.0)));
}

void AudioOut::play(const SoundScape& scape) {
  Impl& m = *impl_;
  m.make_current();
  const bool starting = m.sources.empty();
  if (starting) {
    for (std::size_t k = 0; k < scape.source_count(); ++k) {
      Impl::Source s;
      alGenSources(1, &s.id);
      s.free.resize(kPoolBuffers);
      alGenBuffers(kPoolBuffers, s.free.data());
      const SoundSource& settings = scape.source(k);
      alSourcef(s.id, AL_REFERENCE_DISTANCE, static_cast<float>(settings.reference_distance_m));
      alSourcef(s.id, AL_ROLLOFF_FACTOR, 1.0f);
      alSourcef(s.id, AL_MAX_DISTANCE, 2000.0f);
      alSourcei(s.id, AL_SOURCE_RELATIVE, scape.relative(k) ? AL_TRUE : AL_FALSE);
      alSource3f(s.id, AL_POSITION, 0.0f, 0.0f, 0.0f);
      m.queue(s, m.silence);  // one block ahead: a source never runs dry between two blocks
      m.sources.push_back(std::move(s));
    }
  }
  const Listener& l = scape.listener();
  const auto fl = [](double x) { return static_cast<float>(x); };
  alListener3f(AL_POSITION, fl(l.position_m.x), fl(l.position_m.y), fl(l.position_m.z));
  const float orientation[] = {fl(l.forward.x), fl(l.forward.y), fl(l.forward.z),
                               fl(l.up.x),      fl(l.up.y),      fl(l.up.z)};
  alListenerfv(AL_ORIENTATION, orientation);
  std::vector<ALuint> stopped;
  for (std::size_t k = 0; k < m.sources.size() && k < scape.source_count(); ++k) {
    Impl::Source& s = m.sources[k];
    if (!scape.relative(k)) {
      const core::Vec3 p = scape.position_m(k);
      alSource3f(s.id, AL_POSITION, fl(p.x), fl(p.y), fl(p.z));
    }
    m.queue(s, scape.block(k));
    ALint state = 0;
    alGetSourcei(s.id, AL_SOURCE_STATE, &state);
    if (state != AL_PLAYING) stopped.push_back(s.id);
  }
  if (!stopped.empty()) alSourcePlayv(static_cast<ALsizei>(stopped.size()), stopped.data());
}

void AudioOut::render(std::span<float> out) {
  impl_->make_current();
  alcRenderSamplesSOFT(impl_->device, out.data(),
                       static_cast<ALCsizei>(out.size() / static_cast<std::size_t>(channels_)));
}

int AudioOut::blocks_waiting() const {
  if (impl_->sources.empty()) return 0;
  impl_->make_current();
  ALint queued = 0, processed = 0;
  alGetSourcei(impl_->sources.front().id, AL_BUFFERS_QUEUED, &queued);
  alGetSourcei(impl_->sources.front().id, AL_BUFFERS_PROCESSED, &processed);
  return queued - processed;
}

void write_wav(const std::string& path, std::span<const float> samples, int channels, int sample_rate_hz) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path + ": cannot write");
  const auto u32 = [&](std::uint32_t v) {
    const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                                static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 24)};
    out.write(reinterpret_cast<const char*>(b), 4);
  };
  const auto u16 = [&](std::uint16_t v) {
    const unsigned char b[2] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8)};
    out.write(reinterpret_cast<const char*>(b), 2);
  };
  const auto data_bytes = static_cast<std::uint32_t>(samples.size() * 2);
  const auto ch = static_cast<std::uint16_t>(channels);
  const auto rate = static_cast<std::uint32_t>(sample_rate_hz);
  out.write("RIFF", 4);
  u32(36 + data_bytes);
  out.write("WAVEfmt ", 8);
  u32(16);
  u16(1);  // PCM
  u16(ch);
  u32(rate);
  u32(rate * ch * 2u);
  u16(static_cast<std::uint16_t>(ch * 2u));
  u16(16);
  out.write("data", 4);
  u32(data_bytes);
  for (const float s : samples) {
    const long v = std::lround(std::clamp(static_cast<double>(s), -1.0, 1.0) * 32767.0);
    u16(static_cast<std::uint16_t>(static_cast<std::int16_t>(v)));
  }
  if (!out.flush()) throw std::runtime_error(path + ": write failed");
}

OfflineMix::OfflineMix(const scene::SceneDescription& scene, const SoundSettings& sounds,
                       const AudioSettings& audio, bool ambience)
    : scape_(scene, sounds, ambience), out_(AudioOut::loopback(audio)) {}

void OfflineMix::add_block(const scene::Snapshot& snapshot) {
  scape_.update(snapshot);
  out_->play(scape_);
  const std::size_t at = samples_.size();
  samples_.resize(at + SoundScape::kBlockFrames * static_cast<std::size_t>(out_->channels()));
  out_->render(std::span<float>(samples_).subspan(at));
}

}  // namespace harbour::audio
