#include "models/finger_layout.hpp"

#include <cmath>
#include <numbers>

namespace palprig {

std::array<Point2_mm, kFingerCount> FingerLayout::centres(double pen_x_mm, double pen_y_mm) const noexcept {
  const double a = orientation_deg * std::numbers::pi / 180.0;
  const double ux = std::cos(a), uy = std::sin(a);  // layout x axis
  const double vx = -uy, vy = ux;                   // layout y axis, perpendicular
  return {Point2_mm{pen_x_mm, pen_y_mm}, Point2_mm{pen_x_mm + spacing_mm * ux, pen_y_mm + spacing_mm * uy},
          Point2_mm{pen_x_mm + spacing_mm * vx, pen_y_mm + spacing_mm * vy}};
}

}  // namespace palprig
