#pragma once
// Scoring for the pulse localisation task (a protocol trial type run by experiments/): the
// trainee feels for the pulse and marks where the artery is; the mark is scored by its
// distance on the skin plane to the artery's centreline (the polyline the scene gives), and is
// a hit when that distance is within a tolerance the protocol sets (for example the artery's
// radius plus a few millimetres for the finger's width).
#include <limits>
#include <string>

#include "models/artery.hpp"

namespace palprig {

struct PulseMarkScore {
  int artery = -1;  // index of the artery scored against; -1: the scene has none (or no such name)
  double distance_mm = std::numeric_limits<double>::infinity();
  bool hit = false;
};

// Against the named artery, or against the nearest one when artery_name is empty.
PulseMarkScore score_pulse_mark(const PulseField& arteries, const Point2_mm& mark, double tolerance_mm,
                                const std::string& artery_name = {});

}  // namespace palprig
