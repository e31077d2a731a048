#include "statistics/psychometric_fit.hpp"
// Over 400 lines on purpose: the likelihood (templated on Ceres' Jets), its unbounded
// parameterisation, the minimiser and the bootstrap that refits through them are one numerical
// unit: they share the standardisation and the overflow bounds, and splitting them would put
// those templates in a header for no other reader.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

#include <boost/math/distributions/normal.hpp>
#include <ceres/autodiff_first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <glog/logging.h>

#include "statistics/statistics_error.hpp"

namespace palprig::stats {

const char* to_string(Sigmoid s) noexcept {
  switch (s) {
    case Sigmoid::cumulative_gaussian: return "cumulative-gaussian";
    case Sigmoid::logistic: return "logistic";
    case Sigmoid::weibull: return "weibull";
  }
  return "cumulative-gaussian";
}

std::optional<Sigmoid> sigmoid_from_string(const std::string& text) noexcept {
  if (text == "cumulative-gaussian" || text == "gaussian" || text == "probit") return Sigmoid::cumulative_gaussian;
  if (text == "logistic" || text == "logit") return Sigmoid::logistic;
  if (text == "weibull") return Sigmoid::weibull;
  return std::nullopt;
}

std::vector<LevelCounts> counts_per_level(const std::vector<double>& levels, const std::vector<int>& responses) {
  if (levels.size() != responses.size()) throw StatisticsError("levels and responses differ in length");
  // The trials in level order (stable: among equal levels, such as 0 and -0, in the order given,
  // so each group's level is its last trial's, as a map keyed on the level gave), then one count
  // per run of equal levels. A NaN orders with nothing: those go through the map, as before.
  if (std::any_of(levels.begin(), levels.end(), [](double x) { return std::isnan(x); })) {
    std::map<double, LevelCounts> by_level;
    for (std::size_t i = 0; i < levels.size(); ++i) {
      auto& c = by_level[levels[i]];
      c.level = levels[i];
      ++c.n;
      c.k += responses[i] != 0 ? 1 : 0;
    }
    std::vector<LevelCounts> out;
    out.reserve(by_level.size());
    for (auto& [level, c] : by_level) out.push_back(c);
    return out;
  }
  std::vector<std::size_t> order(levels.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return levels[a] < levels[b]; });
  std::vector<LevelCounts> out;
  for (const std::size_t i : order) {
    if (out.empty() || out.back().level < levels[i]) out.push_back(LevelCounts{});
    LevelCounts& c = out.back();
    c.level = levels[i];
    ++c.n;
    c.k += responses[i] != 0 ? 1 : 0;
  }
  return out;
}

namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
// How far the optimiser may go in its unbounded parameters (see Parameterisation): a location
// 10^6 standard deviations from the levels, or a log scale or logit beyond 700 (e^700 is near
// the largest double), is no fit but a step whose derivatives overflow.
constexpr double kLocationBound = 1e6, kLogBound = 700;
// One step between two levels may be at most this many times all the others together.
constexpr double kMaxLevelGapRatio = 1e9;

// (x - alpha) / beta for a plain level x. Doubles are divided as written. For Ceres' Jets the
// division is Ceres' own (the value times 1 / beta.a, the derivative likewise), with that
// inverse, the same for every level, computed once per evaluation by the caller.
inline double standardised(double x, double alpha, double beta, double /*beta_inverse*/) { return (x - alpha) / beta; }
template <class T, int N>
ceres::Jet<T, N> standardised(double x, const ceres::Jet<T, N>& alpha, const ceres::Jet<T, N>& beta, T beta_inverse) {
  const ceres::Jet<T, N> d = x - alpha;
  const T a = d.a * beta_inverse;
  return ceres::Jet<T, N>(a, (d.v - a * beta.v) * beta_inverse);
}

inline double scalar_part(double x) { return x; }
template <class T, int N>
T scalar_part(const ceres::Jet<T, N>& x) {
  return x.a;
}

