#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "harbour/core/Vec3.h"
#include "harbour/sim/MachineType.h"

namespace harbour::physics {
class PhysicsWorld;
}  // namespace harbour::physics
namespace harbour::cable {
struct ReevingSettings;
}  // namespace harbour::cable
namespace harbour::scene {
class ControlTable;
}  // namespace harbour::scene

namespace harbour::sim {

class Machine;

/// A trailer a machine brings to its exercise (a tractor's, coupled at the start): what the exercise's moves
/// and bay markings need of it.
struct BroughtTrailer {
  std::string id;             ///< the exercise's name for it (its moves name it)
  core::Vec3 half_extents_m;  ///< [m] its deck's box
  bool receives_box = false;  ///< a team's crane may set a box on it
};

/// The machine an exercise runs, with where it starts, of whichever kind: a value holding one machine
/// folder's setup (`StsSetup`, `MhcSetup`, ...). A setup type has `static const MachineType& type()`,
/// `std::unique_ptr<Machine> build(physics::PhysicsWorld&) const`, `const ControlTable& controls() const` and
/// `std::vector<cable::ReevingSettings*> reevings()` (its ropes' settings, where a recorded run's rope model
/// is put back); it may have `void end_stops_at_travel()` (its travel stops at its end stops, with no margin
/// before them, as old runs were built), `bool slings_cargo() const` (it handles general cargo slung on its
/// hook, not bulk) and `std::optional<BroughtTrailer> trailer() const`. Nothing here names a machine: a new
/// one is a new setup type in its own folder.
class MachineSetup {
 public:
  MachineSetup() = default;  ///< none yet: an exercise's machine file sets it up
  template <typename Setup, typename = std::enable_if_t<!std::is_same_v<std::decay_t<Setup>, MachineSetup>>>
  MachineSetup(Setup setup)  // NOLINT: a setup is a machine setup
      : held_(std::make_unique<Held<std::decay_t<Setup>>>(std::move(setup))) {}
  MachineSetup(const MachineSetup& other) : held_(other.held_ ? other.held_->clone() : nullptr) {}
  MachineSetup(MachineSetup&&) noexcept = default;
  MachineSetup& operator=(const MachineSetup& other) {
    if (this != &other) held_ = other.held_ ? other.held_->clone() : nullptr;
    return *this;
  }
  MachineSetup& operator=(MachineSetup&&) noexcept = default;

  const MachineType& type() const { return held().type(); }
  /// Its kind as files name it ("sts").
  const char* kind() const { return type().kind; }
  /// The machine itself, in `world` at its start.
  std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const { return held().build(world); }
  /// Its controls as its machine file declares them (what device mappings bind).
  const scene::ControlTable& controls() const { return held().controls(); }
  /// Its reevings' settings (none for a machine without ropes).
  std::vector<cable::ReevingSettings*> reevings() { return held().reevings(); }
  /// Its travel stops at its end stops with no margin before them (a run recorded before the margin was
  /// kept); nothing for a machine whose setup has no such margin.
  void end_stops_at_travel() { held().end_stops_at_travel(); }
  /// Its exercise gives it general cargo slung on its hook (a crane with a grab or a hook: its tool as set
  /// up).
  bool slings_cargo() const { return held().slings_cargo(); }
  /// The trailer it brings to its exercise, if any.
  std::optional<BroughtTrailer> trailer() const { return held().trailer(); }
  /// Whether a machine is set up.
  bool has_value() const { return held_ != nullptr; }

  /// The setup when it is a `Setup`, else nullptr.
  template <typename Setup>
  const Setup* get_if() const {
    const auto* held = dynamic_cast<const Held<Setup>*>(held_.get());
    return held ? &held->setup : nullptr;
  }
  template <typename Setup>
  Setup* get_if() {
    auto* held = dynamic_cast<Held<Setup>*>(held_.get());
    return held ? &held->setup : nullptr;
  }
  /// The setup as a `Setup`; throws std::logic_error naming both kinds when it is another machine's.
  template <typename Setup>
  const Setup& as() const {
    if (const Setup* setup = get_if<Setup>()) return *setup;
    throw std::logic_error(std::string("the machine is an ") + kind() + ", not an " + Setup::type().kind);
  }
  template <typename Setup>
  Setup& as() {
    return const_cast<Setup&>(std::as_const(*this).template as<Setup>());
  }

 private:
  struct Base {
    virtual ~Base() = default;
    virtual std::unique_ptr<Base> clone() const = 0;
    virtual const MachineType& type() const = 0;
    virtual const scene::ControlTable& controls() const = 0;
    virtual std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const = 0;
    virtual std::vector<cable::ReevingSettings*> reevings() = 0;
    virtual void end_stops_at_travel() = 0;
    virtual bool slings_cargo() const = 0;
    virtual std::optional<BroughtTrailer> trailer() const = 0;
  };
  template <typename Setup>
  struct Held final : Base {
    explicit Held(Setup s) : setup(std::move(s)) {}
    std::unique_ptr<Base> clone() const override { return std::make_unique<Held>(setup); }
    const MachineType& type() const override { return Setup::type(); }
    const scene::ControlTable& controls() const override { return setup.controls(); }
    std::unique_ptr<Machine> build(physics::PhysicsWorld& world) const override { return setup.build(world); }
    std::vector<cable::ReevingSettings*> reevings() override { return setup.reevings(); }
    void end_stops_at_travel() override {
      if constexpr (requires { setup.end_stops_at_travel(); }) setup.end_stops_at_travel();
    }
    bool slings_cargo() const override {
      if constexpr (requires { setup.slings_cargo(); })
        return setup.slings_cargo();
      else
        return false;
    }
    std::optional<BroughtTrailer> trailer() const override {
      if constexpr (requires { setup.trailer(); })
        return setup.trailer();
      else
        return std::nullopt;
    }
    Setup setup;
  };

  const Base& held() const {
    if (!held_) throw std::logic_error("no machine set up");
    return *held_;
  }
  Base& held() { return const_cast<Base&>(std::as_const(*this).held()); }

  std::unique_ptr<Base> held_;
};

}  // namespace harbour::sim
