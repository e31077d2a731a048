// Psychometric fits: the cumulative Gaussian with guess = lapse = 0 against an independent
// probit GLM (statsmodels, tests/statistics/psychometric_oracle.py, run by the test), recovery
// of known parameters from simulated data, bootstrap intervals and GOF, and the CLI.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "study/random_source.hpp"
#include "statistics/psychometric_fit.hpp"
#include "statistics/statistics_error.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using stats::LevelCounts;
using stats::PsychometricOptions;
using stats::Sigmoid;
using testing::ScratchDir;

std::vector<LevelCounts> simulate(Sigmoid s, double alpha, double beta, double guess, double lapse,
                                  const std::vector<double>& levels, int n, std::uint64_t seed) {
  RandomSource random(seed);
  std::vector<LevelCounts> out;
  for (double x : levels) {
    const double p = stats::psychometric_value(s, alpha, beta, guess, lapse, x);
    LevelCounts c{x, n, 0};
    for (int i = 0; i < n; ++i) c.k += random.uniform() < p ? 1 : 0;
    out.push_back(c);
  }
  return out;
}

nlohmann::json run_oracle(const std::vector<LevelCounts>& data, const ScratchDir& dir) {
  const auto csv = dir / "oracle.csv";
  std::ofstream out(csv);
  out.precision(17);
  out << "level,n,k\n";
  for (const auto& c : data) out << c.level << "," << c.n << "," << c.k << "\n";
  out.close();
  const auto r = test_support::run_process(
      "/usr/bin/python3 " + (testing::source_dir() / "tests" / "statistics" / "psychometric_oracle.py").string() + " " +
      csv.string());
  EXPECT_EQ(r.exit_code, 0) << r.err << " (needs Debian's python3-statsmodels, tools/debian-packages-test.txt)";
  return nlohmann::json::parse(r.out);
}

TEST(experiments_psychometric_fit, cumulative_gaussian_without_guess_and_lapse_is_the_probit_glm) {
  ScratchDir dir;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto data =
        simulate(Sigmoid::cumulative_gaussian, 2.5, 1.2, 0, 0, {0.5, 1.0, 1.5, 2, 2.5, 3, 3.5, 4.5}, 15, seed);
    PsychometricOptions o;
    o.guess = 0.0;
    o.lapse = 0.0;
    o.bootstrap = 0;
    const auto fit = stats::fit_psychometric(data, o);
    const auto oracle = run_oracle(data, dir);
    EXPECT_NEAR(fit.alpha, oracle["alpha"].get<double>(), 1e-6 * std::abs(oracle["alpha"].get<double>())) << seed;
    EXPECT_NEAR(fit.beta, oracle["beta"].get<double>(), 1e-6 * oracle["beta"].get<double>()) << seed;
    EXPECT_NEAR(fit.deviance, oracle["deviance"].get<double>(), 1e-6 * (1 + oracle["deviance"].get<double>())) << seed;
    EXPECT_NEAR(fit.log_likelihood, oracle["log_likelihood"].get<double>(), 1e-6) << seed;
    EXPECT_EQ(fit.deviance_df, 6);
    // JND of a cumulative Gaussian: sd * Phi^-1(0.75).
    EXPECT_NEAR(fit.jnd, fit.beta * 0.6744897501960817, 1e-9);
    EXPECT_DOUBLE_EQ(fit.threshold, fit.alpha);
  }
}

TEST(experiments_psychometric_fit, recovers_logistic_and_weibull_with_guess_and_fitted_lapse) {
  const std::vector<double> levels{0.25, 0.5, 0.75, 1, 1.25, 1.5, 2, 2.5, 3, 4};
  {
    const auto data = simulate(Sigmoid::logistic, 1.5, 0.4, 0.0, 0.03, levels, 400, 7);
    PsychometricOptions o;
    o.sigmoid = Sigmoid::logistic;
    o.bootstrap = 0;
    const auto fit = stats::fit_psychometric(data, o);
    EXPECT_NEAR(fit.alpha, 1.5, 0.08);
    EXPECT_NEAR(fit.beta, 0.4, 0.06);
    EXPECT_NEAR(fit.lapse, 0.03, 0.02);
    EXPECT_TRUE(fit.lapse_fitted);
  }
  {
    const auto data = simulate(Sigmoid::weibull, 1.5, 2.5, 0.5, 0.0, levels, 400, 8);
    PsychometricOptions o;
    o.sigmoid = Sigmoid::weibull;
    o.guess = 0.5;
    o.bootstrap = 0;
    o.threshold_at = 0.75;
    const auto fit = stats::fit_psychometric(data, o);
    EXPECT_NEAR(fit.alpha, 1.5, 0.1);
    EXPECT_NEAR(fit.beta, 2.5, 0.4);
    EXPECT_NEAR(fit.threshold_proportion, 0.75, 1e-12);
    EXPECT_NEAR(stats::psychometric_value(Sigmoid::weibull, fit.alpha, fit.beta, fit.guess, fit.lapse, fit.threshold),
                0.75, 1e-9);
  }
}

