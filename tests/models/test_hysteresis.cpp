#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "models/hysteresis.hpp"

using namespace palprig;

namespace {
PrandtlIshlinskii example_model() {
  PrandtlIshlinskii m;
  m.linear_weight = 0.6;
  m.operator_count = 3;
  m.thresholds_kPa = {1.0, 2.5, 5.0};
  m.weights = {0.2, 0.15, 0.1};
  return m;
}

// A trajectory with many reversals of different sizes.
std::vector<double> reversal_trajectory() {
  std::vector<double> x;
  for (int k = 0; k < 4000; ++k) {
    const double t = k * 0.001;
    x.push_back(30 + 20 * std::sin(2 * M_PI * 1.3 * t) + 8 * std::sin(2 * M_PI * 7.1 * t));
  }
  return x;
}
}  // namespace

TEST(PrandtlIshlinskii, SinglePlayOperatorIsBacklash) {
  PrandtlIshlinskii m;
  m.linear_weight = 1e-12;  // practically pure play
  m.operator_count = 1;
  m.thresholds_kPa[0] = 2.0;
  m.weights[0] = 1.0;
  m.reset(0);
  EXPECT_NEAR(m.apply(10), 8, 1e-9);
  EXPECT_NEAR(m.apply(9), 8, 1e-9);  // inside the backlash: no change
  EXPECT_NEAR(m.apply(5), 7, 1e-9);
}

TEST(PrandtlIshlinskii, InverseComposedWithModelIsIdentity) {
  PrandtlIshlinskii model = example_model();
  ASSERT_TRUE(model.valid());
  PrandtlIshlinskii inverse = model.inverse();
  model.reset(0);
  inverse.reset(0);
  double worst = 0;
  for (double target : reversal_trajectory()) worst = std::max(worst, std::abs(model.apply(inverse.apply(target)) - target));
  EXPECT_LT(worst, 1e-9);
}

TEST(PrandtlIshlinskii, ValidityRules) {
  PrandtlIshlinskii m = example_model();
  EXPECT_TRUE(m.valid());
  m.weights[1] = -0.1;
  EXPECT_FALSE(m.valid());
  m = example_model();
  m.thresholds_kPa[2] = 2.0;  // not increasing
  EXPECT_FALSE(m.valid());
  m = example_model();
  m.linear_weight = 0;
  EXPECT_FALSE(m.valid());
}
