// `palprig train` and `palprig stats learning` as a trainer runs them (real processes): enrol,
// a pilot trainee's sessions with what they scored and where they stand, the learning report and
// its figures (PNG and SVG), a benchmark from experts; and the refusals: one line, exit 2,
// nothing stored lost.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

std::string course(const ScratchDir& dir) {
  nlohmann::json doc = {{"version", 1}, {"kind", "curriculum"}, {"name", "cli course"}};
  doc["levels"] = nlohmann::json::array();
  for (const char* name : {"first", "second"}) {
    doc["levels"].push_back({{"name", name},
                             {"cases", {{"generate", "easy"}}},
                             {"cases_per_session", 2},
                             {"benchmark", {{"found_min", 0.5}, {"consecutive_sessions", 1}}}});
  }
  doc["pilot"] = {{"initial_skill", 1.0}, {"learning_rate_per_case", 0.0}};
  doc["cusum"] = {{"horizon_cases", 20}};
  const auto path = dir / "course.json";
  std::ofstream(path) << doc.dump(2);
  return path.string();
}

TEST(TrainCommand, APilotTraineeTrainsAndTheTrainerReadsTheirCurves) {
  ScratchDir dir;
  const std::string c = course(dir), db = (dir / "train.db").string();
  auto r = run_palprig({"train", "enrol", "--curriculum", c, "--trainee", "P1", "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("P1 enrolled in 'cli course' (2 levels)"), std::string::npos) << r.out;
  r = run_palprig({"train", "next", "--curriculum", c, "--trainee", "P1", "--db", db, "--participant", "sim:4"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("level 1 'first', session 1, 2 cases: case-easy-"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  case 1/2 case-easy-"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("session completed: tumors found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("level 'first' passed after session 1"), std::string::npos) << r.out;
  r = run_palprig({"train", "status", "--curriculum", c, "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("P1           level 2 of 2 'second'"), std::string::npos) << r.out;
  r = run_palprig({"train", "status", "--curriculum", c, "--db", db, "--trainee", "P1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto status = nlohmann::json::parse(r.out);
  EXPECT_EQ(status["level"], 1);
  EXPECT_EQ(status["sessions"].size(), 1u);
  EXPECT_EQ(status["sessions"][0]["met_benchmark"], true);

  const auto plots = dir / "plots";
  r = run_palprig({"stats", "learning", db, "--curriculum", c, "--plot", plots.string(), "--svg"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("LC-CUSUM: h = "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("trainee P1: 1 sessions, 2 cases"), std::string::npos) << r.out;
  for (const char* f : {"learning_P1_found.png", "learning_P1_found.svg", "cusum_P1.png", "lc_cusum_P1.svg"})
    EXPECT_TRUE(std::filesystem::is_regular_file(plots / f)) << f;
  r = run_palprig({"stats", "learning", db, "--curriculum", c, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto learning = nlohmann::json::parse(r.out);
  EXPECT_EQ(learning["trainees"][0]["lc_cusum"].size(), 2u);
  EXPECT_GT(learning["lc_cusum_limit"]["limit"].get<double>(), 0.0);
  // export --plot draws the same figures beside the study's.
  r = run_palprig({"export", db, "--out", (dir / "csv").string(), "--plot", (dir / "fig").string(), "--curriculum", c});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "fig" / "lc_cusum_P1.png"));
}

TEST(TrainCommand, RefusalsAreOneLineExitTwoAndKeepTheStore) {
  ScratchDir dir;
  const std::string c = course(dir), db = (dir / "train.db").string();
  ASSERT_EQ(run_palprig({"train", "enrol", "--curriculum", c, "--trainee", "P1", "--db", db}).exit_code, 0);
  ASSERT_EQ(run_palprig({"train", "next", "--curriculum", c, "--trainee", "P1", "--db", db, "--participant", "sim:1"})
                .exit_code,
            0);
  const std::string before = test_support::read_file(db);
  const auto refused = [&](const std::vector<std::string>& args, const std::string& says) {
    const auto r = run_palprig(args);
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_EQ(palprig::testing::count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  };
  refused({"train", "next", "--curriculum", c, "--trainee", "nobody", "--db", db, "--participant", "sim:1"},
          "trainee 'nobody'");
  refused({"train", "status", "--curriculum", c, "--trainee", "nobody", "--db", db}, "trainee 'nobody'");
  const auto bad = dir / "bad.json";
  std::ofstream(bad) << R"({"version": 1, "kind": "curriculum", "name": "x", "levels": []})";
  refused({"train", "next", "--curriculum", bad.string(), "--trainee", "P1", "--db", db, "--participant", "sim:1"},
          "levels");
  refused({"train", "benchmark", "--curriculum", c, "--db", db, "--level", "second", "--expert", "P1"}, "experts");
  refused({"train", "next", "--curriculum", c, "--trainee", "P1", "--db", db}, "participant");  // a person: the window
  refused({"train", "next", "--curriculum", c, "--trainee", "P1", "--db", (dir / "none.db").string(), "--participant",
           "sim:1"},
          "none.db");
  refused({"check", bad.string()}, "levels");
  EXPECT_FALSE(std::filesystem::exists(dir / "none.db"));
  // Nothing in the store changed (a refusal writes nothing; readers open it read-only).
  EXPECT_EQ(test_support::read_file(db), before);
}

TEST(TrainCommand, CheckLoadsTheShippedCurriculumAndSaysWhatThePilotIsExpectedToNeed) {
  const auto r =
      run_palprig({"check", (testing::source_dir() / "data" / "curricula" / "palpation_basics.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.out.find("curriculum 'palpation-basics', 5 levels; a pilot trainee who would find every tumor once skilled "
                 "reaches level 2 at session "),
      std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace palprig