// F and 1 - F computed separately, so neither tail loses its digits to a subtraction. Only the
// ones asked for are computed: the likelihood needs F where some answers were "yes" and 1 - F
// where some were "no", and with one trial per level (10,000 distinct levels) that is one of
// the two (the same operations on the same numbers as computing both: the fit does not change).
// beta_inverse: 1 / beta's value (see standardised).
template <class T>
void sigmoid_parts(Sigmoid s, double x, const T& alpha, const T& beta, double beta_inverse, bool want_f, bool want_fc,
                   T& f, T& fc) {
  using std::erfc;
  using std::exp;
  using std::expm1;
  using std::pow;
  switch (s) {
    case Sigmoid::cumulative_gaussian: {
      const T z = standardised(x, alpha, beta, beta_inverse);
      // Scalars as scalars: a Jet made of a constant carries a zero derivative that Ceres would
      // multiply and add in; the values are the same (1/sqrt(2) is applied as Ceres' Jet
      // division applies it, by its inverse; a double is divided as before).
      if (want_f) f = erfc(-z / kSqrt2) * 0.5;
      if (want_fc) fc = erfc(z / kSqrt2) * 0.5;
      return;
    }
    case Sigmoid::logistic: {
      const T u = standardised(x, alpha, beta, beta_inverse);
      if (want_f) f = T(1) / (T(1) + exp(-u));
      if (want_fc) fc = T(1) / (T(1) + exp(u));
      return;
    }
    case Sigmoid::weibull: {
      const T w = pow(T(x) / alpha, beta);
      if (want_f) f = -expm1(-w);
      if (want_fc) fc = exp(-w);
      return;
    }
  }
}

void sigmoid_pair(Sigmoid s, double x, double alpha, double beta, double& f, double& fc) {
  sigmoid_parts(s, x, alpha, beta, 1.0 / beta, true, true, f, fc);
}

// The optimiser works on unbounded parameters on standardised levels:
//   p0: alpha (location in sd units about the mean level; Weibull: log of scale / level scale)
//   p1: log beta (in the same units)     p2, p3: logits of guess / guess_max and lapse / lapse_max
struct Parameterisation {
  Sigmoid sigmoid;
  // x_standard = (x / unit - centre) / scale (Weibull: centre 0). unit is the largest |level|,
  // so no sum, square or difference of levels can overflow, whatever their magnitude.
  double unit = 1, centre = 0, scale = 1;
  std::optional<double> guess, lapse;
  double guess_max = 0.5, lapse_max = 0.1;

  template <class T>
  void decode(const T* p, T& alpha, T& beta, T& g, T& l) const {
    using std::exp;
    alpha = sigmoid == Sigmoid::weibull ? exp(p[0]) : p[0];
    beta = exp(p[1]);
    g = guess ? T(*guess) : T(guess_max) / (T(1) + exp(-p[2]));
    l = lapse ? T(*lapse) : T(lapse_max) / (T(1) + exp(-p[3]));
  }
  // Back to the data's units.
  void natural(const double* p, double& alpha, double& beta, double& g, double& l) const {
    decode(p, alpha, beta, g, l);
    if (sigmoid == Sigmoid::weibull) {
      alpha *= scale * unit;
    } else {
      alpha = (centre + scale * alpha) * unit;
      beta *= scale * unit;
    }
  }
  double standard(double level) const {
    return sigmoid == Sigmoid::weibull ? level / unit / scale : (level / unit - centre) / scale;
  }
};

// The value and, for Ceres' Jets, every derivative (ceres::isfinite looks at the value only; a
// NaN gradient beside a finite value is what tripped Ceres' line-search CHECK).
inline bool all_finite(double x) { return std::isfinite(x); }
template <class T, int N>
bool all_finite(const ceres::Jet<T, N>& x) {
  return std::isfinite(x.a) && x.v.allFinite();
}

// One level as the likelihood reads it: the standardised level (Parameterisation::standard,
// computed once per fit rather than at every evaluation) and its counts.
struct StandardLevel {
  double x = 0;
  int yes = 0, no = 0;
};

