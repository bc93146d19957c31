#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>

namespace harbour::core {

/// 64-bit FNV-1a over the exact bytes of state values: bit-identical states give equal hashes.
class StateHash {
 public:
  void add_bytes(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      value_ ^= bytes[i];
      value_ *= 0x100000001B3ull;
    }
  }
  template <typename T>
  requires std::is_trivially_copyable_v<T>
  void add(const T& v) { add_bytes(&v, sizeof v); }
  template <typename T>
  requires std::is_trivially_copyable_v<T>
  void add(std::span<const T> values) { add_bytes(values.data(), values.size_bytes()); }
  std::uint64_t value() const { return value_; }

 private:
  std::uint64_t value_ = 0xCBF29CE484222325ull;
};

}  // namespace harbour::core
