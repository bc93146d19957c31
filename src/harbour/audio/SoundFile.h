#pragma once

#include <string>

#include "harbour/audio/SoundScape.h"

namespace harbour::audio {

/// The harbour's sounds (data/sounds/harbour.yaml): each machine kind's and the ambience; a DataError names
/// the file, line and field of anything wrong.
SoundSettings load_sounds(const std::string& path);
/// The same from text (tests).
SoundSettings parse_sounds(const std::string& text, const std::string& name);

}  // namespace harbour::audio
