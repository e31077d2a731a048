#include <gtest/gtest.h>

#include <algorithm>
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
  for (double target : reversal_trajectory())
    worst = std::max(worst, std::abs(model.apply(inverse.apply(target)) - target));
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

TEST(PrandtlIshlinskii, TheForwardModelOfAnInverseIsTheModel) {
  const PrandtlIshlinskii model = example_model();
  const PrandtlIshlinskii back = model.inverse().forward_of_inverse();
  ASSERT_EQ(back.operator_count, model.operator_count);
  EXPECT_NEAR(back.linear_weight, model.linear_weight, 1e-12);
  for (std::size_t i = 0; i < model.operator_count; ++i) {
    EXPECT_NEAR(back.weights[i], model.weights[i], 1e-12) << i;
    EXPECT_NEAR(back.thresholds_kPa[i], model.thresholds_kPa[i], 1e-12) << i;
  }
}

TEST(PrandtlIshlinskii, InputForIsTheExactInverseAtEveryPointOfTheHistory) {
  // Above the exhaust region it is the analytic inverse; and it stays exact when a command is
  // changed after it (a slew limit cutting a reversal's jump short), because the model's states
  // follow what was applied, where the analytic inverse, which assumed its own command, is then
  // off by up to the play's width.
  PrandtlIshlinskii analytic = example_model().inverse(), model = example_model(), actuator = example_model();
  analytic.reset(0);
  model.reset(0);
  actuator.reset(0);
  for (double target : reversal_trajectory()) {
    if (target < 12) continue;  // clear of the exhaust near 0 kPa (twice the largest play: 10 kPa)
    const double x = model.input_for(target);
    ASSERT_NEAR(x, analytic.apply(target), 1e-9) << target;
    ASSERT_NEAR(model.apply_exhausting(x), target, 1e-9);
  }
  auto worst_error = [&](bool follow_applied) {
    PrandtlIshlinskii plant = example_model(), m = example_model(), inv = example_model().inverse();
    plant.reset(0);
    m.reset(0);
    inv.reset(0);
    double last = 0, worst = 0;
    // Targets that turn back every few ticks; a setpoint slewing at most 1 kPa per tick.
    for (int k = 0; k < 400; ++k) {
      const double target = 20 + 6 * std::sin(k * 0.9) + (k % 7 == 0 ? 5 : 0);
      const double x = follow_applied ? m.input_for(target) : inv.apply(target);
      const double sent = std::clamp(x, last - 1.0, last + 1.0);
      last = sent;
      if (follow_applied) m.apply_exhausting(sent);
      const double y = plant.apply_exhausting(sent);
      if (sent == x && k > 50) worst = std::max(worst, std::abs(y - target));  // ticks the slew let through
    }
    return worst;
  };
  EXPECT_LT(worst_error(true), 1e-9);
  EXPECT_GT(worst_error(false), 0.5);
}

TEST(PrandtlIshlinskii, InputForNearTheBottomLandsTheExhaustingActuatorWithoutVenting) {
  // Coming down from 20 kPa to 1 kPa on a play of 2 kPa: the analytic inverse asks for -1 kPa
  // (clamped to 0: the regulator exhausts, and the actuator empties), the exhausting model's
  // inverse for 0.5 kPa, whose narrowed band above it holds the actuator at 1 kPa.
  PrandtlIshlinskii m;
  m.linear_weight = 0.01;
  m.operator_count = 1;
  m.thresholds_kPa[0] = 2.0;
  m.weights[0] = 0.99;
  m.reset(0);
  m.apply_exhausting(m.input_for(20));
  const double x = m.input_for(1.0);
  EXPECT_GT(x, 0.0);
  EXPECT_NEAR(m.apply_exhausting(x), 1.0, 1e-9);
  EXPECT_EQ(m.input_for(-3), 0.0);  // below what 0 kPa gives: the bottom
}

