#pragma once

#include <span>
#include <string_view>

#include "harbour/sim/MachineType.h"

namespace harbour::sim {

/// Every machine type, by kind (generated from the machine folders).
std::span<const MachineType* const> machine_types();
/// The type of that kind, nullptr where there is none.
const MachineType* find_machine_type(std::string_view kind);
/// Every machine type's kind, in the registry's order.
std::span<const std::string_view> machine_kinds();

}  // namespace harbour::sim
