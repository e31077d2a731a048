#include "statistics/diagnostic_measures.hpp"

#include "statistics/statistics_proportion.hpp"

namespace palprig {

namespace {

Measure measure(std::int64_t k, std::int64_t n, double confidence) {
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

}  // namespace

DiagnosticMeasures diagnostic_measures(const ConfusionCounts& c, double confidence) {
  DiagnosticMeasures d;
  d.se = measure(c.tp, c.tp + c.fn, confidence);
  d.sp = measure(c.tn, c.tn + c.fp, confidence);
  d.ppv = measure(c.tp, c.tp + c.fp, confidence);
  d.acc = measure(c.tp + c.tn, c.total(), confidence);
  return d;
}

}  // namespace palprig
