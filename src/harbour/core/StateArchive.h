#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "harbour/core/StateHash.h"

namespace harbour::core {

/// Raised when a saved state does not fit the simulation it is restored into (truncated, or from another
/// scenario or build).
class StateError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// State is written once. A stateful class lists its state in one function template over the archive,
//   template <typename Self, typename Archive> static void archive(Self& self, Archive& ar);
// which its save_state (Self const, a StateWriter) and its restore_state (a StateReader) both call: `ar(a,
// b)` writes or reads fields in order, `ar.sized(v)` a vector whose size the scenario fixes, `ar.part(p)` a
// member's own state, `ar.section(tag, what)` a tag restore checks; `if constexpr (Archive::kRestoring)`
// guards what only a restore does (checking what was read, rebuilding what follows from it).

/// Writes the exact bytes of state values (a keyframe). Values are written in the order the component's
/// save_state lists them; restore_state reads them back in the same order. A writer made on a StateHash
/// keeps nothing: it hashes the bytes (the state hash of exactly what save_state saves, allocating nothing).
class StateWriter {
 public:
  static constexpr bool kRestoring = false;

  StateWriter() = default;
  explicit StateWriter(StateHash& hash) : hash_(&hash) {}

  template <typename... T>
  void operator()(const T&... values) {
    (put(values), ...);
  }
  template <typename T>
  void sized(const std::vector<T>& values) {
    put(values);
  }
  template <typename Part>
  void part(const Part& p) {
    p.save_state(*this);
  }

  template <typename T>
  requires std::is_trivially_copyable_v<T>
  void put(const T& v) { append(&v, sizeof v); }
  template <typename T>
  requires std::is_trivially_copyable_v<T>
  void put(const std::vector<T>& values) {
    put(static_cast<std::uint64_t>(values.size()));
    append(values.data(), values.size() * sizeof(T));
  }
  /// A tag that restore checks, so a state from another layout is refused instead of misread.
  void section(std::uint32_t tag) { put(tag); }
  void section(std::uint32_t tag, const char* /*what: named by the reader*/) { put(tag); }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  void append(const void* data, std::size_t size) {
    if (size == 0) return;  // an empty vector's data() may be null
    if (hash_) {
      hash_->add_bytes(data, size);
      return;
    }
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }

  std::vector<std::uint8_t> bytes_;
  StateHash* hash_ = nullptr;
};

/// Reads what a StateWriter wrote; throws StateError on truncation, a wrong section tag or a wrong count.
class StateReader {
 public:
  static constexpr bool kRestoring = true;

  explicit StateReader(const std::vector<std::uint8_t>& bytes) : bytes_(bytes) {}

  template <typename... T>
  void operator()(T&... values) {
    (get(values), ...);
  }
  /// A vector as long as it is now (its length is the scenario's): a saved one of another length is refused.
  template <typename T>
  void sized(std::vector<T>& values) {
    get(values, static_cast<std::int64_t>(values.size()));
  }
  template <typename Part>
  void part(Part& p) {
    p.restore_state(*this);
  }

  template <typename T>
  requires std::is_trivially_copyable_v<T>
  void get(T& v) {
    need(sizeof v);
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
  }
  template <typename T>
  requires std::is_trivially_copyable_v<T> T get() {
    T v{};
    get(v);
    return v;
  }
  /// Reads a vector; `expected_size` (if not -1) must match, as for arrays whose size the scenario fixes.
  template <typename T>
  requires std::is_trivially_copyable_v<T>
  void get(std::vector<T>& values, std::int64_t expected_size = -1) {
    const auto n = get<std::uint64_t>();
    if (expected_size >= 0 && n != static_cast<std::uint64_t>(expected_size))
      throw StateError("saved state holds " + std::to_string(n) + " entries where the simulation has " +
                       std::to_string(expected_size));
    if (n > (bytes_.size() - at_) / sizeof(T)) throw StateError("saved state is truncated");
    values.resize(static_cast<std::size_t>(n));
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not get
    std::memcpy(values.data(), bytes_.data() + at_, values.size() * sizeof(T));
    at_ += values.size() * sizeof(T);
  }
  void section(std::uint32_t tag, const char* what) {
    if (get<std::uint32_t>() != tag)
      throw StateError(std::string("saved state does not match this simulation at its ") + what + " section");
  }
  /// Whether the next section's tag is `tag` (reads nothing): a layout that changed restores either version.
  bool next_section_is(std::uint32_t tag) const {
    std::uint32_t next = 0;
    if (bytes_.size() - at_ < sizeof next) return false;
    std::memcpy(&next, bytes_.data() + at_, sizeof next);
    return next == tag;
  }
  bool at_end() const { return at_ == bytes_.size(); }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) throw StateError("saved state is truncated");
  }
  const std::vector<std::uint8_t>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace harbour::core
