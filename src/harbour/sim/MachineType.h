#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace harbour::sim {

enum class MachineFault : std::uint8_t;
class Pilot;
struct ExerciseSettings;

/// A scripted operator a machine type brings: why it cannot drive an exercise ("" when it can), and the
/// operator itself.
struct PilotType {
  std::string (*why_cannot_drive)(const ExerciseSettings&) = nullptr;
  std::unique_ptr<Pilot> (*make)(const ExerciseSettings&) = nullptr;
};

template <typename Operator>
std::unique_ptr<Pilot> make_pilot_of(const ExerciseSettings& exercise) {
  return std::make_unique<Operator>(exercise);
}

/// The PilotType of a scripted operator class (static why_cannot_drive, constructed from the exercise).
template <typename Operator>
constexpr PilotType pilot_type() {
  return {&Operator::why_cannot_drive, &make_pilot_of<Operator>};
}

/// What a machine's exercises give it to handle.
enum class Handles : std::uint8_t {
  kContainers,   ///< boxes with its spreader (trucks, a vessel's bays, a yard block)
  kBulkOrCargo,  ///< bulk with its grab, or general cargo on its hook
  kTrailer,      ///< a trailer it tows
};

/// The rubric's deductions every machine's operator can incur, whatever its parts: a collision, the emergency
/// stop, a signaller's stop followed late, the moves and the time, a harsh move.
inline constexpr std::string_view kEveryMachinesDeductions[] = {
    "collision",          "emergency_stop",         "late_stop_signal",
    "move_not_completed", "minute_over_time_limit", "harsh_move"};

/// What a kind of machine is, known without building one: its kind as files name it, what it handles, the
/// faults an instructor can inject into it and the scripted operators that drive its exercises. Each
/// machine's folder defines its own
/// (`src/harbour/machines/<kind>/Type.cpp`, `<kind>_machine_type()`); the list of them
/// (`machines/MachineRegistry.h`) is generated from the folders when the build is configured, so a new
/// machine is one more folder.
struct MachineType {
  const char* kind = "";   ///< as exercise and machine files name it ("sts")
  const char* title = "";  ///< what an instructor calls it ("ship-to-shore gantry crane")
  Handles handles = Handles::kContainers;
  std::span<const MachineFault> faults;  ///< the faults it has the parts for
  bool serves_trucks = false;            ///< road trucks come to it in its exercises
  std::span<const PilotType> pilots;     ///< its scripted operators, the first that can drive an exercise
  /// the rubric's deductions (rules.deductions keys) its operator can incur beyond those every machine's can
  /// (kEveryMachinesDeductions): with them, what the designer offers
  std::span<const std::string_view> deductions;
  /// the figures its attempts store (Metrics::rows names) beyond those every machine's do: what it has the
  /// parts to measure (a spreader's twistlocks, ropes, a gantry's horn, a load-moment limiter, wheels)
  std::span<const std::string_view> figures;

  bool has_fault(MachineFault fault) const {
    for (const MachineFault f : faults)
      if (f == fault) return true;
    return false;
  }
  bool can_incur(std::string_view deduction) const {
    for (const std::string_view d : kEveryMachinesDeductions)
      if (d == deduction) return true;
    for (const std::string_view d : deductions)
      if (d == deduction) return true;
    return false;
  }
  bool measures(std::string_view figure) const {
    for (const std::string_view f : figures)
      if (f == figure) return true;
    return false;
  }
};

}  // namespace harbour::sim
