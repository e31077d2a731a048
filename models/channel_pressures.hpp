#pragma once
// One pressure per finger channel, in kPa: what the tick computes, what a backend is sent and
// what the regulators report. Its own header so that the pure tick and the device seam share
// the type without including each other.
#include <array>

#include "models/finger_layout.hpp"

namespace palprig {

using ChannelPressures = std::array<double, kFingerCount>;  // kPa, one per finger channel

}  // namespace palprig
