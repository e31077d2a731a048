#pragma once
// Confusion counts and paper 002's measures (eq. 5-8), each with its Wilson interval:
//   Se = TP/(TP+FN), Sp = TN/(TN+FP), PPV = TP/(TP+FP), ACC = (TP+TN)/(TP+TN+FP+FN).
// A measure whose denominator is 0 (no positives, say) is marked undefined, not reported as 0.
#include <cstdint>

#include "statistics/outcome.hpp"

namespace palprig {

struct ConfusionCounts {
  std::int64_t tp = 0, fn = 0, tn = 0, fp = 0;
  void add(Outcome o) noexcept {
    switch (o) {
      case Outcome::tp: ++tp; break;
      case Outcome::fn: ++fn; break;
      case Outcome::tn: ++tn; break;
      case Outcome::fp: ++fp; break;
    }
  }
  ConfusionCounts& operator+=(const ConfusionCounts& o) noexcept {
    tp += o.tp;
    fn += o.fn;
    tn += o.tn;
    fp += o.fp;
    return *this;
  }
  std::int64_t total() const noexcept { return tp + fn + tn + fp; }
};

struct Measure {
  std::int64_t k = 0, n = 0;
  bool defined = false;  // n > 0
  double value = 0, lower = 0, upper = 0;
};

struct DiagnosticMeasures {
  Measure se, sp, ppv, acc;
};

DiagnosticMeasures diagnostic_measures(const ConfusionCounts& counts, double confidence = 0.95);
// k of n with its Wilson interval (undefined when n is 0): a measure with another denominator.
Measure proportion_measure(std::int64_t k, std::int64_t n, double confidence = 0.95);

}  // namespace palprig
