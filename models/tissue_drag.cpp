#include "models/tissue_drag.hpp"

#include <cmath>

namespace palprig {

namespace {

void relax(FingerDrag& d, const DragSetting& s, double dt_s) noexcept {
  const double keep = s.relax_s > 0 && dt_s >= 0 ? std::exp(-dt_s / s.relax_s) : 0.0;
  d.offset.x_mm *= keep;
  d.offset.y_mm *= keep;
  if (std::hypot(d.offset.x_mm, d.offset.y_mm) < 1e-6) d.offset = {};
}

}  // namespace

void step_drag(FingerDrag& d, const DragSetting& s, const Point2_mm& centre, double force_N, bool pressed,
               double dt_s) noexcept {
  if (!std::isfinite(centre.x_mm) || !std::isfinite(centre.y_mm) || !std::isfinite(force_N) || !std::isfinite(dt_s)) {
    d = {};  // the tick faults on the bad reading; nothing is carried
    return;
  }
  const bool stick_force = pressed && s.drags() && force_N >= s.f_stick_N;
  if (!stick_force) {
    // Eq. 3's first case: below f_stick (or lifted) no lateral force, the skin relaxes.
    d.phase = DragPhase::free;
    relax(d, s, dt_s);
    return;
  }
  if (d.phase == DragPhase::sticking) {
    // Eq. 2: the stretch is the finger's way from where it stuck; the tissue goes with it.
    d.offset = {centre.x_mm - d.anchor.x_mm, centre.y_mm - d.anchor.y_mm};
    if (std::hypot(d.offset.x_mm, d.offset.y_mm) > s.d_lat_max_mm) {
      // Past d_lat_max: released (f_ext = 0), the skin relaxes from here.
      d.phase = DragPhase::slipping;
      relax(d, s, dt_s);
    }
    return;
  }
  // Free or slipping, pressed above f_stick: stick again once the skin has (nearly) relaxed.
  relax(d, s, dt_s);
  if (std::hypot(d.offset.x_mm, d.offset.y_mm) <= kDragRestickFraction * s.d_lat_max_mm) {
    d.phase = DragPhase::sticking;
    // C' is where the finger would have stuck for the tissue under it now to stay under it.
    d.anchor = {centre.x_mm - d.offset.x_mm, centre.y_mm - d.offset.y_mm};
  } else {
    d.phase = DragPhase::slipping;
  }
}

}  // namespace palprig
