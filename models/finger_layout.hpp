#pragma once
// FingerLayout: paper 002 places three finger spheres in a right-angled triangle whose
// right-angle vertex follows the pen. Finger 0 sits at that vertex (the pen), finger 1 one
// spacing along the layout's x axis, finger 2 one spacing along its y axis; the axes are the
// map's, rotated by orientation_deg (counter-clockwise). Coordinates follow the map: mm, origin
// at the map corner of row 0 / column 0.
#include <array>

namespace palprig {

struct Point2_mm {
  double x_mm = 0, y_mm = 0;
};

inline constexpr int kFingerCount = 3;

struct FingerLayout {
  double spacing_mm = 16.0;  // centre-to-centre along each leg; a fingertip is ~16 mm wide
  double orientation_deg = 0.0;

  std::array<Point2_mm, kFingerCount> centres(double pen_x_mm, double pen_y_mm) const noexcept;
};

}  // namespace palprig
