#include "harbour/audio/Synth.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harbour::audio {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// the factor a level decays by per sample with time constant `tau_s`
double decay_per_sample(double tau_s) {
  return std::exp(-1.0 / (tau_s * kSampleRate_hz));
}

float f(double x) {
  return static_cast<float>(x);
}
}  // namespace

void OnePole::set_cutoff(double cutoff_hz) {
  a_ = f(1.0 - std::exp(-kTwoPi * cutoff_hz / kSampleRate_hz));
}

void Resonator::set(double centre_hz, double q) {
  const double w = kTwoPi * std::clamp(centre_hz, 1.0, 0.45 * kSampleRate_hz) / kSampleRate_hz;
  const double alpha = std::sin(w) / (2.0 * q), a0 = 1.0 + alpha;
  b0_ = alpha / a0;
  b2_ = -alpha / a0;
  a1_ = -2.0 * std::cos(w) / a0;
  a2_ = (1.0 - alpha) / a0;
}

float Resonator::process(float x) {
  const double y = b0_ * x + b2_ * x2_ - a1_ * y1_ - a2_ * y2_;
  x2_ = x1_;
  x1_ = x;
  y2_ = y1_;
  y1_ = y;
  return f(y);
}

double Oscillator::sine(double turns) {
  return std::sin(kTwoPi * turns);
}

ElectricDriveVoice::ElectricDriveVoice(const ElectricDriveSettings& settings, std::uint32_t seed)
    : settings_(settings), noise_(seed) {
  rumble_.set_cutoff(180.0);
  rumble_again_.set_cutoff(180.0);
}

void ElectricDriveVoice::render(std::span<float> out, Ramp speed, Ramp load) {
  for (std::size_t n = 0; n < out.size(); ++n) {
    const double s = std::min(std::abs(speed.at(n, out.size())), 1.0);
    const double l = std::clamp(load.at(n, out.size()), 0.0, 1.0);
    const double turning = std::min(1.0, s / 0.03);  // a drive at rest is silent
    // the magnetic tone and its slot harmonics 2, 3 and 6 (multiple-angle identities: two sines a sample)
    tone_.next(settings_.rated_hz * s);
    const double s1 = Oscillator::sine(tone_.phase()), c1 = Oscillator::sine(tone_.phase() + 0.25);
    const double s2 = 2.0 * s1 * c1, s3 = s1 * (3.0 - 4.0 * s1 * s1), c3 = c1 * (4.0 * c1 * c1 - 3.0);
    const double tone = s1 + 0.45 * s2 + 0.25 * s3 + 0.15 * (2.0 * s3 * c3);
    const double carrier = carrier_.next(settings_.carrier_hz);
    const double rumble = 2.0 * rumble_again_.process(rumble_.process(noise_.next()));
    out[n] += f(settings_.level * turning *
                ((0.35 + 0.65 * l) * (0.4 + 0.6 * s) * tone + 0.2 * l * carrier + 1.5 * s * rumble));
  }
}

DieselVoice::DieselVoice(const DieselSettings& settings, std::uint32_t seed)
    : settings_(settings), noise_(seed) {
  exhaust_.set(settings.exhaust_hz, 2.5);
  block_.set(settings.block_hz, 6.0);
  roar_.set_cutoff(350.0);
}

void DieselVoice::render(std::span<float> out, Ramp speed, Ramp load) {
  const double firings_per_turn = 0.5 * settings_.cylinders;  // four-stroke: every cylinder every other turn
  for (std::size_t n = 0; n < out.size(); ++n) {
    const double s = std::clamp(speed.at(n, out.size()), 0.0, 1.0);
    const double l = std::clamp(load.at(n, out.size()), 0.0, 1.0);
    const double rpm = settings_.idle_rpm + s * (settings_.rated_rpm - settings_.idle_rpm);
    cycle_ += rpm / 60.0 * firings_per_turn / kSampleRate_hz;
    double pulse = 0.0;
    if (cycle_ >= next_firing_) {
      // one firing: harder with the load, each a little different from the last in strength and timing
      // (combustion varies cycle to cycle: the upper harmonics smear into the engine's roughness)
      cycle_ -= next_firing_;
      next_firing_ = 1.0 + 0.03 * noise_.next();
      pulse = (0.3 + 0.7 * l) * (1.0 + 0.2 * noise_.next());
    }
    const double boost = s * (0.4 + 0.6 * l);
    // each firing rings the exhaust and the block at about the pulse's amplitude
    const double firing = 0.7 * exhaust_.process(f(pulse / exhaust_.impulse_response())) +
                          0.3 * block_.process(f(pulse / block_.impulse_response()));
    const double whine = 0.05 * boost * turbo_.next(settings_.turbo_hz * (0.35 + 0.65 * boost));
    const double roar = 0.8 * l * (0.5 + 0.5 * s) * roar_.process(noise_.next());
    out[n] += f(settings_.level * (firing + whine + roar));
  }
}