std::vector<StandardLevel> standard_levels(const std::vector<LevelCounts>& data, const Parameterisation& param) {
  std::vector<StandardLevel> out;
  out.reserve(data.size());
  for (const LevelCounts& c : data) out.push_back({param.standard(c.level), c.k, c.n - c.k});
  return out;
}

struct NegativeLogLikelihood {
  const std::vector<StandardLevel>* data;
  const Parameterisation* param;

  template <class T>
  bool operator()(const T* p, T* cost) const {
    using std::log;
    // Far out in the unbounded parameters the sigmoid is a step and its derivatives overflow;
    // such a point is reported as outside the problem (false), so the line search steps back
    // instead of handing Ceres a non-finite value (which its checks turn into an abort).
    for (int i = 0; i < 4; ++i) {
      const double bound = i == 0 && param->sigmoid != Sigmoid::weibull ? kLocationBound : kLogBound;
      if (!(ceres::abs(p[i]) < T(bound))) return false;
    }
    T alpha, beta, g, l;
    param->decode(p, alpha, beta, g, l);
    const T span = T(1) - g - l;
    const double beta_inverse = 1.0 / scalar_part(beta);
    T sum(0);
    for (const StandardLevel& c : *data) {
      T f, fc;
      sigmoid_parts(param->sigmoid, c.x, alpha, beta, beta_inverse, c.yes > 0, c.no > 0, f, fc);
      // A probability of exactly 0 against an observed answer would be an infinite cost.
      if (c.yes > 0) {
        T psi = g + span * f;
        if (psi < T(1e-300)) psi = T(1e-300);
        sum -= log(psi) * static_cast<double>(c.yes);
      }
      if (c.no > 0) {
        T q = l + span * fc;
        if (q < T(1e-300)) q = T(1e-300);
        sum -= log(q) * static_cast<double>(c.no);
      }
    }
    cost[0] = sum;
    return all_finite(sum);
  }
};

double xlogy_ratio(double k, double expected) { return k > 0 ? k * std::log(k / expected) : 0.0; }

struct Fitted {
  double p[4]{};
  double nll = std::numeric_limits<double>::infinity();
  bool ok = false;
};

Fitted minimise(const std::vector<LevelCounts>& data, const Parameterisation& param, const double start[4]) {
  // Ceres reports through glog, which without InitGoogleLogging writes its warnings to stderr
  // beside palprig's own line. Only errors (there are none to expect) get through.
  static const bool quiet = [] {
    if (FLAGS_minloglevel < google::GLOG_ERROR) FLAGS_minloglevel = google::GLOG_ERROR;
    return true;
  }();
  (void)quiet;
  const std::vector<StandardLevel> levels = standard_levels(data, param);
  auto* function =
      new ceres::AutoDiffFirstOrderFunction<NegativeLogLikelihood, 4>(new NegativeLogLikelihood{&levels, &param});
  ceres::GradientProblem problem(function);
  ceres::GradientProblemSolver::Options options;
  options.logging_type = ceres::SILENT;
  options.max_num_iterations = 500;
  options.function_tolerance = 1e-13;
  options.gradient_tolerance = 1e-11;
  options.parameter_tolerance = 1e-12;
  ceres::GradientProblemSolver::Summary summary;
  Fitted f;
  std::copy(start, start + 4, f.p);
  ceres::Solve(options, problem, f.p, &summary);
  f.nll = summary.final_cost;
  f.ok = summary.IsSolutionUsable() && std::isfinite(f.nll);
  return f;
}

