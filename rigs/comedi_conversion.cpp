#include "rigs/comedi_conversion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"

namespace palprig {

comedi_polynomial_t linear_polynomial(double range_min_V, double range_max_V, lsampl_t maxdata,
                                      comedi_conversion_direction direction) {
  comedi_polynomial_t p{};
  p.order = 1;
  p.expansion_origin = 0.0;
  const double counts_per_volt = double(maxdata) / (range_max_V - range_min_V);
  if (direction == COMEDI_FROM_PHYSICAL) {
    p.coefficients[0] = -range_min_V * counts_per_volt;
    p.coefficients[1] = counts_per_volt;
  } else {
    p.coefficients[0] = range_min_V;
    p.coefficients[1] = 1.0 / counts_per_volt;
  }
  return p;
}

ComediConversion make_comedi_conversion(const comedi_polynomial_t& to_counts, const comedi_polynomial_t& to_volts,
                                        lsampl_t maxdata, double range_min_V, double range_max_V, double span_lo_V,
                                        double span_hi_V, const RegulatorScale& regulator) {
  ComediConversion c;
  c.to_counts = to_counts;
  c.to_volts = to_volts;
  c.maxdata = maxdata;
  c.regulator = regulator;
  auto counts_at = [&](double v) {  // the polynomial comedi_from_physical evaluates, before rounding
    double value = 0, term = 1;
    for (unsigned i = 0; i <= to_counts.order; ++i) {
      value += to_counts.coefficients[i] * term;
      term *= v - to_counts.expansion_origin;
    }
    return value;
  };
  double lo = std::max(span_lo_V, range_min_V), hi = std::min(span_hi_V, range_max_V);
  if (lo > hi) throw BadInput("the regulator's volts span lies outside the card's range");
  if (!(counts_at(hi) > counts_at(lo))) throw BadInput("the conversion polynomial does not rise with volts");
  // Move an edge inwards to where the counts become representable (bisection on a rising
  // polynomial); a calibrated polynomial may put the range edges a few counts outside.
  auto solve = [&](double a, double b, double target) {  // counts_at(a) on the wrong side, counts_at(b) inside
    for (int i = 0; i < 80; ++i) {
      const double m = 0.5 * (a + b);
      const bool inside = target <= 0 ? counts_at(m) >= target : counts_at(m) <= target;
      (inside ? b : a) = m;
    }
    return b;
  };
  if (counts_at(lo) < -0.5) lo = solve(lo, hi, -0.5 + 1e-9);
  if (counts_at(hi) > double(maxdata) + 0.5) hi = solve(hi, lo, double(maxdata) + 0.5 - 1e-9);
  c.safe_lo_V = lo;
  c.safe_hi_V = hi;
  return c;
}

lsampl_t counts_from_volts(const ComediConversion& c, double volts) noexcept {
  if (!std::isfinite(volts)) volts = c.safe_lo_V;
  volts = std::clamp(volts, c.safe_lo_V, c.safe_hi_V);
  const lsampl_t counts = comedi_from_physical(volts, &c.to_counts);
  return std::min(counts, c.maxdata);
}

lsampl_t counts_from_kPa(const ComediConversion& c, double pressure_kPa) noexcept {
  return counts_from_volts(c, c.regulator.volts(pressure_kPa));
}

double kPa_from_counts(const ComediConversion& c, lsampl_t counts) noexcept {
  return c.regulator.pressure_kPa(comedi_to_physical(counts, &c.to_volts));
}

double volts_from_counts(const ComediConversion& c, lsampl_t counts) noexcept {
  return comedi_to_physical(counts, &c.to_volts);
}

}  // namespace palprig
