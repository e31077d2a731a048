// `stats trials` over localisation trials of several cases (store/trial_summary.hpp): tumors are
// kept per case (the "T1" of one generated case is not pooled with another's), a normal case
// answered without a mark is a true negative and one marked a false positive (Sp over the normal
// cases), false marks are no tumor row named "-", and the table spells "not available" one way.
#include <gtest/gtest.h>

#include "sessions/session_setup.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_export.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"
#include "study/localisation_case.hpp"
#include "tests/support/support.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

std::uint64_t normal_hard_seed() {
  for (std::uint64_t seed = 1;; ++seed) {
    if (generate_case(seed, CaseDifficulty::hard).tumors.empty()) return seed;
  }
}

// Two easy cases (both with a tumor "T1") and a normal case, as the trial runner records them.
struct Cases {
  Protocol protocol;
  std::vector<LocalisationCase> cases;
};

Cases three_cases() {
  nlohmann::json doc = {{"version", 1},
                        {"name", "three cases"},
                        {"task", "localisation"},
                        {"conditions", {{{"name", "palpate"}, {"mode", "scene"}}}},
                        {"randomisation", {{"scheme", "fixed"}}}};
  doc["localisation"] = {{"cases",
                          {{{"difficulty", "easy"}, {"seed", 1}},
                           {{"difficulty", "easy"}, {"seed", 2}},
                           {{"difficulty", "hard"}, {"seed", normal_hard_seed()}}}}};
  Cases c;
  c.protocol = parse_protocol(doc, "three.json", ".");
  c.cases = c.protocol.localisation.cases;
  return c;
}

TrialRecord trial_of(const Cases& c, const PlannedTrial& t, const std::vector<Mark>& marks) {
  const LocalisationCase& k = c.cases.at(static_cast<std::size_t>(t.combination));
  TrialRecord r;
  r.planned = t;
  r.condition = "palpate";
  r.mode = PresentationMode::scene;
  r.answered = true;
  r.response_time_s = 30;
  r.marks = marks;
  r.localisation = score_localisation(k.tumors, marks, 5);
  r.case_name = k.name;
  r.case_seed = k.seed;
  r.case_difficulty = k.difficulty;
  r.case_tumors = static_cast<int>(k.tumors.size());
  return r;
}

TEST(LocalisationCaseSummary, TumorsAreKeptPerCaseAndNormalCasesAreScored) {
  ScratchDir dir;
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  const Cases c = three_cases();
  ASSERT_EQ(c.cases[0].tumors.front().name, "T1");
  ASSERT_EQ(c.cases[1].tumors.front().name, "T1");
  ASSERT_TRUE(c.cases[2].normal());
  // Participant A finds every tumor and leaves the normal case unmarked; B misses case 1's T1,
  // marks nothing on case 2 and marks the normal case.
  for (const std::string who : {"A", "B"}) {
    SessionRequest request;
    request.participant_code = who;
    const OpenedSession s = open_session(store, c.protocol, request);
    for (const PlannedTrial& t : s.plan.trials) {
      const LocalisationCase& k = c.cases.at(static_cast<std::size_t>(t.combination));
      std::vector<Mark> marks;
      if (who == "A") {
        for (const TumorTruth& tumor : k.tumors) marks.push_back({tumor.x_mm, tumor.y_mm});
      } else if (k.normal()) {
        marks.push_back({40, 40});
      }
      store.commit_trial(s.session_id, trial_of(c, t, marks));
    }
  }
  SummaryOptions by_tumor;
  by_tumor.by = {SummaryKey::tumor};
  const TrialSummary s = summarise_trials(store, by_tumor);
  std::map<std::string, const SummaryRow*> rows;
  for (const SummaryRow& r : s.rows) rows[r.key[0]] = &r;
  for (const auto& [key, row] : rows) EXPECT_NE(key, "-") << "a row named '-'";
  const std::string one = c.cases[0].name + "/T1", two = c.cases[1].name + "/T1";
  ASSERT_TRUE(rows.count(one) && rows.count(two)) << "tumors keyed by case";
  EXPECT_EQ(rows[one]->counts.tp + rows[one]->counts.fn, 2);  // two participants, one case: never pooled
  EXPECT_EQ(rows[two]->counts.tp, 1);
  EXPECT_EQ(rows[two]->counts.fn, 1);
  const std::string normal = c.cases[2].name + "/elsewhere";
  ASSERT_TRUE(rows.count(normal));
  EXPECT_EQ(rows[normal]->counts.tn, 1);  // A: nothing marked, the right answer
  EXPECT_EQ(rows[normal]->counts.fp, 1);  // B: one mark on a normal case
  EXPECT_EQ(rows[normal]->normal_cases, 2);
  EXPECT_NEAR(rows[normal]->measures.sp.value, 0.5, 1e-12);

  // One row for everything: Sp over the normal cases (1 of 2), PPV over the marks.
  const TrialSummary all = summarise_trials(store, SummaryOptions{});
  ASSERT_EQ(all.rows.size(), 1u);
  EXPECT_EQ(all.rows[0].counts.tn, 1);
  EXPECT_EQ(all.rows[0].counts.fp, 1);
  EXPECT_TRUE(all.rows[0].negatives_counted);
  EXPECT_NEAR(all.rows[0].measures.sp.value, 0.5, 1e-12);
  EXPECT_FALSE(all.rows[0].measures.acc.defined);
}

TEST(LocalisationCaseSummary, TheTableSpellsNotAvailableOneWay) {
  ScratchDir dir;
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  const Cases c = three_cases();
  SessionRequest request;
  request.participant_code = "A";
  const OpenedSession session = open_session(store, c.protocol, request);
  TrialRecord r = trial_of(c, session.plan.trials[0], {});
  r.answered = false;  // no answer: no response time, "not available" in its columns
  store.commit_trial(session.session_id, r);
  SummaryOptions by_tumor;
  by_tumor.by = {SummaryKey::tumor};
  const std::string table = summary_table(summarise_trials(store, by_tumor));
  EXPECT_NE(table.find("n/a"), std::string::npos) << table;
  EXPECT_EQ(table.find("NA"), std::string::npos) << table;
}

TEST(LocalisationCaseSummary, ExportNamesEachTrialsCaseAndANormalCasesOutcome) {
  ScratchDir dir;
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  const Cases c = three_cases();
  SessionRequest request;
  request.participant_code = "A";
  const OpenedSession session = open_session(store, c.protocol, request);
  for (const PlannedTrial& t : session.plan.trials) store.commit_trial(session.session_id, trial_of(c, t, {}));
  export_long_csv(store, dir / "csv", ExportOptions{});
  const std::string csv = test_support::read_file(dir / "csv" / "trials_long.csv");
  EXPECT_NE(csv.find(",rt_from_reached_s,case\n"), std::string::npos);
  EXPECT_NE(csv.find(",case,n/a,n/a,n/a,n/a,n/a,0,1,0,TN,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("," + c.cases[2].name + "\n"), std::string::npos);
}

}  // namespace
}  // namespace palprig
