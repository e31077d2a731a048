// What the first users tripped over in the analysis commands, each reproduced on a real store
// made by `palprig experiment run`:
//   - `stats trials` on a threshold store printed only the discrimination header (exit 0); every
//     task kind now gives its statistics (thresholds per track), one JSON object for programs,
//     and a store without trials is refused;
//   - `experiment plan --participant sim:2` printed participant 1's order without saying so; it
//     now takes --db for the participant's real number and always says which number it used;
//   - an export wrote a header-only marks.csv for a store without localisation trials;
//   - `stats psychometric` printed ~150 YAML-like lines and did not say where its thresholds are
//     taken, beside the session's own at 79.4 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

namespace fs = std::filesystem;
using testing::run_palprig;
using testing::ScratchDir;

std::string protocol(const std::string& name) { return (testing::protocols_dir() / name).string(); }

void run_session(const std::string& protocol_file, const std::string& who, const std::string& db) {
  const auto r = run_palprig(
      {"experiment", "run", "--protocol", protocol(protocol_file), "--participant", who, "--db", db, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

TEST(AnalysisCommands, StatsTrialsGivesAThresholdStoresThresholds) {
  ScratchDir dir;
  const std::string db = (dir / "t.db").string();
  run_session("threshold_1up3down.json", "sim:1", db);
  const auto table = run_palprig({"stats", "trials", db});
  ASSERT_EQ(table.exit_code, 0) << table.err;
  // The tracks experiment run reported: one-finger 0.844 kPa and three-finger 0.555 kPa at 79.4 %.
  EXPECT_TRUE(std::regex_search(table.out, std::regex("one-finger +one +staircase +121 .* 0\\.844 +79\\.4")))
      << table.out;
  EXPECT_TRUE(std::regex_search(table.out, std::regex("three-finger +three +staircase +103 .* 0\\.555 +79\\.4")))
      << table.out;
  EXPECT_EQ(table.out.find("TP  FN"), std::string::npos) << "the empty discrimination table is gone: " << table.out;
  const auto json = run_palprig({"stats", "trials", db, "--json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["task"], "threshold");
  ASSERT_EQ(j["tracks"].size(), 2u);
  EXPECT_NEAR(j["tracks"][0]["target_probability"].get<double>(), 0.794, 0.001);

  // A store holding two kinds: one JSON object naming each (it was two documents back to back).
  run_session("discrimination_002.json", "sim:2", db);
  const auto both = run_palprig({"stats", "trials", db, "--json"});
  ASSERT_EQ(both.exit_code, 0) << both.err;
  const auto b = nlohmann::json::parse(both.out);
  ASSERT_EQ(b["tasks"].size(), 2u);
  EXPECT_EQ(b["tasks"][0]["task"], "threshold");
  EXPECT_EQ(b["tasks"][1]["task"], "discrimination/localisation");
}

TEST(AnalysisCommands, StatsTrialsRefusesAStoreWithoutTrials) {
  ScratchDir dir;
  const std::string db = (dir / "empty.db").string();
  { SqliteTrialStore store(db, TrialStore::Access::read_write); }
  const auto r = run_palprig({"stats", "trials", db});
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(palprig::testing::count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("holds none"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(AnalysisCommands, ExperimentPlanUsesTheParticipantsNumberInTheStoreAndSaysIt) {
  ScratchDir dir;
  const std::string db = (dir / "s.db").string();
  run_session("discrimination_002.json", "sim:1", db);
  run_session("discrimination_002.json", "sim:2", db);
  const auto planned = run_palprig(
      {"experiment", "plan", "--protocol", protocol("discrimination_002.json"), "--participant", "sim:2", "--db", db});
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  EXPECT_NE(planned.err.find("participant sim:2 as no. 2, enrolled in " + db), std::string::npos) << planned.err;
  // The order the session ran (no. 2, its seed), not participant 1's.
  const auto second = run_palprig({"experiment", "plan", "--protocol", protocol("discrimination_002.json"),
                                   "--participant", "sim:2", "--number", "2"});
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_EQ(planned.out, second.out);
  const auto first =
      run_palprig({"experiment", "plan", "--protocol", protocol("discrimination_002.json"), "--participant", "sim:2"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out, planned.out) << "counterbalancing alternates the conditions' order by number";
  EXPECT_NE(first.err.find("as no. 1 (no --db"), std::string::npos) << first.err;
  // Someone new: the next enrolment's number.
  const auto next = run_palprig(
      {"experiment", "plan", "--protocol", protocol("discrimination_002.json"), "--participant", "P07", "--db", db});
  ASSERT_EQ(next.exit_code, 0) << next.err;
  EXPECT_NE(next.err.find("as no. 3, the next enrolment in"), std::string::npos) << next.err;
  // The stored order is the plan's: compare with the trials the session ran.
  SqliteTrialStore store(db, TrialStore::Access::read_only);
  std::string conditions;
  for (const StoredTrial& t : store.read_trials(true))
    if (t.participant == "sim:2") conditions += t.condition + "\n";
  std::string planned_conditions;
  std::istringstream csv(planned.out);
  std::string line;
  std::getline(csv, line);  // header
  while (std::getline(csv, line)) {
    const auto a = line.find(',', line.find(',') + 1);
    planned_conditions += line.substr(a + 1, line.find(',', a + 1) - a - 1) + "\n";
  }
  EXPECT_EQ(planned_conditions, conditions);
}

TEST(AnalysisCommands, AnExportWritesMarksOnlyForLocalisationAndATrialsFileBesideTheLongOne) {
  ScratchDir dir;
  const std::string db = (dir / "d.db").string();
  run_session("discrimination_002.json", "sim:1", db);
  const auto r = run_palprig({"export", db, "--out", (dir / "csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "csv" / "trials_long.csv"));
  EXPECT_TRUE(fs::exists(dir / "csv" / "trials.csv"));
  EXPECT_FALSE(fs::exists(dir / "csv" / "marks.csv")) << r.out;
  const std::string loc = (dir / "l.db").string();
  run_session("localisation_002.json", "sim:1", loc);
  const auto l = run_palprig({"export", loc, "--out", (dir / "loc").string()});
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_TRUE(fs::exists(dir / "loc" / "marks.csv")) << l.out;
}

TEST(AnalysisCommands, StatsPsychometricPrintsATableAndSaysWhereEachThresholdIsTaken) {
  ScratchDir dir;
  const std::string db = (dir / "t.db").string();
  run_session("threshold_1up3down.json", "sim:1", db);
  const auto r = run_palprig({"stats", "psychometric", db, "--by", "track_name", "--bootstrap", "50"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LE(palprig::testing::count_lines(r.out), 10) << r.out;
  EXPECT_EQ(r.out.find("levels:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("threshold: the level where F = 0.5"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("three-finger +103 "))) << r.out;
  EXPECT_NE(r.out.find("at 79.4 %"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--threshold-at 0.794"), std::string::npos) << r.out;
  // Taken where the sessions' own are: the table says so.
  const auto at = run_palprig(
      {"stats", "psychometric", db, "--by", "track_name", "--bootstrap", "0", "--threshold-at", "0.794", "--json"});
  ASSERT_EQ(at.exit_code, 0) << at.err;
  const auto j = nlohmann::json::parse(at.out);
  EXPECT_NE(j["threshold_rule"].get<std::string>().find("psi = 0.794"), std::string::npos);
  for (const auto& g : j["groups"]) EXPECT_NEAR(g["threshold_proportion"].get<double>(), 0.794, 1e-9);
}

TEST(AnalysisCommands, AbsurdPsychometricLevelsAreRefusedWithTheRangeExpected) {
  ScratchDir dir;
  const auto csv = dir / "levels.csv";
  std::ofstream(csv) << "level,n,k\n1,20,10\n2,20,14\n3,20,18\n1e308,20,20\n";
  const auto r =
      run_palprig({"stats", "psychometric", csv.string(), "--level", "level", "--response", "k", "--n", "n"});
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(palprig::testing::count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("levels within 1e9 times the other steps of each other: the step from 3 to 1e+308"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out, "");
}

}  // namespace
}  // namespace palprig
