#include "statistics/statistics_correlation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "statistics/statistics_describe.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_proportion.hpp"
#include "statistics/statistics_ttest.hpp"

namespace palprig::stats {

PearsonResult pearson_from_r(double r, std::size_t n, double confidence) {
  if (n < 3) throw StatisticsError("a correlation test needs at least 3 pairs");
  if (!(r >= -1.0 && r <= 1.0)) throw StatisticsError("r must lie between -1 and 1");
  PearsonResult out;
  out.n = n;
  out.r = r;
  out.confidence = confidence;
  out.df = static_cast<double>(n) - 2.0;
  const double one_minus_r2 = 1.0 - r * r;
  out.t = one_minus_r2 > 0.0 ? r * std::sqrt(out.df / one_minus_r2)
                             : std::copysign(std::numeric_limits<double>::infinity(), r);
  out.p = two_sided_t_p(out.t, out.df);

  const double z_crit = two_sided_z(confidence);
  if (n > 3) {
    // Fisher's z = atanh(r) has standard error 1 / sqrt(n - 3).
    const double z = std::atanh(std::clamp(r, -1.0, 1.0));
    const double half = z_crit / std::sqrt(static_cast<double>(n) - 3.0);
    out.ci_lower = std::tanh(z - half);
    out.ci_upper = std::tanh(z + half);
  } else {
    out.ci_lower = out.ci_upper = std::numeric_limits<double>::quiet_NaN();
  }
  return out;
}

PearsonResult pearson(std::span<const double> x, std::span<const double> y, double confidence) {
  if (x.size() != y.size()) throw StatisticsError("a correlation needs two columns of equal length");
  if (x.size() < 3) throw StatisticsError("a correlation test needs at least 3 pairs");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) throw StatisticsError("a value is not a finite number");
  }
  // r does not depend on the units: each column is divided by a power of two near its largest
  // magnitude (exact), so sums and squares of values near +-1e308 cannot overflow.
  const double scale_x = power_of_two_scale(x), scale_y = power_of_two_scale(y);
  double mean_x = 0, mean_y = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mean_x += x[i] / scale_x;
    mean_y += y[i] / scale_y;
  }
  mean_x /= static_cast<double>(x.size());
  mean_y /= static_cast<double>(y.size());
  // Centred sums (two passes) rather than raw sums of squares, which cancel badly.
  double sxx = 0, syy = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] / scale_x - mean_x, dy = y[i] / scale_y - mean_y;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  if (!(sxx > 0.0) || !(syy > 0.0)) throw StatisticsError("a column is constant: the correlation is undefined");
  const double r = std::clamp(sxy / std::sqrt(sxx * syy), -1.0, 1.0);
  return pearson_from_r(r, x.size(), confidence);
}

}  // namespace palprig::stats
