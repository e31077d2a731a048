#pragma once
// Ordinary least-squares line y = slope * x + intercept with the figures paper 002 reports for
// its actuator deformation fits (fig. 8): R^2 and the spread of the residuals. Refuses what
// would give a meaningless line (too few points, constant x or y, NaN) with an InputError
// naming the data set, so no calibration is ever written from a silent degenerate fit.
#include <span>
#include <string>

namespace palprig {

struct LineFit {
  double slope = 0;
  double intercept = 0;
  double r_squared = 0;    // 1 - SS_res / SS_tot
  double residual_sd = 0;  // sqrt(SS_res / (n - 2)), in y's unit
  std::size_t n = 0;
  double x_min = 0, x_max = 0;

  double at(double x) const noexcept { return slope * x + intercept; }
  // x for a given y (the inverse the stress model uses); requires slope != 0.
  double x_for(double y) const noexcept { return (y - intercept) / slope; }
};

// `file` and `what` name the data in errors, e.g. ("DATA.csv", "channel 2 inflation").
// Two points always fit: no R^2 and no spread. A fit needs this many (and two distinct x).
inline constexpr std::size_t kMinLinePoints = 3;

LineFit fit_line(std::span<const double> x, std::span<const double> y, const std::string& file,
                 const std::string& what);

// R^2 of y against a given prediction (e.g. output against target, the identity line):
// 1 - sum (y - p)^2 / sum (y - mean y)^2. Not clamped: a prediction worse than the mean is < 0.
double r_squared_against(std::span<const double> y, std::span<const double> prediction) noexcept;

}  // namespace palprig
