#pragma once
// LatestValue<T>: hands the newest value from one writer thread to one reader thread without
// either ever waiting (a triple buffer). The bus I/O thread and the loop exchange setpoints and
// monitor readings through it, and the pen reader publishes samples through it, so the 1 kHz
// loop never blocks on a slow bus or device, and a preempted writer can never stall the reader
// (a sequence lock could make a real-time reader spin on a writer it preempted).
#include <atomic>
#include <cstdint>
#include <type_traits>

namespace palprig {

template <class T>
class LatestValue {
  static_assert(std::is_trivially_copyable_v<T>, "LatestValue carries plain values");

 public:
  explicit LatestValue(const T& initial = T{}) noexcept : slots_{initial, initial, initial} {}
  LatestValue(const LatestValue&) = delete;
  LatestValue& operator=(const LatestValue&) = delete;

  // Writer thread only.
  void publish(const T& value) noexcept {
    slots_[back_] = value;
    const std::uint8_t previous =
        middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel);
    back_ = previous & kIndexMask;
    published_.fetch_add(1, std::memory_order_relaxed);
  }

  // Reader thread only: the newest published value (or the last one read if nothing is new).
  const T& latest() noexcept {
    if (middle_.load(std::memory_order_relaxed) & kFresh) {
      const std::uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
      front_ = previous & kIndexMask;
    }
    return slots_[front_];
  }

  // How many values were published so far (any thread; for tests and statistics).
  std::uint64_t published() const noexcept { return published_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::uint8_t kFresh = 0x4, kIndexMask = 0x3;
  T slots_[3];
  std::uint8_t back_ = 1;   // owned by the writer
  std::uint8_t front_ = 0;  // owned by the reader
  std::atomic<std::uint8_t> middle_{2};
  std::atomic<std::uint64_t> published_{0};
};

}  // namespace palprig
