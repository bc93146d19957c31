#pragma once

#include <array>
#include <atomic>
#include <memory>

namespace harbour::station {

/// One writer hands its latest value to one reader without locks or allocation: the writer fills back() and
/// publishes it; the reader takes the newest published value whenever it looks, at its own rate.
template <class T>
class TripleBuffer {
 public:
  TripleBuffer() : buffers_(std::make_unique<std::array<T, 3>>()) {}

  /// Writer: the buffer to fill next.
  T& back() { return (*buffers_)[back_]; }
  /// Before the reader starts: `prepare` runs on each of the three buffers (room reserved in each, so that
  /// neither side allocates later).
  template <class Prepare>
  void prepare_each(Prepare&& prepare) {
    for (T& buffer : *buffers_)
      prepare(buffer);
  }
  /// Writer: back() becomes the newest value.
  void publish() { back_ = state_.exchange(back_ | kFresh, std::memory_order_acq_rel) & kIndex; }

  /// Reader: the newest published value (nullptr before the first), stable until the next call.
  const T* latest() {
    if (state_.load(std::memory_order_acquire) & kFresh) {
      front_ = state_.exchange(front_, std::memory_order_acq_rel) & kIndex;
      has_value_ = true;
    }
    return has_value_ ? &(*buffers_)[front_] : nullptr;
  }

 private:
  static constexpr unsigned kIndex = 3, kFresh = 4;
  std::unique_ptr<std::array<T, 3>> buffers_;
  std::atomic<unsigned> state_{1};  // the middle buffer's index, and whether it holds a fresh value
  unsigned back_ = 0, front_ = 2;
  bool has_value_ = false;
};

}  // namespace harbour::station
