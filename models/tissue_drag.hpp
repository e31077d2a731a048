#pragma once
// Tissue dragging with stick and slip (paper 000, section 3.2, eq. 3). A finger pressing the
// skin with a normal force of at least f_stick sticks to it: the skin, and what lies under it
// (tumors, arteries), is carried laterally with the finger. The stretch d_lat = |V - C'| (V the
// finger, C' where it stuck) is limited by d_lat_max: past it the skin is released (slip) and
// relaxes back (the external force nulled), and the finger slides on until the skin has
// relaxed, when it sticks again where it is. Pressing below f_stick, or lifting, releases too.
//
// What a finger feels is the tissue now under it: the material point centre - offset, where
// offset is how far the tissue under the finger has been carried (V - C' while sticking, then
// relaxing to 0 with time constant relax_s). So a tumor felt under a sliding finger moves with
// it for a while, then slips back, as on a real patient.
//
// Plain data and a pure step function: the tick keeps one FingerDrag per finger in its state.
#include "models/finger_layout.hpp"

namespace palprig {

// A layer's stick/slip parameters (the scene file's "drag" of a layer). d_lat_max_mm 0: the
// layer does not drag.
struct DragSetting {
  double f_stick_N = 0.5;   // normal force from which the finger sticks
  double d_lat_max_mm = 0;  // longest stretch before the skin slips (paper 000: 20-40 mm)
  double relax_s = 0.05;    // the released skin's relaxation time constant (0: at once)
  bool drags() const noexcept { return d_lat_max_mm > 0; }
};

enum class DragPhase : unsigned char {
  free,      // not pressed above f_stick, or the layer does not drag: relaxing to rest
  sticking,  // carried with the finger
  slipping,  // released past d_lat_max: relaxing, the finger slides until it can stick again
};

struct FingerDrag {
  DragPhase phase = DragPhase::free;
  Point2_mm anchor;  // C': the pad point where the finger stuck (the finger's centre then)
  Point2_mm offset;  // how far the tissue under the finger is carried now
  // The material point under a finger at `centre`.
  Point2_mm felt_point(const Point2_mm& centre) const noexcept {
    return {centre.x_mm - offset.x_mm, centre.y_mm - offset.y_mm};
  }
};

// A slipped skin sticks again once its stretch has relaxed below this fraction of d_lat_max.
inline constexpr double kDragRestickFraction = 0.1;

// One step of a finger's drag state: the finger at `centre` pressing with force_N (pressed:
// in contact at all), dt_s since the last step (0 on the first).
void step_drag(FingerDrag& drag, const DragSetting& setting, const Point2_mm& centre, double force_N, bool pressed,
               double dt_s) noexcept;

}  // namespace palprig
