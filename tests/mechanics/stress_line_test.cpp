// The actuator's stress line (fe stress-model, fe actuator): a least-squares line whose R^2 the
// stress-model file holds and refuses above 1. Points on a line, two points above all, have R^2 1
// exactly; its rounding once gave 1.0000000000000002 and the file was refused.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "mechanics/contact_problems.hpp"

namespace palprig::mechanics {
namespace {

TEST(StressLine, TwoPointsAndPointsOnALineHaveRSquaredOneAtMost) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> stress(0.5, 20.0), slope(0.01, 0.5);
  int exactly_one = 0;
  for (int i = 0; i < 2000; ++i) {
    const double a = slope(rng), b = stress(rng);
    std::vector<double> p{0, 25.0 + 50.0 * (i % 3)}, s{b + stress(rng) * 1e-3, 0};
    s[1] = s[0] + a * p[1];
    if (i % 2) {  // five points on one line
      p = {0, 25, 50, 75, 100};
      s.clear();
      for (double x : p) s.push_back(b + a * x);
    }
    const StressLine line = fit_stress_line(p, s);
    ASSERT_LE(line.r_squared, 1.0) << "points " << p.size() << ", slope " << a << ", intercept " << b;
    EXPECT_NEAR(line.r_squared, 1.0, 1e-12);
    exactly_one += line.r_squared == 1.0;
  }
  EXPECT_GT(exactly_one, 0);
}

TEST(StressLine, ScatterLowersRSquaredAndTheLineIsTheLeastSquaresOne) {
  const StressLine line = fit_stress_line({0, 50, 100}, {5, 11, 15});
  EXPECT_DOUBLE_EQ(line.slope, 0.1);
  EXPECT_NEAR(line.intercept_kPa, 5 + 1.0 / 3, 1e-12);
  EXPECT_NEAR(line.r_squared, 75.0 / 76.0, 1e-12);  // sxy^2 / (sxx syy) = 1000^2 / (5000 x 152/3)
}

TEST(StressLine, ARunsStepsGiveTheLineOfTheirAirAgainstTheirPeaks) {
  ContactRun run;
  for (const auto& [air_kPa, peak_kPa] : {std::pair{0.0, 5.0}, {50.0, 11.0}, {100.0, 15.0}}) {
    ContactStep step;
    step.load = air_kPa;
    step.peak_kPa = peak_kPa;
    run.steps.push_back(step);
  }
  const StressLine line = fit_stress_line(run);
  EXPECT_EQ(line.points, 3u);
  EXPECT_DOUBLE_EQ(line.slope, 0.1);
  EXPECT_NEAR(line.intercept_kPa, 5 + 1.0 / 3, 1e-12);
}

}  // namespace
}  // namespace palprig::mechanics
