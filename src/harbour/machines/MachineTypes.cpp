#include "harbour/machines/MachineType.h"

namespace harbour::sim {

const MachineType* find_machine_type(std::string_view kind) {
  for (const MachineType* type : machine_types())
    if (kind == type->kind) return type;
  return nullptr;
}

}  // namespace harbour::sim
