// Linear regressions: known lines are recovered, R^2 and the residual spread match values
// computed by hand, and degenerate data is refused with a message naming the data set.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "calibration/line_fit.hpp"
#include "core/input_error.hpp"

using namespace palprig;

TEST(LineFit, RecoversAKnownLine) {
  std::vector<double> x, y;
  for (int i = 1; i <= 10; ++i) {
    x.push_back(10.0 * i);
    y.push_back(0.042 * 10.0 * i - 0.31);
  }
  const LineFit f = fit_line(x, y, "DATA.csv", "channel 1 inflation");
  EXPECT_NEAR(f.slope, 0.042, 1e-12);
  EXPECT_NEAR(f.intercept, -0.31, 1e-12);
  EXPECT_NEAR(f.r_squared, 1.0, 1e-12);
  EXPECT_NEAR(f.residual_sd, 0.0, 1e-9);
  EXPECT_EQ(f.n, 10u);
  EXPECT_DOUBLE_EQ(f.x_min, 10.0);
  EXPECT_DOUBLE_EQ(f.x_max, 100.0);
}

TEST(LineFit, RSquaredAndSpreadMatchAHandComputation) {
  // x = 1..5, y = 2, 4, 5, 4, 5: mean x 3, mean y 4, Sxx 10, Sxy 6, Syy 6.
  // slope 0.6, intercept 2.2, SS_res = Syy - slope*Sxy = 2.4, R^2 = 1 - 2.4/6 = 0.6,
  // residual SD = sqrt(2.4 / 3).
  const std::vector<double> x{1, 2, 3, 4, 5}, y{2, 4, 5, 4, 5};
  const LineFit f = fit_line(x, y, "f", "w");
  EXPECT_NEAR(f.slope, 0.6, 1e-12);
  EXPECT_NEAR(f.intercept, 2.2, 1e-12);
  EXPECT_NEAR(f.r_squared, 0.6, 1e-12);
  EXPECT_NEAR(f.residual_sd, std::sqrt(0.8), 1e-12);
  EXPECT_NEAR(f.x_for(f.at(3.7)), 3.7, 1e-12);
}

TEST(LineFit, NoisyLineWithinItsUncertainty) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.5);
  std::vector<double> x, y;
  for (int i = 0; i < 2000; ++i) {
    x.push_back(i * 0.05);
    y.push_back(1.7 * i * 0.05 + 4 + noise(rng));
  }
  const LineFit f = fit_line(x, y, "f", "w");
  EXPECT_NEAR(f.slope, 1.7, 0.01);
  EXPECT_NEAR(f.intercept, 4, 0.06);
  EXPECT_NEAR(f.residual_sd, 0.5, 0.03);
}

TEST(LineFit, RSquaredAgainstTheIdentityLine) {
  const std::vector<double> y{1, 2, 3, 4}, exact{1, 2, 3, 4}, off{2, 3, 4, 5};
  EXPECT_DOUBLE_EQ(r_squared_against(y, exact), 1.0);
  // SS_res = 4, SS_tot = 5: a constant offset of 1 costs 0.8.
  EXPECT_NEAR(r_squared_against(y, off), 1.0 - 4.0 / 5.0, 1e-12);
}

TEST(LineFit, RefusesDegenerateData) {
  auto message = [](std::vector<double> x, std::vector<double> y) -> std::string {
    try {
      fit_line(x, y, "DATA.csv", "channel 2 deflation");
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(message({1, 2}, {1, 2}), "DATA.csv: channel 2 deflation: at least 3 points for a line, got 2");
  EXPECT_EQ(message({5, 5, 5}, {1, 2, 3}),
            "DATA.csv: channel 2 deflation: values spread over x (all 3 points are at x = 5)");
  EXPECT_EQ(message({1, 2, 3}, {7, 7, 7}),
            "DATA.csv: channel 2 deflation: a response that moves (all 3 readings are 7)");
  EXPECT_EQ(message({1, 2, 3}, {1, std::nan(""), 3}),
            "DATA.csv: channel 2 deflation: finite values (point 2 is NaN or infinite)");
  EXPECT_EQ(message({1, 2, 3}, {1, 2}), "DATA.csv: channel 2 deflation: as many x as y values");
}
