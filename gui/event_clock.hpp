#pragma once
// EventClock: when a participant's key press or mouse press happened, on std::chrono::steady_clock
// (CLOCK_MONOTONIC, the clock the session runs on), from the event's own timestamp
// (QInputEvent::timestamp()) rather than from when the window's handler ran. The difference is
// everything that delayed the event on its way: the X server, the window's event queue, a
// repaint, a busy GUI thread; tens of milliseconds on a loaded machine.
//
// The window system stamps each input event in milliseconds on its own clock. On Linux that
// clock is CLOCK_MONOTONIC for a local X server (Xorg and Xvfb stamp with GetTimeInMillis(),
// CLOCK_MONOTONIC in ms, 32 bits wrapping every 49.7 days; events from a real keyboard carry the
// kernel's CLOCK_MONOTONIC stamp of the key through libinput) and for Wayland compositors. So the
// stamp is recognised as that clock when it lies at most kMaxDeliveryLag_ms before the event's
// delivery (modulo 2^32); the event then happened within the stamp's millisecond: stamp + 0.5 ms
// (the stamp truncates; the error is uniform over +/-0.5 ms, sd 0.29 ms).
//
// Any other clock (a remote X server, a test tool's synthetic counter) has an unknown offset to
// ours. It is estimated per session as the smallest (delivery - stamp) seen, the event delayed
// least, and used only once the clock has been seen to run at the monotonic rate (two events at
// least kRateCheckSpan_ms apart whose stamps and deliveries agree within kForeignJitter_ms), and
// only for an event whose own delay agrees with it within kForeignJitter_ms; otherwise the
// delivery time is the best there is, and is used. A timestamp of 0 means none: delivery time.
//
// Not thread-safe: the GUI thread's, one per session (reset() at a session's start).
#include <chrono>
#include <cstdint>
#include <optional>

namespace palprig::gui {

class EventClock {
 public:
  using time_point = std::chrono::steady_clock::time_point;
  enum class Source {
    delivery,   // no usable stamp: when the event was delivered
    monotonic,  // the stamp is CLOCK_MONOTONIC in ms (a local X server, Wayland)
    offset,     // the stamp's own clock, at the offset estimated this session
  };
  struct Mapped {
    time_point at;
    Source source = Source::delivery;
  };

  static constexpr double kMaxDeliveryLag_ms = 2000;  // a stamp older than this is not taken for ours
  static constexpr double kForeignJitter_ms = 20;
  static constexpr double kRateCheckSpan_ms = 1000;

  // The event stamped `stamp_ms` (the window system's milliseconds), delivered at `delivered`.
  // Never later than `delivered`.
  Mapped map(std::uint64_t stamp_ms, time_point delivered) noexcept;
  void reset() noexcept { *this = EventClock{}; }

 private:
  struct Seen {
    double stamp_ms = 0, delivered_ms = 0;
  };
  std::optional<double> min_delay_ms_;  // min(delivered - stamp), foreign clocks
  std::optional<Seen> first_;           // the first stamped event of the session (rate check)
  bool rate_confirmed_ = false;
};

}  // namespace palprig::gui
