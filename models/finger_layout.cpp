#include "models/finger_layout.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace palprig {

std::array<Point2_mm, kFingerCount> FingerLayout::centres(double pen_x_mm, double pen_y_mm) const noexcept {
  // The layout's x axis. The tick places the fingers up to ten times a tick (now and at each
  // look-ahead time) with one orientation, so its cosine and sine are kept per thread for the
  // orientation they were computed for (per thread: a layout is shared read-only between the
  // loop and the window); a new orientation computes them again, bit for bit as before.
  // Compared by their bits: -0 degrees has its own sine (-0), as it had before the cache.
  thread_local std::uint64_t axis_bits = std::bit_cast<std::uint64_t>(0.0);
  thread_local double ux = 1.0, uy = 0.0;
  if (std::bit_cast<std::uint64_t>(orientation_deg) != axis_bits) {
    const double a = orientation_deg * std::numbers::pi / 180.0;
    ux = std::cos(a);
    uy = std::sin(a);
    axis_bits = std::bit_cast<std::uint64_t>(orientation_deg);
  }
  const double vx = -uy, vy = ux;  // layout y axis, perpendicular
  return {Point2_mm{pen_x_mm, pen_y_mm}, Point2_mm{pen_x_mm + spacing_mm * ux, pen_y_mm + spacing_mm * uy},
          Point2_mm{pen_x_mm + spacing_mm * vx, pen_y_mm + spacing_mm * vy}};
}

}  // namespace palprig
