// `palprig stats trials` runs paper 002's tests between conditions: the response-time t-test on
// scored trials (practice left out, one value per trial) equals scipy's on the same trials, read
// from the store by Python's own sqlite3 (tests/store/condition_comparisons_oracle.py), Student's
// and Welch's; the window's statistics (compute_trial_statistics) show the same numbers; the
// combined intervals (eq. 10) are there too; and the tests follow the grouping asked. Before,
// the test existed only in the window, and `stats ttest` on the export's long file gave n 96 vs
// 96 and p 1.8e-14 for what is n 28 vs 28 and p 6.1e-05.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "store/trial_statistics.hpp"
#include "store/trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

// README's study: paper 002's discrimination protocol, sim:1 and sim:2.
std::string make_study(const ScratchDir& dir) {
  std::string db = (dir / "study.db").string();
  for (const char* who : {"sim:1", "sim:2"}) {
    const auto run =
        run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "discrimination_002.json").string(),
                     "--participant", who, "--db", db, "--quiet"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
  }
  return db;
}

nlohmann::json scipy_oracle(const std::string& db) {
  const auto r = test_support::run_process(
      "/usr/bin/python3 " + (testing::source_dir() / "tests/store/condition_comparisons_oracle.py").string() + " " +
      db);
  EXPECT_EQ(r.exit_code, 0) << r.err << " (needs Debian's python3-scipy, tools/debian-packages-test.txt)";
  return nlohmann::json::parse(r.out);
}

const nlohmann::json& rt_comparison(const nlohmann::json& stats) {
  for (const auto& c : stats["comparisons"])
    if (c["measure"] == "RT") return c;
  static const nlohmann::json none;
  ADD_FAILURE() << "no RT comparison in " << stats.dump(1);
  return none;
}

TEST(ConditionComparisons, TheResponseTimeTTestEqualsScipysOnTheScoredTrials) {
  ScratchDir dir;
  const std::string db = make_study(dir);
  const nlohmann::json oracle = scipy_oracle(db);
  for (const char* test : {"student", "welch"}) {
    const auto r = run_palprig({"stats", "trials", db, "--json", "--rt-test", test});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json stats = nlohmann::json::parse(r.out);
    const nlohmann::json& rt = rt_comparison(stats);
    const nlohmann::json& want = oracle[test];
    EXPECT_EQ(rt["first"], oracle["conditions"][0]);
    EXPECT_EQ(rt["second"], oracle["conditions"][1]);
    EXPECT_EQ(rt["n_first"], oracle["n"][0]);
    EXPECT_EQ(rt["n_second"], oracle["n"][1]);
    EXPECT_NEAR(rt["t"].get<double>(), want["t"].get<double>(), 1e-9 * std::abs(want["t"].get<double>())) << test;
    EXPECT_NEAR(rt["df"].get<double>(), want["df"].get<double>(), 1e-9 * want["df"].get<double>()) << test;
    EXPECT_NEAR(rt["p"].get<double>(), want["p"].get<double>(), 1e-7 * want["p"].get<double>()) << test;
  }
  // The README's figures for this study (its analysis example): 28 scored trials a condition, t 4.35, p 6.1e-05.
  EXPECT_EQ(oracle["n"][0], 28);
  EXPECT_EQ(oracle["n"][1], 28);
  EXPECT_NEAR(std::abs(oracle["student"]["t"].get<double>()), 4.35, 0.005);
  EXPECT_NEAR(oracle["student"]["p"].get<double>(), 6.1e-5, 0.05e-5);
}

