// Identification of Prandtl-Ishlinskii models with Ceres: known parameters are recovered from
// synthetic data, the fitted model's analytic inverse undoes it over many reversals, and
// unusable data is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "calibration/hysteresis_fit.hpp"
#include "core/input_error.hpp"

using namespace palprig;

namespace {

// A quasi-static trajectory with reversals of many sizes inside [lo, hi]: random turning
// points joined by steps of at most step_kPa.
std::vector<double> reversal_sequence(std::size_t samples, double lo, double hi, double step_kPa, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> level(lo, hi);
  std::vector<double> x{lo};
  double goal = level(rng);
  while (x.size() < samples) {
    const double cur = x.back();
    if (std::abs(goal - cur) < 1e-9) {
      goal = level(rng);
      continue;
    }
    x.push_back(cur + std::clamp(goal - cur, -step_kPa, step_kPa));
  }
  return x;
}

PrandtlIshlinskii known_model() {
  PrandtlIshlinskii m;
  m.linear_weight = 0.55;
  m.operator_count = 4;
  m.thresholds_kPa = {1.0, 2.0, 3.0, 4.0};
  m.weights = {0.20, 0.0, 0.15, 0.10};
  return m;
}

// Weight of the operator at threshold r (0 when the fit dropped it as unused).
double weight_at(const PrandtlIshlinskii& m, double r) {
  for (std::size_t i = 0; i < m.operator_count; ++i)
    if (std::abs(m.thresholds_kPa[i] - r) < 1e-9) return m.weights[i];
  return 0.0;
}

std::vector<double> outputs(const PrandtlIshlinskii& m, const std::vector<double>& x, double noise_sd, unsigned seed) {
  std::vector<double> y(x.size());
  simulate_hysteresis(m, x, y);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_sd);
  if (noise_sd > 0)
    for (double& v : y) v += noise(rng);
  return y;
}

}  // namespace

TEST(HysteresisFit, RecoversKnownWeightsOnTheirThresholdGrid) {
  const PrandtlIshlinskii truth = known_model();
  const auto x = reversal_sequence(3000, 0, 60, 2.5, 7);
  const auto y = outputs(truth, x, 0.0, 1);
  HysteresisFitOptions o;
  o.operator_count = 4;
  o.max_threshold_kPa = 4.0;  // grid 1, 2, 3, 4 kPa: the true thresholds
  o.refine_thresholds = false;
  const HysteresisFit fit = fit_hysteresis(x, y, o, "synthetic", "known model");
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  EXPECT_NEAR(fit.model.linear_weight, truth.linear_weight, 1e-6);
  EXPECT_EQ(fit.model.operator_count, 3u);  // the zero-weight operator at 2 kPa is dropped
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(weight_at(fit.model, truth.thresholds_kPa[i]), truth.weights[i], 1e-6) << "operator " << i;
  EXPECT_LT(fit.rms_error_kPa, 1e-6);
  EXPECT_GT(fit.r_squared, 0.999999);
}

TEST(HysteresisFit, RecoversWeightsWithinNoise) {
  const PrandtlIshlinskii truth = known_model();
  const auto x = reversal_sequence(5000, 0, 60, 2.5, 11);
  const auto y = outputs(truth, x, 0.1, 2);
  HysteresisFitOptions o;
  o.operator_count = 4;
  o.max_threshold_kPa = 4.0;
  o.refine_thresholds = false;
  const HysteresisFit fit = fit_hysteresis(x, y, o, "synthetic", "noisy known model");
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  EXPECT_NEAR(fit.model.linear_weight, truth.linear_weight, 0.01);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(weight_at(fit.model, truth.thresholds_kPa[i]), truth.weights[i], 0.02) << "operator " << i;
  EXPECT_NEAR(fit.rms_error_kPa, 0.1, 0.01);  // what is left is the noise
}

TEST(HysteresisFit, RefinedThresholdsFindABacklashOffTheGrid) {
  // The simulated regulator's hysteresis: a pure play of half-width 2.3 kPa, no linear part.
  PrandtlIshlinskii backlash;
  backlash.linear_weight = 1e-9;
  backlash.operator_count = 1;
  backlash.thresholds_kPa[0] = 2.3;
  backlash.weights[0] = 1.0;
  const auto x = reversal_sequence(2000, 5, 60, 5.0, 3);
  const auto y = outputs(backlash, x, 0.05, 4);
  HysteresisFitOptions o;
  o.operator_count = 6;
  HysteresisFitOptions fixed = o;
  fixed.refine_thresholds = false;
  const HysteresisFit on_grid = fit_hysteresis(x, y, fixed, "synthetic", "backlash");
  const HysteresisFit refined = fit_hysteresis(x, y, o, "synthetic", "backlash");
  ASSERT_TRUE(refined.converged) << refined.solver_report;
  EXPECT_LE(refined.rms_error_kPa, on_grid.rms_error_kPa + 1e-9);
  EXPECT_LT(refined.rms_error_kPa, 0.08);  // noise 0.05 plus the forced 1 % linear part
  EXPECT_GE(refined.model.linear_weight, o.min_linear_weight);
  EXPECT_TRUE(refined.model.valid());
}

