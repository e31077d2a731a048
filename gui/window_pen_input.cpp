#include "gui/window_pen_input.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/monotonic_clock.hpp"

namespace palprig::gui {

WindowPenInput::WindowPenInput() { pens_.publish(WindowPen{0, 0, 0, false, mono_ns()}); }

void WindowPenInput::publish(double x_mm, double y_mm, double force_N, bool in_contact) noexcept {
  pens_.publish(WindowPen{x_mm, y_mm, force_N, in_contact, mono_ns()});
}

TouchSample WindowPenInput::latest(double t_s) noexcept {
  const std::int64_t now = mono_ns();
  if (!epoch_fixed_.load(std::memory_order_relaxed)) {
    epoch_ns_ = now - static_cast<std::int64_t>(std::llround(t_s * 1e9));
    epoch_fixed_.store(true, std::memory_order_relaxed);
  }
  const WindowPen& p = pens_.latest();
  TouchSample s;
  s.x_mm = p.x_mm;
  s.y_mm = p.y_mm;
  s.force_N = p.force_N;
  s.in_contact = p.in_contact;
  // The stamp on the loop's clock; never in the loop's future (a stamp taken between the
  // epoch and this tick's time would otherwise look younger than it is).
  s.t_s = std::min(t_s, double(p.stamp_ns - epoch_ns_) * 1e-9);
  if (!p.in_contact && std::isfinite(p.force_N)) s.t_s = t_s;  // lifted: nothing to go stale
  return s;
}

}  // namespace palprig::gui