HydraulicVoice::HydraulicVoice(const HydraulicSettings& settings, std::uint32_t seed)
    : settings_(settings), noise_(seed) {
  hiss_.set(2600.0, 1.2);
}

void HydraulicVoice::render(std::span<float> out, Ramp flow, Ramp load) {
  for (std::size_t n = 0; n < out.size(); ++n) {
    const double q = std::min(std::abs(flow.at(n, out.size())), 1.0);
    const double p = std::clamp(load.at(n, out.size()), 0.0, 1.0);
    const double active = std::min(1.0, q / 0.03);
    const double pump = pump_.next(settings_.pump_hz * (0.97 + 0.03 * p));
    const double tone = pump + 0.4 * Oscillator::sine(2.0 * pump_.phase());
    out[n] += f(settings_.level * active * ((0.3 + 0.7 * p) * tone + 1.2 * q * hiss_.process(noise_.next())));
  }
}

KnockVoice::KnockVoice(const KnockSettings& settings, std::uint32_t seed)
    : settings_(settings), noise_(seed) {}

void KnockVoice::strike(double strength, std::size_t at) {
  if (pending_count_ < kMaxPending) pending_[pending_count_++] = {at, strength};
}

void KnockVoice::render(std::span<float> out) {
  const std::array<double, 4> frequency{settings_.thump_hz, settings_.ring_hz[0], settings_.ring_hz[1],
                                        settings_.ring_hz[2]};
  const std::array<double, 4> share{1.0, 0.5, 0.35, 0.2};
  const std::array<double, 4> decay{decay_per_sample(0.08), decay_per_sample(settings_.decay_s),
                                    decay_per_sample(0.7 * settings_.decay_s),
                                    decay_per_sample(0.5 * settings_.decay_s)};
  const double burst_decay = decay_per_sample(0.004);
  for (std::size_t n = 0; n < out.size(); ++n) {
    for (std::size_t p = 0; p < pending_count_; ++p)
      if (pending_[p].first == n) {
        for (std::size_t m = 0; m < amplitude_.size(); ++m)
          amplitude_[m] += pending_[p].second * share[m];
        burst_ += 0.6 * pending_[p].second;
      }
    double sample = burst_ * noise_.next();
    for (std::size_t m = 0; m < modes_.size(); ++m) {
      sample += amplitude_[m] * modes_[m].next(frequency[m]);
      amplitude_[m] *= decay[m];
    }
    burst_ *= burst_decay;
    out[n] += f(settings_.level * sample);
  }
  // strikes later than this block move on to the next
  std::size_t kept = 0;
  for (std::size_t p = 0; p < pending_count_; ++p)
    if (pending_[p].first >= out.size())
      pending_[kept++] = {pending_[p].first - out.size(), pending_[p].second};
  pending_count_ = kept;
}

void ToneVoice::render(std::span<float> out, bool on) {
  const float step = f(1.0 / (0.005 * kSampleRate_hz));  // 5 ms attack and release
  const double period = settings_.on_s + settings_.off_s;
  for (float& sample : out) {
    bool sounding = on, second = false;
    if (on && settings_.on_s > 0.0) {
      const double in_period = std::fmod(elapsed_s_, period);
      sounding = in_period < settings_.on_s;
      second = settings_.second_hz > 0.0 && static_cast<long>(elapsed_s_ / period) % 2 == 1;
    }
    envelope_ = sounding ? std::min(1.0f, envelope_ + step) : std::max(0.0f, envelope_ - step);
    double wave = 0.0;
    if (settings_.chord) {
      // a horn: two notes, each a buzz of its first four harmonics
      const float a = first_.next(settings_.frequency_hz), b = second_.next(settings_.second_hz);
      wave = 0.5 * (a + b);
      for (int k = 2; k <= 4; ++k)
        wave += 0.5 / k * (Oscillator::sine(k * first_.phase()) + Oscillator::sine(k * second_.phase()));
    } else {
      // an alarm: a square-ish beep (odd harmonics)
      first_.next(second ? settings_.second_hz : settings_.frequency_hz);
      for (int k = 1; k <= 5; k += 2)
        wave += 1.0 / k * Oscillator::sine(k * first_.phase());
    }
    sample += f(settings_.level * envelope_ * wave);
    elapsed_s_ = on ? elapsed_s_ + 1.0 / kSampleRate_hz : 0.0;
  }
}

