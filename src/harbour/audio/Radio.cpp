#include "harbour/audio/Radio.h"

#include <espeak-ng/speak_lib.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "harbour/audio/AudioOut.h"
#include "harbour/audio/Synth.h"

namespace harbour::audio {

namespace {

// espeak-ng is one global synthesiser: one caller at a time
std::mutex g_espeak;
std::vector<short>* g_speech = nullptr;

int collect(short* samples, int count, espeak_EVENT*) {
  if (samples && count > 0 && g_speech) g_speech->insert(g_speech->end(), samples, samples + count);
  return 0;
}

int espeak_rate_hz() {
  static const int rate = [] {
    const int r = espeak_Initialize(AUDIO_OUTPUT_SYNCHRONOUS, 0, nullptr, 0);
    if (r > 0) espeak_SetSynthCallback(collect);
    return r;
  }();
  return rate;
}

}  // namespace

std::vector<float> speak_on_radio(const std::string& text, const std::string& language, double level) {
  std::vector<short> speech;
  int rate = 0;
  {
    const std::lock_guard lock(g_espeak);
    rate = espeak_rate_hz();
    if (rate <= 0) throw AudioError("espeak-ng did not start (its data: the espeak-ng-data package)");
    if (espeak_SetVoiceByName(language.c_str()) != EE_OK)
      throw AudioError("espeak-ng has no voice for language '" + language + "'");
    g_speech = &speech;
    const std::string said = text.substr(0, kMaxRadioCallBytes);
    const espeak_ERROR e =
        espeak_Synth(said.c_str(), said.size() + 1, 0, POS_CHARACTER, 0, espeakCHARS_UTF8, nullptr, nullptr);
    espeak_Synchronize();
    g_speech = nullptr;
    if (e != EE_OK) throw AudioError("espeak-ng could not speak '" + said + "'");
  }
  // to 48 kHz (linear interpolation), then the radio: the speech band, overdrive, squelch hiss each end
  const double step = static_cast<double>(rate) / kSampleRate_hz;
  const auto frames = static_cast<std::size_t>(static_cast<double>(speech.size()) / step);
  constexpr std::size_t kSquelch = 4800;  // 0.1 s
  std::vector<float> out(frames + 2 * kSquelch, 0.0f);
  Resonator low, high;
  low.set(700.0, 0.6);
  high.set(2000.0, 0.8);
  Noise noise(0x5ad10u);
  double peak = 1e-9;
  for (std::size_t n = 0; n < out.size(); ++n) {
    double x = 0.0;
    if (n >= kSquelch && n < kSquelch + frames) {
      const double at = static_cast<double>(n - kSquelch) * step;
      const auto i = static_cast<std::size_t>(at);
      const double u = at - static_cast<double>(i);
      const double a = speech[i] / 32768.0, b = i + 1 < speech.size() ? speech[i + 1] / 32768.0 : a;
      x = 3.0 * ((1.0 - u) * a + u * b);
    } else {
      x = 0.15 * noise.next();  // the squelch opening and closing
    }
    const double band = low.process(static_cast<float>(x)) + high.process(static_cast<float>(x));
    out[n] = static_cast<float>(std::tanh(2.0 * band));
    peak = std::max(peak, std::abs(static_cast<double>(out[n])));
  }
  for (float& s : out)
    s = static_cast<float>(s / peak * level);
  return out;
}

}  // namespace harbour::audio
