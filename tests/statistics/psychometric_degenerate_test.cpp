// Plausible data that took the psychometric fit out of its depth: 20 "yes" of 1,000 at one level
// (the optimiser ran the sigmoid into a step, and a Ceres CHECK aborted the process with five
// lines of its logging), and levels near the largest double (the fit printed "threshold inf").
// Each now gives a finite fit or a StatisticsError, in this process, with nothing on stderr.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "statistics/psychometric_fit.hpp"
#include "statistics/statistics_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::palprig_bin;
using palprig::test_support::run_process;
using palprig::test_support::TempDir;

namespace {

// A finite fit, or the StatisticsError's text (never an abort, never an inf).
std::string fit_or_refusal(const std::vector<stats::LevelCounts>& data, stats::PsychometricOptions o = {}) {
  o.bootstrap = 20;
  try {
    const auto fit = stats::fit_psychometric(data, o);
    EXPECT_TRUE(std::isfinite(fit.alpha) && std::isfinite(fit.beta)) << fit.alpha << " " << fit.beta;
    EXPECT_FALSE(std::isinf(fit.threshold)) << fit.threshold;
    return "fitted";
  } catch (const stats::StatisticsError& e) {
    return e.what();
  }
}

// " inf", "-inf" or "inf," as a printed number (not "information").
bool prints_inf(const std::string& text) {
  for (std::size_t at = text.find("inf"); at != std::string::npos; at = text.find("inf", at + 1)) {
    const bool before = at == 0 || !std::isalpha(static_cast<unsigned char>(text[at - 1]));
    const bool after = at + 3 >= text.size() || !std::isalpha(static_cast<unsigned char>(text[at + 3]));
    if (before && after) return true;
  }
  return false;
}

}  // namespace

TEST(PsychometricDegenerate, TwentyYesOfAThousandAtOneLevelDoesNotAbort) {
  for (auto sigmoid : {stats::Sigmoid::cumulative_gaussian, stats::Sigmoid::logistic, stats::Sigmoid::weibull}) {
    SCOPED_TRACE(stats::to_string(sigmoid));
    stats::PsychometricOptions o;
    o.sigmoid = sigmoid;
    // 20 of 1,000 at one level and none elsewhere; and every level but one all "no".
    for (const auto& data : std::vector<std::vector<stats::LevelCounts>>{
             {{1, 1000, 0}, {2, 1000, 20}},
             {{1, 1000, 20}, {2, 1000, 0}},
             {{1, 1000, 0}, {2, 1000, 0}, {3, 1000, 20}, {4, 1000, 0}},
             {{1, 1000, 20}, {2, 1000, 1000}},
             {{1, 1000, 0}, {2, 1000, 1000}},
         }) {
      for (bool fitted_lapse : {false, true}) {
        stats::PsychometricOptions one = o;
        if (!fitted_lapse) one.lapse = 0.0;
        const std::string r = fit_or_refusal(data, one);
        EXPECT_TRUE(r == "fitted" || r.find("the maximum-likelihood fit did not converge") != std::string::npos ||
                    r.find("a fit whose threshold") != std::string::npos)
            << r;
      }
    }
  }
}

TEST(PsychometricDegenerate, LevelsNearTheLargestDoubleAreFittedInScaleOrRefused) {
  // The same responses with levels in units 1e300 apart: the fit scales with them.
  const std::vector<stats::LevelCounts> small{{1, 40, 4}, {2, 40, 12}, {3, 40, 25}, {4, 40, 36}};
  std::vector<stats::LevelCounts> huge = small;
  for (auto& c : huge) c.level *= 1e300;
  stats::PsychometricOptions o;
  o.bootstrap = 0;
  const auto a = stats::fit_psychometric(small, o), b = stats::fit_psychometric(huge, o);
  EXPECT_NEAR(b.threshold / 1e300, a.threshold, 1e-6 * a.threshold);
  EXPECT_NEAR(b.beta / 1e300, a.beta, 1e-6 * a.beta);
  // A level of 1e308 beside 1: refused with a line that says why, not "threshold inf".
  const std::string r = fit_or_refusal({{1, 10, 2}, {1e308, 10, 8}});
  EXPECT_TRUE(r == "fitted" || r.find("a fit whose threshold, slope and scale are finite numbers") != std::string::npos)
      << r;
  const std::string w = fit_or_refusal({{1e307, 10, 1}, {1.7e308, 10, 9}});
  EXPECT_TRUE(w == "fitted" || w.find("finite numbers") != std::string::npos) << w;
}

TEST(PsychometricDegenerate, TheCommandLineSaysOneLineOfItsOwn) {
  TempDir dir;
  const auto rare = dir.write("rare.csv", "level,yes,n\n1,0,1000\n2,20,1000\n");
  const auto huge = dir.write("huge.csv", "level,yes,n\n1,2,10\n1e308,8,10\n");
  for (const auto& f : {rare, huge}) {
    SCOPED_TRACE(f.string());
    const auto r = run_process(palprig_bin() + " stats psychometric " + f.string() +
                               " --level level --response yes --n n --bootstrap 50");
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.exit_code << r.err;
    EXPECT_EQ(r.err.find("Check failed"), std::string::npos) << r.err;
    EXPECT_FALSE(prints_inf(r.out)) << r.out;
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    if (r.exit_code == 2) {
      EXPECT_EQ(r.err.rfind("palprig: " + f.string() + ": group 'all': ", 0), 0u) << r.err;
    }
  }
}