TEST(ConditionComparisons, TheWindowShowsTheNumbersOfStatsTrials) {
  ScratchDir dir;
  const std::string db = make_study(dir);
  const auto r = run_palprig({"stats", "trials", db, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json cli = nlohmann::json::parse(r.out);
  const auto store = open_trial_store(db, TrialStore::Access::read_only);
  const TrialStatistics window = compute_trial_statistics(*store, SummaryOptions{});
  ASSERT_EQ(window.response_times.size(), 1u);
  ASSERT_TRUE(window.response_times[0].test);
  const nlohmann::json& rt = rt_comparison(cli);
  EXPECT_EQ(window.response_times[0].test->t, rt["t"].get<double>());  // one library call, the same bits
  EXPECT_EQ(window.response_times[0].test->p, rt["p"].get<double>());
  // Eq. 10 for each measure, in the same order.
  std::vector<nlohmann::json> measures;
  for (const auto& c : cli["comparisons"])
    if (c["measure"] != "RT") measures.push_back(c);
  ASSERT_EQ(measures.size(), window.measures.size());
  for (std::size_t i = 0; i < measures.size(); ++i) {
    EXPECT_EQ(measures[i]["measure"], window.measures[i].measure);
    EXPECT_EQ(measures[i]["combined_interval"].get<double>(), window.measures[i].comparison.combined_interval);
    EXPECT_EQ(measures[i]["different"].get<bool>(), window.measures[i].comparison.significant);
  }
}

TEST(ConditionComparisons, TheTableSaysWhichTestAndTheTestsFollowTheGrouping) {
  ScratchDir dir;
  const std::string db = make_study(dir);
  const auto table = run_palprig({"stats", "trials", db});
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("Student's t-test (pooled variance)"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("single-finger vs three-finger  RT s"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("t(54) = 4.35"), std::string::npos) << table.out;
  // Per participant: one comparison of the conditions within each, the participant named.
  const auto by = run_palprig({"stats", "trials", db, "--by", "condition,participant", "--json"});
  ASSERT_EQ(by.exit_code, 0) << by.err;
  int rt = 0;
  const nlohmann::json per_participant = nlohmann::json::parse(by.out);
  for (const auto& c : per_participant["comparisons"]) {
    EXPECT_TRUE(c.contains("participant")) << c.dump();
    if (c["measure"] != "RT") continue;
    ++rt;
    EXPECT_EQ(c["n_first"].get<int>(), 14) << c.dump();
  }
  EXPECT_EQ(rt, 2);
  // No condition in the grouping: nothing compared, and no empty section printed.
  const auto none = run_palprig({"stats", "trials", db, "--by", "participant"});
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_EQ(none.out.find("Between conditions"), std::string::npos) << none.out;
}

TEST(ConditionComparisons, StatsTtestOnTheLongExportSaysItHasSeveralRowsPerTrial) {
  ScratchDir dir;
  const std::string db = make_study(dir);
  const std::string out = (dir / "csv").string();
  const auto exported = run_palprig({"export", db, "--out", out});
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const auto long_test = run_palprig({"stats", "ttest", out + "/trials_long.csv", "--column", "response_time_s", "--by",
                                      "condition", "--student", "--json"});
  ASSERT_EQ(long_test.exit_code, 0) << long_test.err;
  EXPECT_NE(long_test.err.find("several rows per trial"), std::string::npos) << long_test.err;
  EXPECT_NE(long_test.err.find("practice trials"), std::string::npos) << long_test.err;
  EXPECT_EQ(nlohmann::json::parse(long_test.out)["warnings"].size(), 2u);
  // The one-row-per-trial file, practice filtered, gives the store's test (and no warning about rows).
  const std::string trials = out + "/trials.csv";
  std::ifstream in(trials);
  std::string header, line, scored = "condition,rt\n";
  std::getline(in, header);
  EXPECT_NE(header.find("response_time_s"), std::string::npos);
  // Columns by name: the file is what an analyst reads in R.
  std::vector<std::string> names;
  for (std::size_t a = 0, b; a <= header.size(); a = b + 1) {
    b = header.find(',', a);
    if (b == std::string::npos) b = header.size();
    names.push_back(header.substr(a, b - a));
  }
  const auto at = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  int rows = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    for (std::size_t a = 0, b; a <= line.size(); a = b + 1) {
      b = line.find(',', a);
      if (b == std::string::npos) b = line.size();
      cells.push_back(line.substr(a, b - a));
    }
    ++rows;
    if (cells[at("practice")] == "0" && cells[at("answered")] == "1")
      scored += cells[at("condition")] + "," + cells[at("response_time_s")] + "\n";
  }
  EXPECT_EQ(rows, 64);  // one row per trial: 2 participants x 32 trials
  std::ofstream(dir / "scored.csv") << scored;
  const auto per_trial = run_palprig(
      {"stats", "ttest", (dir / "scored.csv").string(), "--column", "rt", "--by", "condition", "--student", "--json"});
  ASSERT_EQ(per_trial.exit_code, 0) << per_trial.err;
  EXPECT_EQ(per_trial.err, "");
  const auto j = nlohmann::json::parse(per_trial.out);
  EXPECT_EQ(j["n_x"], 28);
  EXPECT_NEAR(std::abs(j["t"].get<double>()), 4.35, 0.005);  // the exported times have 4 decimals
}

}  // namespace
}  // namespace palprig
