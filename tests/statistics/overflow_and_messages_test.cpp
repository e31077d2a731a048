// Statistics on values near the largest double, and the refusals of `palprig stats`: computed
// in the units' power-of-two scale (t, p and r do not depend on units) or refused with one
// line naming the right thing (the option, the column, the file), exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "statistics/statistics_correlation.hpp"
#include "statistics/statistics_describe.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_ttest.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::count_lines;
using testing::run_palprig;
using testing::ScratchDir;

std::vector<double> times(const std::vector<double>& v, double k) {
  std::vector<double> out;
  out.reserve(v.size());
  for (double x : v) out.push_back(x * k);
  return out;
}

const std::vector<double> kOverflowX{5.1, 4.9, 6.2, 5.8, 6.0, 5.5, 5.3};
const std::vector<double> kOverflowY{4.2, 4.8, 4.5, 5.0, 4.1, 4.6};

TEST(StatisticsOverflow, WelchOnHugeValuesEqualsWelchInOtherUnits) {
  const auto small = stats::two_sample_t_test(kOverflowX, kOverflowY, false);
  const auto huge = stats::two_sample_t_test(times(kOverflowX, 1e200), times(kOverflowY, 1e200), false);
  EXPECT_NEAR(huge.t, small.t, 1e-9 * std::fabs(small.t));
  EXPECT_NEAR(huge.df, small.df, 1e-9 * small.df);
  EXPECT_NEAR(huge.p, small.p, 1e-9 * small.p);
  EXPECT_NEAR(huge.estimate / 1e200, small.estimate, 1e-9);
  EXPECT_NEAR(huge.ci_lower / 1e200, small.ci_lower, 1e-9);
}

TEST(StatisticsOverflow, StudentPairedAndOneSampleOnHugeValues) {
  const auto s = stats::two_sample_t_test(times(kOverflowX, 1e300), times(kOverflowY, 1e300), true);
  EXPECT_NEAR(s.t, stats::two_sample_t_test(kOverflowX, kOverflowY, true).t, 1e-9);
  const std::vector<double> a{1, 2, 4, 3, 5}, b{0.5, 2.5, 3, 2, 4};
  const auto paired = stats::paired_t_test(times(a, 1e307), times(b, -1e307));
  std::vector<double> sum(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) sum[i] = a[i] + b[i];
  EXPECT_NEAR(paired.t, stats::one_sample_t_test(sum, 0).t, 1e-9);
  const auto one = stats::one_sample_t_test(times(a, 1e305), 2e305);
  EXPECT_NEAR(one.t, stats::one_sample_t_test(a, 2).t, 1e-9);
}

TEST(StatisticsOverflow, DifferenceBeyondTheLargestDoubleIsRefusedNotConstant) {
  const std::vector<double> x{1e308, 1.5e308, 1.7e308}, y{-1e308, -1.5e308, -1.7e308};
  try {
    stats::two_sample_t_test(x, y, false);
    FAIL() << "a difference of 2.7e308 was reported";
  } catch (const stats::StatisticsError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find("constant"), std::string::npos) << what;
    EXPECT_NE(what.find("too large"), std::string::npos) << what;
  }
}

TEST(StatisticsOverflow, PearsonOnExtremeValuesIsTheSameR) {
  const std::vector<double> x{1, 2, 3, 4, 5}, y{2, 1, 4, 3, 6};
  const auto plain = stats::pearson(x, y);
  const auto extreme = stats::pearson(times(x, 1e308 / 5), times(y, -1e308 / 6));
  EXPECT_NEAR(extreme.r, -plain.r, 1e-12);
  EXPECT_NEAR(extreme.p, plain.p, 1e-9);
  EXPECT_LT(extreme.p, 1.0);
}

TEST(StatisticsOverflow, DescribeKeepsAFiniteSdOfHugeValues) {
  const auto d = stats::describe(times(kOverflowX, 1e300), stats::QuantileRule::r_type7);
  const auto plain = stats::describe(kOverflowX, stats::QuantileRule::r_type7);
  EXPECT_TRUE(std::isfinite(d.sd));
  EXPECT_NEAR(d.sd / 1e300, plain.sd, 1e-12);
  EXPECT_THROW(stats::describe(std::vector<double>{-1.7e308, 1.7e308, 1.7e308, -1.7e308}, stats::QuantileRule::r_type7),
               stats::StatisticsError);
}

void expect_one_line_refusal(const testing::CommandResult& r, const std::string& names,
                             const std::string& not_named = "") {
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
  if (!not_named.empty()) {
    EXPECT_EQ(r.err.find(not_named), std::string::npos) << r.err;
  }
  EXPECT_LT(r.err.size(), 400u) << r.err;
}

TEST(StatsCli, HugeWelchIsComputedAndOverflowingDifferenceNamesTheColumn) {
  ScratchDir dir;
  const auto csv = dir / "big.csv";
  std::ofstream(csv) << "g,v\na,1e200\na,3e200\na,2.5e200\nb,-1e200\nb,0.5e200\nb,0\n";
  auto r = run_palprig({"stats", "ttest", csv.string(), "--column", "v", "--by", "g", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["t"].is_number() && std::isfinite(j["t"].get<double>()));
  EXPECT_GT(j["df"].get<double>(), 1.0);

  std::ofstream(csv) << "g,v\na,1e308\na,1.7e308\na,1.2e308\nb,-1e308\nb,-1.7e308\nb,-1.1e308\n";
  r = run_palprig({"stats", "ttest", csv.string(), "--column", "v", "--by", "g"});
  expect_one_line_refusal(r, "column 'v'", "constant");
  r = run_palprig({"stats", "pearson", csv.string(), "--x", "v", "--y", "v", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["r"].get<double>(), 1.0, 1e-12);
}

TEST(StatsCli, ConfidenceIsBlamedOnTheOption) {
  expect_one_line_refusal(run_palprig({"stats", "proportion", "--k", "3", "--n", "10", "--confidence", "2"}),
                          "--confidence", "--k/--n");
  expect_one_line_refusal(run_palprig({"stats", "proportion", "--k", "3", "--n", "10", "--confidence", "nan"}),
                          "--confidence", "--k/--n");
  ScratchDir dir;
  const auto csv = dir / "d.csv";
  std::ofstream(csv) << "g,v\na,1\na,2\na,3\nb,2\nb,3\nb,5\n";
  expect_one_line_refusal(
      run_palprig({"stats", "ttest", csv.string(), "--column", "v", "--by", "g", "--confidence", "nan"}),
      "--confidence", "column 'v'");
  expect_one_line_refusal(run_palprig({"stats", "pearson", csv.string(), "--x", "v", "--y", "v", "--confidence", "1"}),
                          "--confidence");
}

TEST(StatsCli, DescribeByOnAnEmptyTableIsRefused) {
  ScratchDir dir;
  const auto csv = dir / "empty.csv";
  std::ofstream(csv) << "g,v\n";
  expect_one_line_refusal(run_palprig({"stats", "describe", csv.string(), "--column", "v", "--by", "g"}), csv.string());
}

}  // namespace
}  // namespace palprig
