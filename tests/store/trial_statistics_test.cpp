// The statistics view's numbers (store/trial_statistics) against the command line's own tests:
// the response-time t-test equals `palprig stats ttest --student` on the stored response times,
// and each eq. 10 comparison equals `palprig stats compare-proportions` on the stored counts.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "store/trial_statistics.hpp"
#include "store/trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

TEST(TrialStatistics, TTestAndCombinedIntervalsEqualTheCommandLine) {
  ScratchDir dir;
  const std::string db = (dir / "trials.db").string();
  for (const char* who : {"sim:21", "sim:22"}) {
    const auto run =
        run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "discrimination_002.json").string(),
                     "--participant", who, "--db", db, "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  const auto store = open_trial_store(db, TrialStore::Access::read_only);
  const TrialStatistics s = compute_trial_statistics(*store, SummaryOptions{});
  ASSERT_EQ(s.by_condition.rows.size(), 2u);
  ASSERT_EQ(s.response_times.size(), 1u);
  ASSERT_TRUE(s.response_times[0].test.has_value()) << s.response_times[0].why_not;

  // The stored response times of answered, non-practice trials, one row per trial.
  const std::string csv = (dir / "rt.csv").string();
  {
    std::ofstream out(csv);
    out << "condition,rt\n";
    out.precision(17);
    for (const StoredTrial& t : store->read_trials(false))
      if (t.answered && t.response_time_s) out << t.condition << "," << *t.response_time_s << "\n";
  }
  const auto& rt = s.response_times[0];
  const auto ttest = run_palprig({"stats", "ttest", csv, "--column", "rt", "--by", "condition", "--groups",
                                  rt.first + "," + rt.second, "--student", "--json"});
  ASSERT_EQ(ttest.exit_code, 0) << ttest.err;
  const auto cli = nlohmann::json::parse(ttest.out);
  EXPECT_NEAR(rt.test->t, cli["t"].get<double>(), 1e-9);
  EXPECT_EQ(rt.test->df, cli["df"].get<double>());
  EXPECT_NEAR(rt.test->p, cli["p"].get<double>(), 1e-12);
  EXPECT_EQ(rt.test->n_x, cli["n_x"].get<std::size_t>());

  // Every measure is defined in both conditions of a discrimination study: four comparisons.
  ASSERT_EQ(s.measures.size(), 4u);
  for (const MeasureComparison& m : s.measures) {
    const auto& c = m.comparison;
    const auto cmp = run_palprig({"stats", "compare-proportions", "--k1", std::to_string(c.first.k), "--n1",
                                  std::to_string(c.first.n), "--k2", std::to_string(c.second.k), "--n2",
                                  std::to_string(c.second.n), "--json"});
    ASSERT_EQ(cmp.exit_code, 0) << cmp.err;
    const auto j = nlohmann::json::parse(cmp.out);
    EXPECT_EQ(c.combined_interval, j["combined_interval"].get<double>()) << m.measure;
    EXPECT_EQ(c.significant, j["significant"].get<bool>()) << m.measure;
    EXPECT_EQ(m.first, s.by_condition.rows[0].key[0]);
  }
  // Per finger value: three rows whose counts add up to the conditions' counts.
  ASSERT_EQ(s.by_finger.rows.size(), 3u);
  ConfusionCounts fingers, conditions;
  for (const auto& r : s.by_finger.rows) fingers += r.counts;
  for (const auto& r : s.by_condition.rows) conditions += r.counts;
  EXPECT_EQ(fingers.tp, conditions.tp);
  EXPECT_EQ(fingers.tn, conditions.tn);
  EXPECT_TRUE(s.by_tumor.rows.empty());  // no localisation trial, and the "-" row is left out
}

TEST(TrialStatistics, OneConditionHasNothingToCompare) {
  ScratchDir dir;
  const std::string db = (dir / "loc.db").string();
  const auto run =
      run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "localisation_002.json").string(),
                   "--participant", "sim:5", "--db", db, "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto store = open_trial_store(db, TrialStore::Access::read_only);
  const TrialStatistics s = compute_trial_statistics(*store, SummaryOptions{});
  ASSERT_EQ(s.by_condition.rows.size(), 1u);
  EXPECT_TRUE(s.response_times.empty());
  EXPECT_TRUE(s.measures.empty());
  EXPECT_FALSE(s.by_tumor.rows.empty());
  for (const auto& r : s.by_tumor.rows) EXPECT_NE(r.key[0], "-");
}

}  // namespace
}  // namespace palprig
