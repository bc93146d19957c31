#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harbour/audio/SoundScape.h"

namespace harbour::audio {

/// The harbour's sounds: the ambience every scene has (data/sounds/harbour.yaml) and each machine's own,
/// from its machine file's `sounds` list (of several files of one kind the last: an exercise's own machine
/// file after the shipped one). A DataError names the file, line and field of anything wrong.
SoundSettings load_sounds(const std::string& path, const std::vector<std::string>& machine_files);
/// The shipped sounds: `data_folder`/sounds/harbour.yaml with io::machine_data_files() (the registry's kinds
/// from the caller: the sound names no machine).
SoundSettings load_shipped_sounds(const std::string& data_folder, std::span<const std::string_view> kinds,
                                  const std::string& machine_file = "");
/// The ambience file from text (tests).
SoundSettings parse_sounds(const std::string& text, const std::string& name);

}  // namespace harbour::audio
