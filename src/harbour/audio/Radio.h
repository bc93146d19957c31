#pragma once

#include <string>
#include <vector>

namespace harbour::audio {

/// The longest call spoken [bytes of text] (a radio call is a few words).
inline constexpr std::size_t kMaxRadioCallBytes = 200;

/// `text` spoken by espeak-ng in `language` (an espeak-ng voice: en, de, es, fr, nl, ...) as a handheld
/// radio gives it: band-limited to the speech band (300-3000 Hz), a little overdriven, the squelch's hiss
/// before and after; mono at 48 kHz, peak amplitude `level`. Deterministic. Throws AudioError when espeak-ng
/// has no such voice or fails.
std::vector<float> speak_on_radio(const std::string& text, const std::string& language, double level);

}  // namespace harbour::audio
