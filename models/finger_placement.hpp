#pragma once
// Where the fingers are and how hard each presses, from one sample: FingerLayout's triangle
// around the pen (paper 002), or each finger at its own tracked position; one force
// for all fingers (the pen, a shared load cell) or one per finger (a load cell under each).
#include <array>

#include "models/finger_layout.hpp"
#include "models/touch_sample.hpp"

namespace palprig {

struct PlacedFingers {
  std::array<Point2_mm, kFingerCount> centres{};
  std::array<double, kFingerCount> force_N{};
  // In contact, pressing at least contact_force_N, and not vented (FingerVent::none).
  std::array<bool, kFingerCount> pressed{};
};

PlacedFingers place_fingers(const FingerLayout& layout, const TouchSample& sample, double contact_force_N) noexcept;

// True when every per-finger value the sample uses is finite (and each used force >= 0): the
// tick checks this beside the pen's own x, y and force.
bool finger_positions_finite(const TouchSample& sample) noexcept;
bool finger_forces_valid(const TouchSample& sample) noexcept;

}  // namespace palprig