// The asymmetric (generalised) model: rising and falling plays of their own widths.
namespace {
PrandtlIshlinskii asymmetric_model() {
  PrandtlIshlinskii m;
  m.linear_weight = 0.3;
  m.operator_count = 3;
  m.asymmetric = true;
  m.thresholds_kPa = {3.0, 1.2, 5.0};  // rising: any order
  m.falling_thresholds_kPa = {1.0, 0.4, 2.0};
  m.weights = {0.45, 0.15, 0.1};
  return m;
}
}  // namespace

TEST(PrandtlIshlinskii, AsymmetricPlayLagsRisingAndFallingByItsOwnThresholds) {
  PrandtlIshlinskii m;
  m.linear_weight = 1e-12;
  m.operator_count = 1;
  m.asymmetric = true;
  m.thresholds_kPa[0] = 3.0;
  m.falling_thresholds_kPa[0] = 1.0;
  m.weights[0] = 1.0;
  ASSERT_TRUE(m.valid());
  m.reset(0);
  EXPECT_NEAR(m.apply(20), 17, 1e-9);  // rising: x - r+
  EXPECT_NEAR(m.apply(17.5), 17, 1e-9);
  EXPECT_NEAR(m.apply(10), 11, 1e-9);  // falling: x + r-
  EXPECT_NEAR(m.apply(14), 11, 1e-9);  // reversal: flat across r+ + r-
  // Exhausting: the band above narrows near 0, as the simulated regulator's.
  EXPECT_NEAR(m.apply_exhausting(0.5), 1.0, 1e-9);
  EXPECT_NEAR(m.apply_exhausting(0.0), 0.0, 1e-9);
}

TEST(PrandtlIshlinskii, AsymmetricWithEqualThresholdsIsTheSymmetricModel) {
  PrandtlIshlinskii sym = example_model(), asym = example_model();
  asym.asymmetric = true;
  asym.falling_thresholds_kPa = asym.thresholds_kPa;
  sym.reset(0);
  asym.reset(0);
  for (double x : reversal_trajectory()) ASSERT_EQ(sym.apply_exhausting(x), asym.apply_exhausting(x));
}

TEST(PrandtlIshlinskii, AsymmetricInverseLandsOnTargetOnBothBranches) {
  // The tick's use: the input for the target from the actuator's present state, then the
  // actuator (the same model, exhausting at 0) follows that input. Every target is met, rising
  // and falling, near 0 kPa too.
  PrandtlIshlinskii model = asymmetric_model(), actuator = asymmetric_model();
  ASSERT_TRUE(model.valid());
  model.reset(0);
  actuator.reset(0);
  std::vector<double> targets;
  for (double t : reversal_trajectory()) targets.push_back(t);
  for (int k = 0; k <= 200; ++k) targets.push_back(0.05 * (200 - k));  // down to 0
  for (int k = 0; k <= 100; ++k) targets.push_back(0.1 * k);           // and up from it
  double worst = 0, previous = 0;
  int rising = 0, falling = 0;
  for (double t : targets) {
    const double u = model.input_for(t);
    model.apply_exhausting(u);
    const double y = actuator.apply_exhausting(u);
    worst = std::max(worst, std::abs(y - t));
    (t > previous ? rising : falling) += t != previous;
    previous = t;
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(rising, 1000);
  EXPECT_GT(falling, 1000);
  // Without the inverse the same targets miss by the plays' widths, differently by branch.
  PrandtlIshlinskii plain = asymmetric_model();
  plain.reset(0);
  double worst_plain = 0;
  for (double t : targets) worst_plain = std::max(worst_plain, std::abs(plain.apply_exhausting(t) - t));
  EXPECT_GT(worst_plain, 1.0);
}

TEST(PrandtlIshlinskii, AsymmetricValidityRules) {
  PrandtlIshlinskii m = asymmetric_model();
  EXPECT_TRUE(m.valid());  // rising thresholds not in order: fine for the asymmetric model
  m.asymmetric = false;
  EXPECT_FALSE(m.valid());  // the symmetric model needs them increasing
  m = asymmetric_model();
  m.falling_thresholds_kPa[1] = 0;
  EXPECT_FALSE(m.valid());
  m.falling_thresholds_kPa[1] = NAN;
  EXPECT_FALSE(m.valid());
}
