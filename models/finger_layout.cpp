#include "models/finger_layout.hpp"

#include <cmath>
#include <numbers>

namespace palprig {

std::array<Point2_mm, kFingerCount> FingerLayout::centres(double pen_x_mm, double pen_y_mm) const noexcept {
  // The layout's x axis. The tick places the fingers up to ten times a tick (now and at each
  // look-ahead time) with one orientation, so its cosine and sine are kept per thread for the
  // orientation they were computed for (per thread: a layout is shared read-only between the
  // loop and the window); a new orientation computes them again, bit for bit as before.
  thread_local double axis_deg = 0.0, ux = 1.0, uy = 0.0;
  if (orientation_deg != axis_deg) {
    const double a = orientation_deg * std::numbers::pi / 180.0;
    ux = std::cos(a);
    uy = std::sin(a);
    axis_deg = orientation_deg;
  }
  const double vx = -uy, vy = ux;  // layout y axis, perpendicular
  return {Point2_mm{pen_x_mm, pen_y_mm}, Point2_mm{pen_x_mm + spacing_mm * ux, pen_y_mm + spacing_mm * uy},
          Point2_mm{pen_x_mm + spacing_mm * vx, pen_y_mm + spacing_mm * vy}};
}

}  // namespace palprig
