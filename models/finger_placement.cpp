#include "models/finger_placement.hpp"

#include <cmath>

namespace palprig {

PlacedFingers place_fingers(const FingerLayout& layout, const TouchSample& s, double contact_force_N) noexcept {
  PlacedFingers out;
  if (s.own_positions) {
    for (std::size_t i = 0; i < kFingerCount; ++i) out.centres[i] = {s.fingers[i].x_mm, s.fingers[i].y_mm};
  } else {
    out.centres = layout.centres(s.x_mm, s.y_mm);
  }
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    out.force_N[i] = s.per_finger_force ? s.fingers[i].force_N : s.force_N;
    out.pressed[i] = s.in_contact && out.force_N[i] >= contact_force_N && s.fingers[i].vent == FingerVent::none;
  }
  return out;
}

bool finger_positions_finite(const TouchSample& s) noexcept {
  if (!s.own_positions) return true;
  for (const FingerTouch& f : s.fingers)
    if (f.vent == FingerVent::none && (!std::isfinite(f.x_mm) || !std::isfinite(f.y_mm))) return false;
  return true;
}

bool finger_forces_valid(const TouchSample& s) noexcept {
  if (!s.per_finger_force) return true;
  for (const FingerTouch& f : s.fingers)
    if (!std::isfinite(f.force_N) || f.force_N < 0) return false;
  return true;
}

}  // namespace palprig