NoiseVoice::NoiseVoice(const NoiseSettings& settings, std::uint32_t seed)
    : settings_(settings), noise_(seed) {
  switch (settings.kind) {
    case NoiseKind::kWind:
      low_.set_cutoff(900.0);
      break;
    case NoiseKind::kRain:
      low_.set_cutoff(1500.0), band_.set(3200.0, 3.0);
      break;
    case NoiseKind::kSea:
      low_.set_cutoff(450.0);
      break;
    case NoiseKind::kHarbour:
      low_.set_cutoff(110.0);
      break;
    case NoiseKind::kPour:
      low_.set_cutoff(250.0), band_.set(900.0, 0.6);
      break;
  }
}

void NoiseVoice::render(std::span<float> out, Ramp amount) {
  constexpr double kStayWire_m = 0.012;  // the rigging's thin stays whistle at St v / d (St = 0.2)
  for (std::size_t n = 0; n < out.size(); ++n) {
    const double a = std::max(0.0, amount.at(n, out.size()));
    const double r = a / settings_.reference;
    const double white = noise_.next();
    double sample = 0.0;
    switch (settings_.kind) {
      case NoiseKind::kWind: {
        // aerodynamic noise: amplitude with the speed cubed (a dipole's power with its sixth power), its
        // band rising with the speed; the stays' Aeolian tone above a fresh breeze
        if (n % 64 == 0) band_.set(250.0 + 60.0 * a, 0.8), whistle_.set(0.2 * a / kStayWire_m, 40.0);
        const double gain = std::min(std::pow(r, 3.0), 4.0);
        sample = gain * (2.0 * band_.process(f(white)) + 0.5 * low_.process(f(white)));
        sample += std::clamp(r - 0.8, 0.0, 1.0) * 6.0 * whistle_.process(f(white));
        break;
      }
      case NoiseKind::kRain: {
        // a hiss above the rumble, and drops: random clicks at a rate with the rain
        const double hiss = white - low_.process(f(white));
        const double drop = noise_.uniform() < 300.0 * r / kSampleRate_hz ? noise_.next() * 40.0 : 0.0;
        sample = std::sqrt(r) * (0.5 * hiss + band_.process(f(drop)));
        break;
      }
      case NoiseKind::kSea: {
        // surf on the quay wall: low noise rising and falling with an 8 s swell
        const double swell = 0.6 + 0.4 * swell_.next(1.0 / 8.0);
        sample = std::min(0.3 + r, 2.0) * swell * 3.0 * low_.process(f(white));
        break;
      }
      case NoiseKind::kHarbour:
        sample = 4.0 * low_.process(f(white));
        break;
      case NoiseKind::kPour:
        // material falling: a broad rush with a rumble, with the mass flow's square root
        sample = std::sqrt(std::min(r, 4.0)) * (2.0 * band_.process(f(white)) + 2.0 * low_.process(f(white)));
        break;
    }
    out[n] += f(settings_.level * sample);
  }
}

void ClipVoice::start(std::shared_ptr<const std::vector<float>> clip, std::size_t at) {
  playing_.push_back({std::move(clip), 0, at});
}

void ClipVoice::render(std::span<float> out) {
  for (Playing& p : playing_) {
    for (std::size_t n = p.delay; n < out.size() && p.next < p.clip->size(); ++n)
      out[n] += (*p.clip)[p.next++];
    p.delay = 0;
  }
  std::erase_if(playing_, [](const Playing& p) { return p.next >= p.clip->size(); });
}

}  // namespace harbour::audio
