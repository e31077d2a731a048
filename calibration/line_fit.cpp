#include "calibration/line_fit.hpp"

#include <cmath>
#include <sstream>

#include "core/input_error.hpp"

namespace palprig {

LineFit fit_line(std::span<const double> x, std::span<const double> y, const std::string& file,
                 const std::string& what) {
  if (x.size() != y.size()) throw InputError(file, what, "as many x as y values");
  const std::size_t n = x.size();
  if (n < kMinLinePoints)
    throw InputError(file, what,
                     "at least " + std::to_string(kMinLinePoints) + " points for a line, got " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
      throw InputError(file, what, "finite values (point " + std::to_string(i + 1) + " is NaN or infinite)");
  // Two-pass sums around the means: stable for readings far from zero.
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= double(n);
  my /= double(n);
  double sxx = 0, syy = 0, sxy = 0;
  LineFit f;
  f.n = n;
  f.x_min = f.x_max = x[0];
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = x[i] - mx, dy = y[i] - my;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
    f.x_min = std::min(f.x_min, x[i]);
    f.x_max = std::max(f.x_max, x[i]);
  }
  const double scale_x = std::max(std::abs(mx), 1.0), scale_y = std::max(std::abs(my), 1.0);
  if (!(sxx > 1e-18 * scale_x * scale_x * double(n))) {
    std::ostringstream s;
    s << "values spread over x (all " << n << " points are at x = " << mx << ")";
    throw InputError(file, what, s.str());
  }
  if (!(syy > 1e-18 * scale_y * scale_y * double(n))) {
    std::ostringstream s;
    s << "a response that moves (all " << n << " readings are " << my << ")";
    throw InputError(file, what, s.str());
  }
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  double ss_res = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - f.at(x[i]);
    ss_res += r * r;
  }
  f.r_squared = 1.0 - ss_res / syy;
  f.residual_sd = n > 2 ? std::sqrt(ss_res / double(n - 2)) : 0.0;
  return f;
}

double r_squared_against(std::span<const double> y, std::span<const double> prediction) noexcept {
  const std::size_t n = std::min(y.size(), prediction.size());
  if (n == 0) return 0;
  double my = 0;
  for (std::size_t i = 0; i < n; ++i) my += y[i];
  my /= double(n);
  double ss_res = 0, ss_tot = 0;
  for (std::size_t i = 0; i < n; ++i) {
    ss_res += (y[i] - prediction[i]) * (y[i] - prediction[i]);
    ss_tot += (y[i] - my) * (y[i] - my);
  }
  return ss_tot > 0 ? 1.0 - ss_res / ss_tot : 0.0;
}

}  // namespace palprig