double inverse_f(Sigmoid s, double alpha, double beta, double f) {
  if (!(f > 0 && f < 1)) return std::numeric_limits<double>::quiet_NaN();
  switch (s) {
    case Sigmoid::cumulative_gaussian:
      return alpha + beta * boost::math::quantile(boost::math::normal_distribution<>(), f);
    case Sigmoid::logistic: return alpha + beta * std::log(f / (1 - f));
    case Sigmoid::weibull: return alpha * std::pow(-std::log1p(-f), 1.0 / beta);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double density_f(Sigmoid s, double alpha, double beta, double x) {
  switch (s) {
    case Sigmoid::cumulative_gaussian: {
      const double z = (x - alpha) / beta;
      return std::exp(-0.5 * z * z) / (std::sqrt(2 * M_PI) * beta);
    }
    case Sigmoid::logistic: {
      const double f = 1 / (1 + std::exp(-(x - alpha) / beta));
      return f * (1 - f) / beta;
    }
    case Sigmoid::weibull: {
      if (x <= 0) return 0;
      const double r = x / alpha;
      return beta / alpha * std::pow(r, beta - 1) * std::exp(-std::pow(r, beta));
    }
  }
  return 0;
}

// The fitted quantities of one parameter set (fills everything but the bootstrap).
void describe(const Parameterisation& param, const double p[4], const std::vector<LevelCounts>& data,
              const PsychometricOptions& o, PsychometricFit& fit) {
  param.natural(p, fit.alpha, fit.beta, fit.guess, fit.lapse);
  const double span = 1 - fit.guess - fit.lapse;
  const double f_threshold = o.threshold_at ? (*o.threshold_at - fit.guess) / span : 0.5;
  fit.threshold = inverse_f(fit.sigmoid, fit.alpha, fit.beta, f_threshold);
  fit.threshold_proportion = fit.guess + span * f_threshold;
  fit.slope = span * density_f(fit.sigmoid, fit.alpha, fit.beta, fit.threshold);
  fit.jnd = inverse_f(fit.sigmoid, fit.alpha, fit.beta, 0.75) - inverse_f(fit.sigmoid, fit.alpha, fit.beta, 0.5);
  double ll = 0, deviance = 0;
  for (const LevelCounts& c : data) {
    const double psi = std::clamp(psychometric_value(fit.sigmoid, fit.alpha, fit.beta, fit.guess, fit.lapse, c.level),
                                  1e-300, 1 - 1e-16);
    ll += c.k * std::log(psi) + (c.n - c.k) * std::log1p(-psi);
    deviance += 2 * (xlogy_ratio(c.k, c.n * psi) + xlogy_ratio(c.n - c.k, c.n * (1 - psi)));
  }
  fit.log_likelihood = ll;
  fit.deviance = deviance;
}

// SplitMix64: a small seeded generator whose stream is the same on every machine.
struct SplitMix {
  std::uint64_t state;
  double uniform() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

double quantile7(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double h = (static_cast<double>(v.size()) - 1) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

Interval percentile_interval(const std::vector<double>& v, double confidence) {
  if (v.empty()) return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {quantile7(v, (1 - confidence) / 2), quantile7(v, 1 - (1 - confidence) / 2)};
}

}  // namespace

double psychometric_value(Sigmoid s, double alpha, double beta, double guess, double lapse, double x) noexcept {
  double f = 0, fc = 0;
  if (s == Sigmoid::weibull && x <= 0) return guess;
  sigmoid_pair(s, x, alpha, beta, f, fc);
  return guess + (1 - guess - lapse) * f;
}

PsychometricFit fit_psychometric(const std::vector<LevelCounts>& data, const PsychometricOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  if (o.guess && !(*o.guess >= 0 && *o.guess < 1)) throw StatisticsError("guess rate in [0, 1)");
  if (o.lapse && !(*o.lapse >= 0 && *o.lapse < 1)) throw StatisticsError("lapse rate in [0, 1)");
  if (o.guess && o.lapse && !(*o.guess + *o.lapse < 1)) throw StatisticsError("guess + lapse below 1");
  if (!(o.guess_max > 0 && o.guess_max < 1) || !(o.lapse_max > 0 && o.lapse_max < 1)) {
    throw StatisticsError("guess_max and lapse_max in (0, 1)");
  }
  if (o.bootstrap < 0) throw StatisticsError("bootstrap count >= 0");
  if (!(o.confidence > 0 && o.confidence < 1)) throw StatisticsError("confidence in (0, 1)");
  // Levels are summed and squared in a power-of-two unit near the largest of them: exact (the
  // same bits as in the levels' own unit), and no sum or square overflows, even at 1e308.
  double largest = 0;
  for (const LevelCounts& c : data) {
    if (c.n > 0 && std::isfinite(c.level)) largest = std::max(largest, std::fabs(c.level));
  }
  const double unit = largest > 0 ? std::ldexp(1.0, std::ilogb(largest)) : 1.0;
  int trials = 0;
  double sum = 0, sum_sq = 0, sum_log = 0;
  for (const LevelCounts& c : data) {
    if (c.n < 0 || c.k < 0 || c.k > c.n || !std::isfinite(c.level)) {
      throw StatisticsError("counts with 0 <= k <= n and finite levels (level " + std::to_string(c.level) + ")");
    }
    if (o.sigmoid == Sigmoid::weibull && c.level <= 0 && c.n > 0) {
      throw StatisticsError("levels > 0 for a Weibull (got " + std::to_string(c.level) + ")");
    }
    if (c.n > std::numeric_limits<int>::max() - trials) throw StatisticsError("at most 2^31 - 1 trials in all");
    trials += c.n;
    const double x = c.level / unit;
    sum += x * c.n;
    sum_sq += x * x * c.n;
    if (c.level > 0) sum_log += std::log(c.level) * c.n;
  }
  std::vector<LevelCounts> used;
  for (const LevelCounts& c : data) {
    if (c.n > 0) used.push_back(c);
  }
  if (used.size() < 2) throw StatisticsError("trials at 2 or more different levels");
  // Levels a double can hold but a fit cannot resolve: one level far beyond the others (a level
  // of 1e308 beside steps of 1 fitted to a threshold of -2.2e306 before). The fit reads location
  // and slope on the scale of the steps between levels; a single step more than 1e9 times all
  // the others together leaves it nothing to read them on. (Levels that differ only by rounding,
  // as a QUEST track's may, are steps like any other and pass.)
  {
    std::vector<double> levels;
    levels.reserve(used.size());
    for (const LevelCounts& c : used) levels.push_back(c.level);
    std::sort(levels.begin(), levels.end());
    double widest = 0, others = 0;
    std::size_t at = 0;
    for (std::size_t i = 1; i < levels.size(); ++i) {
      if (levels[i] - levels[i - 1] > widest) {
        widest = levels[i] - levels[i - 1];
        at = i;
      }
    }
    // Summed apart from the widest (which would absorb them in a running sum).
    for (std::size_t i = 1; i < levels.size(); ++i)
      if (i != at) others += levels[i] - levels[i - 1];
    if (levels.size() > 2 && others > 0 && widest > kMaxLevelGapRatio * others) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "levels within 1e9 times the other steps of each other: the step from %.3g to %.3g is beyond "
                    "what the fit can resolve beside the others' %.3g",
                    levels[at - 1], levels[at], others);
      throw StatisticsError(text);
    }
  }

  Parameterisation param;
  param.sigmoid = o.sigmoid;
  param.guess = o.guess;
  param.lapse = o.lapse;
  param.guess_max = o.guess_max;
  param.lapse_max = o.lapse_max;
  param.unit = unit;
  const double mean = sum / trials;
  const double sd = std::sqrt(std::max(sum_sq / trials - mean * mean, 0.0));
  if (o.sigmoid == Sigmoid::weibull) {
    param.centre = 0;
    param.scale = std::exp(sum_log / trials) / unit;
  } else {
    param.centre = mean;
    param.scale = sd > 0 ? sd : 1.0;
  }

  const int free_params = 2 + (o.guess ? 0 : 1) + (o.lapse ? 0 : 1);
  const double g_start = o.guess ? 0.0 : std::log(0.25 / 0.75);  // guess = guess_max / 4
  const double l_start = o.lapse ? 0.0 : std::log(0.02 / (o.lapse_max - 0.02 > 0 ? o.lapse_max - 0.02 : o.lapse_max));
  Fitted best;
  for (double a : {-0.7, 0.0, 0.7}) {
    for (double b : {std::log(0.3), std::log(1.0)}) {
      const double start[4] = {o.sigmoid == Sigmoid::weibull ? a * 0.5 : a, o.sigmoid == Sigmoid::weibull ? b + 1.0 : b,
                               g_start, l_start};
      const Fitted f = minimise(used, param, start);
      if (f.ok && f.nll < best.nll) best = f;
    }
  }
  if (!best.ok) throw StatisticsError("the maximum-likelihood fit did not converge");

  PsychometricFit fit;
  fit.sigmoid = o.sigmoid;
  fit.guess_fitted = !o.guess;
  fit.lapse_fitted = !o.lapse;
  fit.trials = trials;
  fit.levels = used;
  fit.deviance_df = static_cast<int>(used.size()) - free_params;
  describe(param, best.p, used, o, fit);
  // A fit in range of the optimiser can still land beyond the largest double in the levels'
  // unit (levels near 1e308): refused rather than printed as "threshold inf".
  if (!std::isfinite(fit.alpha) || !std::isfinite(fit.beta) || std::isinf(fit.threshold) || std::isinf(fit.slope) ||
      std::isinf(fit.jnd)) {
    std::ostringstream got;
    got << "threshold " << fit.threshold << ", scale " << fit.beta << " with levels up to " << largest;
    throw StatisticsError("a fit whose threshold, slope and scale are finite numbers (got " + got.str() +
                          "; give the levels in a smaller unit)");
  }
  fit.fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  const double nan = std::numeric_limits<double>::quiet_NaN();
  fit.alpha_ci = fit.beta_ci = fit.threshold_ci = fit.slope_ci = fit.jnd_ci = {nan, nan};
  fit.gof_p = nan;
  if (o.bootstrap == 0) return fit;

  const auto boot_started = std::chrono::steady_clock::now();
  std::vector<double> predicted;
  predicted.reserve(used.size());
  for (const LevelCounts& c : used)
    predicted.push_back(psychometric_value(fit.sigmoid, fit.alpha, fit.beta, fit.guess, fit.lapse, c.level));
  SplitMix random{o.seed};
  std::vector<double> alphas, betas, thresholds, slopes, jnds;
  int deviance_at_least = 0, good = 0;
  std::vector<LevelCounts> resample = used;
  for (int b = 0; b < o.bootstrap; ++b) {
    for (std::size_t i = 0; i < used.size(); ++i) {
      int k = 0;
      for (int t = 0; t < used[i].n; ++t) k += random.uniform() < predicted[i] ? 1 : 0;
      resample[i].k = k;
    }
    Fitted f = minimise(resample, param, best.p);
    if (!f.ok) {
      ++fit.bootstrap_failed;
      continue;
    }
    PsychometricFit one;
    one.sigmoid = fit.sigmoid;
    describe(param, f.p, resample, o, one);
    if (!std::isfinite(one.threshold) || !std::isfinite(one.jnd)) {
      ++fit.bootstrap_failed;
      continue;
    }
    ++good;
    alphas.push_back(one.alpha);
    betas.push_back(one.beta);
    thresholds.push_back(one.threshold);
    slopes.push_back(one.slope);
    jnds.push_back(one.jnd);
    if (one.deviance >= fit.deviance) ++deviance_at_least;
  }
  fit.bootstrap = good;
  fit.alpha_ci = percentile_interval(alphas, o.confidence);
  fit.beta_ci = percentile_interval(betas, o.confidence);
  fit.threshold_ci = percentile_interval(thresholds, o.confidence);
  fit.slope_ci = percentile_interval(slopes, o.confidence);
  fit.jnd_ci = percentile_interval(jnds, o.confidence);
  fit.gof_p = good > 0 ? static_cast<double>(deviance_at_least) / good : nan;
  fit.bootstrap_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - boot_started).count();
  return fit;
}

}  // namespace palprig::stats