TEST(experiments_psychometric_fit, bootstrap_intervals_cover_the_truth_are_seeded_and_gof_flags_misfit) {
  const auto data = simulate(Sigmoid::cumulative_gaussian, 2.0, 0.8, 0, 0, {0.5, 1, 1.5, 2, 2.5, 3, 3.5}, 40, 11);
  PsychometricOptions o;
  o.lapse = 0.0;
  o.bootstrap = 400;
  o.seed = 5;
  const auto a = stats::fit_psychometric(data, o);
  EXPECT_EQ(a.bootstrap + a.bootstrap_failed, 400);
  EXPECT_LT(a.threshold_ci.low, 2.0);
  EXPECT_GT(a.threshold_ci.high, 2.0);
  EXPECT_LT(a.threshold_ci.low, a.threshold);
  EXPECT_GT(a.threshold_ci.high, a.threshold);
  EXPECT_GT(a.gof_p, 0.01);
  const auto same = stats::fit_psychometric(data, o);
  EXPECT_DOUBLE_EQ(same.threshold_ci.low, a.threshold_ci.low);
  EXPECT_DOUBLE_EQ(same.gof_p, a.gof_p);
  o.seed = 6;
  EXPECT_NE(stats::fit_psychometric(data, o).threshold_ci.low, a.threshold_ci.low);

  // Data no sigmoid describes (non-monotonic): the deviance is far in the bootstrap's tail.
  std::vector<LevelCounts> bad{{1, 40, 2}, {2, 40, 38}, {3, 40, 3}, {4, 40, 37}, {5, 40, 4}, {6, 40, 39}};
  o.seed = 5;
  const auto misfit = stats::fit_psychometric(bad, o);
  EXPECT_LT(misfit.gof_p, 0.01);
}

TEST(experiments_psychometric_fit, refuses_data_it_cannot_fit) {
  PsychometricOptions o;
  EXPECT_THROW(stats::fit_psychometric({{1, 10, 5}}, o), stats::StatisticsError);
  o.sigmoid = Sigmoid::weibull;
  EXPECT_THROW(stats::fit_psychometric({{0, 10, 5}, {1, 10, 7}}, o), stats::StatisticsError);
  EXPECT_THROW(stats::fit_psychometric({{1, 10, 11}, {2, 10, 7}}, PsychometricOptions{}), stats::StatisticsError);
}

TEST(experiments_psychometric_cli, per_trial_and_per_level_csv_give_the_same_fit_and_bad_rows_are_named) {
  ScratchDir dir;
  const auto data = simulate(Sigmoid::cumulative_gaussian, 2.0, 0.7, 0, 0, {1, 1.5, 2, 2.5, 3}, 20, 3);
  {
    std::ofstream trials(dir / "trials.csv"), levels(dir / "levels.csv");
    trials << "stimulus,yes,who\n";
    levels << "stimulus,yes,n\n";
    for (const auto& c : data) {
      for (int i = 0; i < c.n; ++i) trials << c.level << "," << (i < c.k ? 1 : 0) << ",p1\n";
      levels << c.level << "," << c.k << "," << c.n << "\n";
    }
  }
  const auto a = testing::run_palprig({"stats", "psychometric", (dir / "trials.csv").string(), "--level", "stimulus",
                                       "--response", "yes", "--lapse", "0", "--bootstrap", "200", "--json"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto b =
      testing::run_palprig({"stats", "psychometric", (dir / "levels.csv").string(), "--level", "stimulus", "--response",
                            "yes", "--n", "n", "--lapse", "0", "--bootstrap", "200", "--json"});
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out)["groups"][0], jb = nlohmann::json::parse(b.out)["groups"][0];
  EXPECT_DOUBLE_EQ(ja["threshold"].get<double>(), jb["threshold"].get<double>());
  EXPECT_DOUBLE_EQ(ja["threshold_ci"]["low"].get<double>(), jb["threshold_ci"]["low"].get<double>());
  EXPECT_EQ(ja["trials"].get<int>(), 100);
  EXPECT_NEAR(ja["threshold"].get<double>(), 2.0, 0.3);

  {
    std::ofstream bad(dir / "bad.csv");
    bad << "stimulus,yes\n1,0\n2,1\n3,yes\n";
  }
  const auto c = testing::run_palprig(
      {"stats", "psychometric", (dir / "bad.csv").string(), "--level", "stimulus", "--response", "yes"});
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find("line 4"), std::string::npos) << c.err;
  const auto d = testing::run_palprig(
      {"stats", "psychometric", (dir / "levels.csv").string(), "--level", "stimulus", "--response", "yes"});
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("0 or 1"), std::string::npos) << d.err;
}

}  // namespace
}  // namespace palprig
