#pragma once

#include <string>
#include <vector>

namespace harbour::scene {

/// A signaller's spoken instruction at a moment of an exercise, or an instructor's call.
struct RadioCall {
  double at_s = 0.0;  ///< [s] exercise time
  std::string text;   ///< "hoist up slowly"
};

/// An exercise's radio script: the signaller's calls, spoken in the exercise's language on the cab's radio
/// (the sound speaks them; they change nothing in the simulation).
struct RadioScript {
  std::string language = "en";  ///< an espeak-ng voice: en, de, es, fr, nl, ...
  std::vector<RadioCall> calls;
};

}  // namespace harbour::scene