TEST(HysteresisFit, InverseOfTheFittedModelUndoesTheTrueHysteresis) {
  PrandtlIshlinskii truth = known_model();
  const auto x = reversal_sequence(4000, 0, 60, 2.0, 5);
  const auto y = outputs(truth, x, 0.05, 6);
  const HysteresisFit fit = fit_hysteresis(x, y, HysteresisFitOptions{}, "synthetic", "known model");
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  // Target trajectory with many reversals (a different one from the fit's).
  PrandtlIshlinskii inverse = fit.model.inverse();
  truth.reset(0);
  inverse.reset(0);
  const auto target = reversal_sequence(4000, 5, 55, 1.0, 99);
  double worst = 0, worst_uncompensated = 0;
  PrandtlIshlinskii plain = known_model();
  plain.reset(0);
  const double gain = truth.linear_weight + 0.2 + 0.15 + 0.10;
  for (double t : target) {
    worst = std::max(worst, std::abs(truth.apply(inverse.apply(t)) - t));
    worst_uncompensated = std::max(worst_uncompensated, std::abs(plain.apply(t / gain) - t));
  }
  EXPECT_LT(worst, 0.15);
  EXPECT_GT(worst_uncompensated, 5 * worst);
}

TEST(HysteresisFit, RobustLossResistsOutliers) {
  const PrandtlIshlinskii truth = known_model();
  const auto x = reversal_sequence(3000, 0, 60, 2.5, 8);
  auto y = outputs(truth, x, 0.05, 9);
  for (std::size_t k = 50; k < y.size(); k += 97) y[k] += 15.0;  // a sensor glitching upwards
  HysteresisFitOptions o;
  o.operator_count = 4;
  o.max_threshold_kPa = 4.0;
  o.refine_thresholds = false;
  const HysteresisFit plain = fit_hysteresis(x, y, o, "synthetic", "outliers");
  o.loss = RobustLoss::cauchy;
  o.loss_scale_kPa = 0.5;
  const HysteresisFit robust = fit_hysteresis(x, y, o, "synthetic", "outliers");
  ASSERT_TRUE(robust.converged) << robust.solver_report;
  auto weight_error = [&](const PrandtlIshlinskii& m) {
    double e = std::abs(m.linear_weight - truth.linear_weight);
    for (std::size_t i = 0; i < 4; ++i) e += std::abs(weight_at(m, truth.thresholds_kPa[i]) - truth.weights[i]);
    return e;
  };
  EXPECT_LT(weight_error(robust.model), 0.02);
  EXPECT_LT(weight_error(robust.model), 0.5 * weight_error(plain.model));
}

TEST(HysteresisFit, RefusesUnusableData) {
  HysteresisFitOptions o;
  o.operator_count = 4;
  const auto x = reversal_sequence(200, 0, 60, 2.5, 1);
  const auto y = outputs(known_model(), x, 0, 1);
  auto refused = [&](std::vector<double> xs, std::vector<double> ys, const std::string& fragment) {
    try {
      fit_hysteresis(xs, ys, o, "DATA.csv", "channel 2 hysteresis");
      ADD_FAILURE() << "accepted data that should be refused (" << fragment << ")";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("channel 2 hysteresis"), std::string::npos) << e.what();
    }
  };
  refused({x.begin(), x.begin() + 20}, {y.begin(), y.begin() + 20}, "at least 36");
  auto with_nan = y;
  with_nan[17] = std::nan("");
  refused(x, with_nan, "sample 18");
  refused(std::vector<double>(200, 30.0), y, "an input that moves");
  std::vector<double> ramp(200);
  for (std::size_t k = 0; k < ramp.size(); ++k) ramp[k] = 0.25 * double(k);
  refused(ramp, ramp, "reverses");
  std::vector<double> falling(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) falling[k] = 100 - y[k];
  refused(x, falling, "rises with the input");
  // Options Ceres would abort on are refused before it sees them.
  HysteresisFitOptions bad;
  bad.loss = RobustLoss::huber;
  bad.loss_scale_kPa = 0;
  EXPECT_THROW(fit_hysteresis(x, y, bad, "f", "w"), InputError);
  bad = {};
  bad.min_linear_weight = 0;
  EXPECT_THROW(fit_hysteresis(x, y, bad, "f", "w"), InputError);
  bad = {};
  bad.max_iterations = 0;
  EXPECT_THROW(fit_hysteresis(x, y, bad, "f", "w"), InputError);
}

