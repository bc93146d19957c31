#include "harbour/io/MachineDataFiles.h"

#include <algorithm>

#include "harbour/io/YamlFile.h"

namespace harbour::io {

std::vector<std::string> machine_data_files(const std::string& data_folder,
                                            std::span<const std::string_view> kinds,
                                            const std::string& machine_file) {
  std::vector<std::string> files;
  for (const std::string_view kind : kinds)
    files.push_back(data_folder + "/machines/" + std::string(kind) + ".yaml");
  if (!machine_file.empty()) files.push_back(machine_file);
  return files;
}

std::vector<std::pair<std::string, std::string>> machine_files_by_kind(
    const std::vector<std::string>& files) {
  std::vector<std::pair<std::string, std::string>> by_kind;
  for (const std::string& file : files) {
    const YamlFile f = YamlFile::load(file);
    const std::string kind = f.text(f.required_map(f.root(), "machine", ""), "kind", "machine");
    const auto same =
        std::find_if(by_kind.begin(), by_kind.end(), [&](const auto& k) { return k.first == kind; });
    if (same == by_kind.end())
      by_kind.emplace_back(kind, file);
    else
      same->second = file;
  }
  return by_kind;
}

}  // namespace harbour::io
