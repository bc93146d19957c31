#pragma once

#include <span>
#include <string>
#include <string_view>

#include "harbour/audio/SoundScape.h"

namespace harbour::audio {

/// The harbour's sounds (data/sounds/harbour.yaml): each machine kind's and the ambience; a DataError names
/// the file, line and field of anything wrong, a machine not among `machine_kinds` (the registry's) too.
SoundSettings load_sounds(const std::string& path, std::span<const std::string_view> machine_kinds);
/// The same from text (tests).
SoundSettings parse_sounds(const std::string& text, const std::string& name,
                           std::span<const std::string_view> machine_kinds);

}  // namespace harbour::audio
