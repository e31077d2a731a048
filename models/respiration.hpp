#pragma once
// Respiration (paper 001): organs under the ribs move with the breathing cycle, so what a
// finger feels at a fixed point changes over time. One cycle of period_s starts at full
// expiration (t = 0, rest position) and reaches full inspiration at half the period; an organ
// that moves with breathing is displaced by its excursion times
//     (1 - cos(2 pi t / period)) / 2,
// a smooth cycle with no jump at the start of a run. period_s = 0 means no breathing.
#include <cmath>
#include <numbers>

#include "models/frep.hpp"

namespace palprig {

struct Respiration {
  double period_s = 0.0;

  bool breathing() const noexcept { return period_s > 0; }
  // 0 at full expiration, 1 at full inspiration.
  double inspiration(double t_s) const noexcept {
    if (!breathing() || !std::isfinite(t_s)) return 0.0;
    return 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * t_s / period_s));
  }
  Point3_mm displacement(const Point3_mm& excursion_mm, double t_s) const noexcept {
    const double k = inspiration(t_s);
    return {excursion_mm.x_mm * k, excursion_mm.y_mm * k, excursion_mm.z_mm * k};
  }
};

}  // namespace palprig
