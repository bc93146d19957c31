#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace harbour::audio {

/// The sample rate every voice renders at [Hz].
inline constexpr double kSampleRate_hz = 48000.0;

/// A deterministic white-noise source in [-1, 1] (xorshift32): the same seed gives the same samples.
class Noise {
 public:
  explicit Noise(std::uint32_t seed) : state_(seed == 0 ? 0x9e3779b9u : seed) {}
  float next() {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 17;
    state_ ^= state_ << 5;
    return static_cast<float>(static_cast<double>(state_) / 2147483647.5 - 1.0);
  }
  /// Uniform in [0, 1).
  double uniform() { return 0.5 * (static_cast<double>(next()) + 1.0) * 0.999999; }

 private:
  std::uint32_t state_;
};

/// A one-pole low-pass filter (a smoothing of noise into rumble or of a level into a ramp).
class OnePole {
 public:
  void set_cutoff(double cutoff_hz);
  float process(float x) {
    y_ += a_ * (x - y_);
    return y_;
  }

 private:
  float a_ = 1.0f, y_ = 0.0f;
};

/// A two-pole resonator (RBJ band-pass, constant peak gain): one mode of a struck or excited body.
class Resonator {
 public:
  void set(double centre_hz, double q);
  float process(float x);
  /// Its first output sample for a unit impulse: an impulse of 1 / this rings at about unit amplitude.
  double impulse_response() const { return b0_; }

 private:
  double b0_ = 0, b2_ = 0, a1_ = 0, a2_ = 0;
  double x1_ = 0, x2_ = 0, y1_ = 0, y2_ = 0;
};

/// A sine oscillator with a running phase (its frequency may change every sample without a click).
class Oscillator {
 public:
  float next(double frequency_hz) {
    phase_ += frequency_hz / kSampleRate_hz;
    phase_ -= static_cast<double>(static_cast<long>(phase_));
    return static_cast<float>(sine(phase_));
  }
  /// The phase in turns [0, 1), for harmonics at whole multiples of it.
  double phase() const { return phase_; }
  static double sine(double turns);

 private:
  double phase_ = 0.0;
};

/// What one block's sound source is asked for: its drive (or quantity) at the block's start and end; the
/// voices ramp linearly between them over the block so a change never clicks.
struct Ramp {
  double from = 0.0, to = 0.0;
  double at(std::size_t n, std::size_t count) const {
    return from + (to - from) * static_cast<double>(n) / static_cast<double>(count);
  }
};

/// An electric drive as an operator hears it (an induction motor on an inverter, through a gearbox): the
/// magnetic tone at twice the electrical frequency, which follows the motor's speed, with its slot
/// harmonics; the inverter's switching tone at its carrier, louder with the current (the load); and the
/// gears' and drum's rumble with the speed.
struct ElectricDriveSettings {
  double rated_hz = 100.0;     ///< [Hz] the magnetic tone at rated speed (2 x 50 Hz supply)
  double carrier_hz = 2500.0;  ///< [Hz] the inverter's switching frequency
  double level = 0.2;          ///< the tone's amplitude at rated speed and load (full scale 1)
};
class ElectricDriveVoice {
 public:
  ElectricDriveVoice(const ElectricDriveSettings& settings, std::uint32_t seed);
  /// Adds the block to `out`: `speed` signed fraction of rated, `load` fraction of rated force.
  void render(std::span<float> out, Ramp speed, Ramp load);

 private:
  ElectricDriveSettings settings_;
  Oscillator tone_, carrier_;
  Noise noise_;
  OnePole rumble_, rumble_again_;  // two poles: a rumble, not a hiss
};

/// A diesel engine: a firing pulse every 2/cylinders of a turn (four-stroke), each exciting the exhaust's
/// and the block's resonances with a little cycle-to-cycle variation (a granular synthesis of the firing
/// events); louder and rougher with the load; a turbocharger's whine that rises with the boost (speed and
/// load together).
struct DieselSettings {
  int cylinders = 6;
  double idle_rpm = 700.0, rated_rpm = 1800.0;  ///< [rpm] at speed 0 and 1
  double exhaust_hz = 110.0, block_hz = 520.0;  ///< [Hz] the resonances a firing excites
  double turbo_hz = 4200.0;                     ///< [Hz] the whine at full boost
  double level = 0.2;                           ///< amplitude at rated speed and full load
};
class DieselVoice {
 public:
  DieselVoice(const DieselSettings& settings, std::uint32_t seed);
  void render(std::span<float> out, Ramp speed, Ramp load);

