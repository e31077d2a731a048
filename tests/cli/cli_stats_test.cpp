// `palprig stats ...` end to end: numbers, --json, and one-line refusals with exit code 2.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

TEST(experiments_cli_stats, compare_proportions_reproduces_paper_002) {
  const auto r = run_palprig(
      {"stats", "compare-proportions", "--k1", "488", "--n1", "504", "--k2", "470", "--n2", "504", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["combined_interval"].get<double>(), 0.027, 0.0005);
  EXPECT_TRUE(j["significant"].get<bool>());
  EXPECT_NE(j["convention"].get<std::string>().find("eq. 10"), std::string::npos);
}

TEST(experiments_cli_stats, csv_tests_match_the_library_oracles) {
  ScratchDir dir;
  write(dir / "d.csv",
        "group,time,before,after\n"
        "x,5.1,12.1,11.4\nx,4.9,14.3,13.9\nx,6.2,11.8,11.9\nx,5.8,13.5,12.6\nx,6.0,12.9,12.1\nx,5.5,15.0,14.2\nx,5.3,"
        "13.2,12.8\n"
        "y,4.2,12.4,12.0\ny,4.8,1,1\ny,4.5,1,1\ny,5.0,1,1\ny,4.1,1,1\ny,4.6,1,1\n");
  auto r = run_palprig(
      {"stats", "ttest", (dir / "d.csv").string(), "--column", "time", "--by", "group", "--student", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["t"].get<double>(), 4.2872645411485274, 1e-9);
  EXPECT_NEAR(j["p"].get<double>(), 0.0012830163137908882, 1e-12);
  r = run_palprig({"stats", "ttest", (dir / "d.csv").string(), "--column", "time", "--by", "group", "--json"});
  j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["df"].get<double>(), 10.734521849964823, 1e-9);  // Welch by default

  r = run_palprig({"stats", "mannwhitney", (dir / "d.csv").string(), "--column", "time", "--by", "group", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["n1"].get<int>(), 7);
  EXPECT_EQ(j["p_method"].get<std::string>(), "exact");
  EXPECT_DOUBLE_EQ(j["U1"].get<double>(), 41.0);  // 42 pairs: every x beats every y except 4.9 < 5.0

  r = run_palprig({"stats", "describe", (dir / "d.csv").string(), "--column", "time", "--by", "group", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["groups"].size(), 2u);
  EXPECT_EQ(j["groups"][0]["group"], "x");
  EXPECT_DOUBLE_EQ(j["groups"][0]["median"].get<double>(), 5.5);

  r = run_palprig({"stats", "pearson", (dir / "d.csv").string(), "--x", "before", "--y", "after", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(nlohmann::json::parse(r.out)["r"].get<double>(), 0.99);

  write(dir / "likert.csv", "item6\n3\n4\n4\n4\n4\n4\n4\n4\n4\n4\n");
  r = run_palprig(
      {"stats", "wilcoxon", (dir / "likert.csv").string(), "--column", "item6", "--against", "3", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["p"].get<double>(), 0.0033534364549463227, 1e-12);
  EXPECT_EQ(j["zeros_dropped"].get<int>(), 1);
}

TEST(experiments_cli_stats, refusals_are_one_line_naming_file_line_and_expectation) {
  ScratchDir dir;
  write(dir / "bad.csv", "group,time\nx,1.0\nx,2.5\ny,\ny,3.0\n");
  auto r = run_palprig({"stats", "ttest", (dir / "bad.csv").string(), "--column", "time", "--by", "group"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(testing::count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bad.csv"), std::string::npos);
  EXPECT_NE(r.err.find("line 4"), std::string::npos);
  EXPECT_NE(r.err.find("column 'time'"), std::string::npos);
  EXPECT_NE(r.err.find("a number"), std::string::npos);

  write(dir / "text.csv", "v\n1\nabc\n");
  r = run_palprig({"stats", "describe", (dir / "text.csv").string(), "--column", "v"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 3"), std::string::npos);
  EXPECT_NE(r.err.find("'abc'"), std::string::npos);

  write(dir / "three.csv", "g,v\na,1\nb,2\nc,3\na,4\n");
  r = run_palprig({"stats", "mannwhitney", (dir / "three.csv").string(), "--column", "v", "--by", "g"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("exactly two groups"), std::string::npos);

  r = run_palprig({"stats", "ttest", (dir / "three.csv").string(), "--column", "missing", "--by", "g"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("columns: g, v"), std::string::npos);

  r = run_palprig({"stats", "proportion", "--k", "7", "--n", "5"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(testing::count_lines(r.err), 1);
}

TEST(experiments_cli_stats, help_names_the_conventions) {
  const auto r = run_palprig({"stats", "--help"});
  ASSERT_EQ(r.exit_code, 0);
  for (const char* word : {"Wilson", "R wilcox.test", "scipy", "type 7", "Welch", "continuity"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
  }
}

}  // namespace
}  // namespace palprig