// The asymmetric (generalised) model, separate rising and falling thresholds.
namespace {
PrandtlIshlinskii known_asymmetric_model() {
  PrandtlIshlinskii m;
  m.linear_weight = 0.2;
  m.operator_count = 2;
  m.asymmetric = true;
  m.thresholds_kPa = {3.0, 1.5};
  m.falling_thresholds_kPa = {1.0, 0.5};
  m.weights = {0.6, 0.2};
  return m;
}
}  // namespace

TEST(HysteresisFit, AsymmetricModelRecoversKnownParameters) {
  const PrandtlIshlinskii truth = known_asymmetric_model();
  const auto x = reversal_sequence(4000, 0, 60, 1.0, 21);
  const auto y = outputs(truth, x, 0.02, 22);
  HysteresisFitOptions o;
  o.asymmetric = true;
  o.operator_count = 4;
  const HysteresisFit fit = fit_hysteresis(x, y, o, "synthetic", "asymmetric known model");
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  ASSERT_TRUE(fit.model.asymmetric);
  ASSERT_TRUE(fit.model.valid());
  EXPECT_LT(fit.rms_error_kPa, 0.03);  // the noise
  // What the data determines: the total gain, and the weighted mean rising and falling widths
  // (the loop's lag behind a rising and a falling input): 0.8 x 2.625 and 0.8 x 0.875 kPa.
  double gain = fit.model.linear_weight, rise = 0, fall = 0, w = 0;
  for (std::size_t i = 0; i < fit.model.operator_count; ++i) {
    gain += fit.model.weights[i];
    w += fit.model.weights[i];
    rise += fit.model.weights[i] * fit.model.thresholds_kPa[i];
    fall += fit.model.weights[i] * fit.model.falling_thresholds_kPa[i];
  }
  EXPECT_NEAR(gain, 1.0, 0.005);
  EXPECT_NEAR(rise, 0.6 * 3.0 + 0.2 * 1.5, 0.03);
  EXPECT_NEAR(fall, 0.6 * 1.0 + 0.2 * 0.5, 0.03);
  EXPECT_NEAR(fit.model.linear_weight, 0.2, 0.03);
  // And it predicts a different trajectory of the same plant.
  const auto x2 = reversal_sequence(2000, 0, 60, 1.0, 23);
  const auto y2 = outputs(truth, x2, 0, 0);
  std::vector<double> predicted(x2.size());
  simulate_hysteresis(fit.model, x2, predicted);
  double worst = 0;
  for (std::size_t k = 0; k < x2.size(); ++k) worst = std::max(worst, std::abs(predicted[k] - y2[k]));
  EXPECT_LT(worst, 0.1);
  // The symmetric model cannot: it splits the difference between the branches.
  o.asymmetric = false;
  const HysteresisFit sym = fit_hysteresis(x, y, o, "synthetic", "asymmetric known model");
  EXPECT_GT(sym.rms_error_kPa, 5 * fit.rms_error_kPa);
}

TEST(HysteresisFit, AsymmetricPlayRecoveredExactly) {
  // One play of 3 kPa rising and 1 kPa falling (the shipped asymmetric regulator's), weight 0.8,
  // linear part 0.2: off the grid, found by Ceres.
  PrandtlIshlinskii truth;
  truth.linear_weight = 0.2;
  truth.operator_count = 1;
  truth.asymmetric = true;
  truth.thresholds_kPa[0] = 3.0;
  truth.falling_thresholds_kPa[0] = 1.0;
  truth.weights[0] = 0.8;
  const auto x = reversal_sequence(2000, 0, 60, 2.0, 31);
  const auto y = outputs(truth, x, 0.01, 32);
  HysteresisFitOptions o;
  o.asymmetric = true;
  o.operator_count = 1;
  const HysteresisFit fit = fit_hysteresis(x, y, o, "synthetic", "one asymmetric play");
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  ASSERT_EQ(fit.model.operator_count, 1u);
  EXPECT_NEAR(fit.model.linear_weight, 0.2, 0.005);
  EXPECT_NEAR(fit.model.weights[0], 0.8, 0.005);
  EXPECT_NEAR(fit.model.thresholds_kPa[0], 3.0, 0.02);
  EXPECT_NEAR(fit.model.falling_thresholds_kPa[0], 1.0, 0.02);
}