 private:
  DieselSettings settings_;
  double cycle_ = 0.0;        // firing phase [firings]
  double next_firing_ = 1.0;  // when the next cylinder fires [firings]
  Resonator exhaust_, block_;
  Oscillator turbo_;
  Noise noise_;
  OnePole roar_;
};

/// A hydraulic pump and valves: the pump's piston tone and the oil's hiss through the valve, both with the
/// flow (the cylinder's speed), the tone harder with the pressure (its load).
struct HydraulicSettings {
  double pump_hz = 270.0;  ///< [Hz] pistons times the pump's shaft rate
  double level = 0.1;
};
class HydraulicVoice {
 public:
  HydraulicVoice(const HydraulicSettings& settings, std::uint32_t seed);
  void render(std::span<float> out, Ramp flow, Ramp load);

 private:
  HydraulicSettings settings_;
  Oscillator pump_;
  Noise noise_;
  Resonator hiss_;
};

/// A struck steel body: a low thump and a few inharmonic ringing modes after a short noise burst; its
/// amplitude is set per strike (a contact's impulse, a twistlock's turn).
struct KnockSettings {
  double thump_hz = 70.0;                               ///< [Hz] the body's lowest mode
  std::array<double, 3> ring_hz{310.0, 770.0, 1530.0};  ///< [Hz] steel plate modes
  double decay_s = 0.12;                                ///< [s] the ringing's time constant
  double level = 0.3;                                   ///< amplitude of a strike of strength 1
};
class KnockVoice {
 public:
  KnockVoice(const KnockSettings& settings, std::uint32_t seed);
  /// A strike of `strength` (1: the settings' level) starting `at` samples into the next block.
  void strike(double strength, std::size_t at);
  void render(std::span<float> out);

 private:
  static constexpr std::size_t kMaxPending = 8;
  KnockSettings settings_;
  std::array<Oscillator, 4> modes_;
  std::array<double, 4> amplitude_{};
  double burst_ = 0.0;
  Noise noise_;
  std::array<std::pair<std::size_t, double>, kMaxPending> pending_{};
  std::size_t pending_count_ = 0;
};

/// A warning tone: an alarm's beeps (on and off, two alternating pitches) or a horn's chord (a partial and
/// its major third, rich in harmonics).
struct ToneSettings {
  double frequency_hz = 900.0;
  double second_hz = 0.0;  ///< [Hz] alternating pitch (alarm) or the chord's other note (horn); 0: none
  double on_s = 0.0;       ///< [s] beep length; 0: continuous
  double off_s = 0.0;      ///< [s] pause between beeps
  bool chord = false;      ///< both notes together (a horn) rather than alternating
  double level = 0.15;
};
class ToneVoice {
 public:
  explicit ToneVoice(const ToneSettings& settings) : settings_(settings) {}
  /// Adds the block while `on` (the condition holds); the beep pattern restarts when it comes on.
  void render(std::span<float> out, bool on);

 private:
  ToneSettings settings_;
  Oscillator first_, second_;
  double elapsed_s_ = 0.0;
  float envelope_ = 0.0f;
};

/// Weather and place as filtered noise: wind (a band that rises in pitch and level with the speed, with the
/// rigging's Aeolian whistle), rain (a hiss of drops), the sea (a slow swell of surf on the quay wall) and
/// the harbour's distant hum; the amount is the quantity the snapshot gives (m/s, mm/h, m).
enum class NoiseKind : std::uint8_t { kWind, kRain, kSea, kHarbour, kPour };
struct NoiseSettings {
  NoiseKind kind = NoiseKind::kWind;
  double reference = 10.0;  ///< the amount at which the sound has its level (wind m/s, rain mm/h, ...)
  double level = 0.1;
};
class NoiseVoice {
 public:
  NoiseVoice(const NoiseSettings& settings, std::uint32_t seed);
  void render(std::span<float> out, Ramp amount);

 private:
  NoiseSettings settings_;
  Noise noise_;
  Resonator band_, whistle_;
  OnePole low_;
  Oscillator swell_;
};

/// Prepared sounds played as they are (a radio call): each started at a sample of a block, mixed while it
/// lasts.
class ClipVoice {
 public:
  void start(std::shared_ptr<const std::vector<float>> clip, std::size_t at);
  void render(std::span<float> out);
  bool playing() const { return !playing_.empty(); }

 private:
  struct Playing {
    std::shared_ptr<const std::vector<float>> clip;
    std::size_t next = 0;   // its next sample
    std::size_t delay = 0;  // samples of this block before it starts
  };
  std::vector<Playing> playing_;
};

}  // namespace harbour::audio
