#include "harbour/io/MachineDataFiles.h"

#include <algorithm>
#include <utility>

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

std::vector<MachineDataFile> load_machine_data_files(const std::vector<std::string>& files) {
  std::vector<MachineDataFile> by_kind;
  for (const std::string& path : files) {
    YamlFile f = YamlFile::load(path);
    std::string kind = f.text(f.required_map(f.root(), "machine", ""), "kind", "machine");
    const auto same = std::find_if(by_kind.begin(), by_kind.end(),
                                   [&](const MachineDataFile& read) { return read.kind == kind; });
    if (same == by_kind.end())
      by_kind.push_back({std::move(kind), std::move(f)});
    else
      same->file = std::move(f);
  }
  return by_kind;
}

}  // namespace harbour::io
