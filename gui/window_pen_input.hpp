#pragma once
// WindowPenInput: the pen on the GUI's scene view (mouse or tablet) as the loop's input source.
// The GUI thread publishes timestamped pen states through a wait-free LatestValue; the loop's
// latest() only reads it, so neither thread ever waits on the other.
//
// Sample age: the GUI re-publishes the pen state on its poll timer (every 16 ms) even when
// the pen does not move, so the stamp is the GUI thread's heartbeat. A pressed pen whose GUI
// stalls ages past the rig's max_input_age_s and the tick vents (input_stale): the window can
// hang but the rig cannot keep pressing on its behalf. A lifted pen asks for 0 kPa anyway, so
// its age is not held against it (a GUI hiccup while nobody presses must not fault the rig).
#include <atomic>
#include <cstdint>
#include <string>

#include "inputs/input_source.hpp"
#include "runtime/latest_value.hpp"

namespace palprig::gui {

struct WindowPen {
  double x_mm = 0, y_mm = 0, force_N = 0;
  bool in_contact = false;
  std::int64_t stamp_ns = 0;  // CLOCK_MONOTONIC when the GUI saw this state
};

class WindowPenInput final : public InputSource {
 public:
  WindowPenInput();
  // GUI thread only: the pen as the window sees it now, stamped on the monotonic clock.
  void publish(double x_mm, double y_mm, double force_N, bool in_contact) noexcept;
  void publish(const WindowPen& pen) noexcept { pens_.publish(pen); }

  // Loop thread only.
  TouchSample latest(double t_s) noexcept override;
  double duration_s() const noexcept override { return 0; }
  std::string describe() const override { return "window pen (mouse or tablet on the scene view)"; }

  // A new run restarts the loop's clock: the next latest() fixes a new epoch.
  void restart_clock() noexcept { epoch_fixed_.store(false, std::memory_order_relaxed); }

 private:
  LatestValue<WindowPen> pens_;
  std::atomic<bool> epoch_fixed_{false};
  std::int64_t epoch_ns_ = 0;  // loop time 0 on CLOCK_MONOTONIC (loop thread)
};

}  // namespace palprig::gui
