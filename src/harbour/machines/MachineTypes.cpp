#include "harbour/machines/MachineRegistry.h"

#include <vector>

namespace harbour::sim {

const MachineType* find_machine_type(std::string_view kind) {
  for (const MachineType* type : machine_types())
    if (kind == type->kind) return type;
  return nullptr;
}

std::span<const std::string_view> machine_kinds() {
  static const std::vector<std::string_view> kinds = [] {
    std::vector<std::string_view> k;
    for (const MachineType* type : machine_types())
      k.emplace_back(type->kind);
    return k;
  }();
  return kinds;
}

}  // namespace harbour::sim
