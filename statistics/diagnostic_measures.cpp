#include "statistics/diagnostic_measures.hpp"

#include "statistics/statistics_proportion.hpp"

namespace palprig {

Measure proportion_measure(std::int64_t k, std::int64_t n, double confidence) {
  Measure m;
  m.k = k;
  m.n = n;
  m.defined = n > 0;
  if (m.defined) {
    const stats::WilsonInterval w = stats::wilson_interval(k, n, confidence);
    m.value = w.p;
    m.lower = w.lower;
    m.upper = w.upper;
  }
  return m;
}

DiagnosticMeasures diagnostic_measures(const ConfusionCounts& c, double confidence) {
  DiagnosticMeasures d;
  d.se = proportion_measure(c.tp, c.tp + c.fn, confidence);
  d.sp = proportion_measure(c.tn, c.tn + c.fp, confidence);
  d.ppv = proportion_measure(c.tp, c.tp + c.fp, confidence);
  d.acc = proportion_measure(c.tp + c.tn, c.total(), confidence);
  return d;
}

}  // namespace palprig
