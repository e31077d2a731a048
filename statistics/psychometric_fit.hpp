#pragma once
// Psychometric function fits by maximum likelihood (Ceres), with a parametric bootstrap.
//
//   psi(x) = guess + (1 - guess - lapse) * F(x; alpha, beta)
//   F: cumulative Gaussian  Phi((x - alpha) / beta)          alpha = PSE (F = 0.5), beta = sd
//      logistic             1 / (1 + exp(-(x - alpha) / beta)) alpha = PSE, beta = scale
//      Weibull              1 - exp(-(x / alpha)^beta), x > 0  alpha = scale (F = 0.632), beta = shape
//
// Conventions, next to the usual tools:
//   - guess ("gamma") is fixed (0 for yes/no, 0.5 for 2AFC) or fitted within [0, guess_max];
//     lapse ("lambda") is fitted within [0, lapse_max] (0.1 by default; psignifit 4 bounds it
//     at 0.5 by default with a Beta prior, quickpsy at [0, 0.1] when fitted) or fixed. No priors:
//     plain maximum likelihood, as quickpsy (psignifit 4 reports a Bayesian posterior instead).
//   - threshold: by default the PSE, where F = 0.5 (psignifit's default "threshold at 0.5 of
//     the unscaled sigmoid", quickpsy's default threshold at guess + (1-guess-lapse)/2). With
//     threshold_at = p it is the level where psi = p (quickpsy's `prob`).
//   - slope: dpsi/dx at the threshold, in proportion per level unit (psignifit's getSlope).
//   - JND: x(F = 0.75) - x(F = 0.5), half the interquartile range of F (the classical
//     definition for a yes/no PSE; for 2AFC data it is the 75 %-point distance on F).
//   - intervals: 95 % percentile intervals of a parametric bootstrap (quickpsy's `B`; Wichmann
//     and Hill 2001), seeded, count configurable; goodness of fit: deviance and its bootstrap
//     p (the fraction of simulated deviances at least as large; Wichmann and Hill 2001).
// With guess = lapse = 0 the cumulative Gaussian fit is a probit regression (R glm binomial
// probit; statsmodels Probit): alpha = -b0/b1, beta = 1/b1.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace palprig::stats {

enum class Sigmoid { cumulative_gaussian, logistic, weibull };
const char* to_string(Sigmoid s) noexcept;
std::optional<Sigmoid> sigmoid_from_string(const std::string& text) noexcept;

// Counts at one stimulus level.
struct LevelCounts {
  double level = 0;
  int n = 0;  // trials
  int k = 0;  // "yes" or correct answers
};

// Per-trial (level, 0/1) pairs grouped into counts per distinct level, in increasing level.
std::vector<LevelCounts> counts_per_level(const std::vector<double>& levels, const std::vector<int>& responses);

struct PsychometricOptions {
  Sigmoid sigmoid = Sigmoid::cumulative_gaussian;
  std::optional<double> guess = 0.0;  // nullopt: fitted within [0, guess_max]
  std::optional<double> lapse;        // nullopt: fitted within [0, lapse_max]
  double guess_max = 0.5, lapse_max = 0.1;
  std::optional<double> threshold_at;  // proportion on psi; default: F = 0.5
  int bootstrap = 1000;                // resamples (0: no intervals, no GOF p)
  std::uint64_t seed = 1;
  double confidence = 0.95;
};

struct Interval {
  double low = 0, high = 0;
};

struct PsychometricFit {
  Sigmoid sigmoid = Sigmoid::cumulative_gaussian;
  double alpha = 0, beta = 0, guess = 0, lapse = 0;
  bool guess_fitted = false, lapse_fitted = false;
  double threshold = 0, slope = 0, jnd = 0;
  double threshold_proportion = 0;  // psi at the threshold
  double log_likelihood = 0, deviance = 0;
  int deviance_df = 0;
  int trials = 0;
  std::vector<LevelCounts> levels;
  // Bootstrap (empty / NaN when bootstrap = 0).
  int bootstrap = 0, bootstrap_failed = 0;
  Interval alpha_ci, beta_ci, threshold_ci, slope_ci, jnd_ci;
  double gof_p = 0;
  double fit_seconds = 0, bootstrap_seconds = 0;
};

// psi at x under a fit's parameters.
double psychometric_value(Sigmoid s, double alpha, double beta, double guess, double lapse, double x) noexcept;

// Throws StatisticsError for data that cannot be fitted (fewer than 2 levels, a Weibull with
// levels <= 0, no trials, options out of range).
PsychometricFit fit_psychometric(const std::vector<LevelCounts>& data, const PsychometricOptions& options);

}  // namespace palprig::stats