// A regulator's plays exhaust near 0 kPa: commanded 0 kPa it empties the actuator, so the band
// above the command narrows to the command (PrandtlIshlinskii::apply_exhausting, the model the
// tick inverts). A sweep whose runs start from a vent, fitted with the plays as the regulator runs
// them, recovers the one asymmetric play of palprig's shipped regulator; fitted with the plain
// plays of the textbook model (exhausting false), the states the vents leave are wrong for the
// whole next run and the same data leaves several times the error.
TEST(HysteresisFit, PlaysExhaustingAtTheVentAreFittedAsTheRegulatorRunsThem) {
  PrandtlIshlinskii truth;
  truth.linear_weight = 0.2;
  truth.operator_count = 1;
  truth.asymmetric = true;
  truth.thresholds_kPa[0] = 3.0;
  truth.falling_thresholds_kPa[0] = 1.0;
  truth.weights[0] = 0.8;
  // Five staircases 10..60..10 kPa, each from a vent at 0 kPa, as calibrate sweep runs them.
  std::vector<double> x;
  for (int run = 0; run < 5; ++run) {
    x.push_back(0.0);
    for (int l = 10; l <= 60; l += 10) x.push_back(l);
    for (int l = 60; l >= 10; l -= 10) x.push_back(l);
  }
  std::vector<double> y(x.size());
  PrandtlIshlinskii regulator = truth;
  regulator.reset(0.0);
  for (std::size_t k = 0; k < x.size(); ++k) y[k] = regulator.apply_exhausting(x[k]);
  std::vector<double> simulated(x.size());
  simulate_hysteresis(truth, x, simulated);  // exhausting by default: the same outputs
  for (std::size_t k = 0; k < x.size(); ++k) ASSERT_DOUBLE_EQ(simulated[k], y[k]) << k;

  HysteresisFitOptions o;
  o.asymmetric = true;
  o.operator_count = 1;
  const HysteresisFit fit = fit_hysteresis(x, y, o, "synthetic", "exhausting play");
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  EXPECT_LT(fit.rms_error_kPa, 0.01);
  // Steps of 10 kPa, larger than the play, show the loop's width but not how it splits between
  // a threshold and its weight: what they identify is the gain and the two offsets w r+ and w r-
  // (2.4 and 0.8 kPa here).
  ASSERT_EQ(fit.model.operator_count, 1u);
  EXPECT_NEAR(fit.model.weights[0] + fit.model.linear_weight, 1.0, 0.01);
  EXPECT_NEAR(fit.model.weights[0] * fit.model.thresholds_kPa[0], 2.4, 0.05);
  EXPECT_NEAR(fit.model.weights[0] * fit.model.falling_thresholds_kPa[0], 0.8, 0.05);

  o.exhausting = false;
  const HysteresisFit plain = fit_hysteresis(x, y, o, "synthetic", "plain play");
  EXPECT_GT(plain.rms_error_kPa, 5 * fit.rms_error_kPa + 0.05) << plain.solver_report;
}

// The textbook model stays available: data from plain plays (a regulator that does not empty at
// a vent), through 0 kPa, fitted with exhausting off, recovers its weights on their grid.
TEST(HysteresisFit, PlainPlaysFitDataFromARegulatorThatDoesNotExhaust) {
  const PrandtlIshlinskii truth = known_model();
  const auto x = reversal_sequence(3000, 0, 60, 2.5, 7);
  std::vector<double> y(x.size());
  simulate_hysteresis(truth, x, y, false);
  HysteresisFitOptions o;
  o.operator_count = 4;
  o.max_threshold_kPa = 4.0;
  o.refine_thresholds = false;
  o.exhausting = false;
  const HysteresisFit fit = fit_hysteresis(x, y, o, "synthetic", "plain plays");
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  EXPECT_LT(fit.rms_error_kPa, 1e-6);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(weight_at(fit.model, truth.thresholds_kPa[i]), truth.weights[i], 1e-6) << "operator " << i;
  // The same data fitted exhausting cannot be exact wherever the sequence comes near 0 kPa.
  o.exhausting = true;
  EXPECT_GT(fit_hysteresis(x, y, o, "synthetic", "exhausting").rms_error_kPa, 10 * fit.rms_error_kPa);
}
