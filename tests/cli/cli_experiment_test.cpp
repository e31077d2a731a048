// `palprig experiment run`, `stats trials` and `export` end to end with simulated participants
// and a person typing at the terminal (stdin), and the refusals before any stimulus.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

const std::string kDiscrimination = (testing::protocols_dir() / "discrimination_002.json").string();
const std::string kLocalisation = (testing::protocols_dir() / "localisation_002.json").string();

std::int64_t scalar(const std::filesystem::path& db, const std::string& sql) {
  SqliteTrialStore store(db, TrialStore::Access::read_only);
  auto q = store.database().prepare(sql);
  return q.step() ? q.integer(0) : -1;
}

TEST(experiments_cli_experiment, simulated_study_then_stats_and_exports) {
  ScratchDir dir;
  const std::string db = (dir / "study.db").string();
  for (int seed = 1; seed <= 4; ++seed) {
    const auto r = run_palprig({"experiment", "run", "--protocol", kDiscrimination, "--participant",
                                "sim:" + std::to_string(seed), "--db", db, "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("completed: 32 trials"), std::string::npos) << r.out;
  }
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials"), 4 * 32);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 4);
  // Alternate counterbalancing: participants 1 and 3 start three-finger, 2 and 4 single-finger.
  EXPECT_EQ(scalar(db,
                   "SELECT count(*) FROM trials t JOIN sessions s ON s.id = t.session_id "
                   "WHERE t.position = 0 AND t.condition = 'three-finger'"),
            2);

  auto r = run_palprig({"stats", "trials", db, "--by", "condition", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 2u);
  for (const auto& row : j["rows"]) {
    // 4 participants x 14 scored trials x 3 finger values; practice left out.
    EXPECT_EQ(row["TP"].get<int>() + row["FN"].get<int>() + row["TN"].get<int>() + row["FP"].get<int>(), 4 * 14 * 3);
    EXPECT_EQ(row["trials"].get<int>(), 4 * 14);
    EXPECT_GT(row["ACC"]["value"].get<double>(), 0.8);  // the default observer is good but not perfect
    EXPECT_LE(row["ACC"]["lower"].get<double>(), row["ACC"]["value"].get<double>());
  }
  const double rt_three = j["rows"][1]["rt_mean_s"].get<double>();
  const double rt_single = j["rows"][0]["rt_mean_s"].get<double>();
  EXPECT_EQ(j["rows"][1]["condition"], "three-finger");
  EXPECT_LT(rt_three, rt_single) << "paper 002: three fingers are faster";

  r = run_palprig({"stats", "trials", db, "--by", "participant,finger", "--format", "csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(testing::count_lines(r.out), 1 + 4 * 3);

  r = run_palprig({"export", db, "--format", "csv", "--out", (dir / "csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream csv(dir / "csv" / "trials_long.csv");
  std::string all((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_EQ(testing::count_lines(all), 1 + 4 * 32 * 3);

  r = run_palprig({"export", db, "--format", "bids", "--out", (dir / "bids").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto tsv = dir / "bids" / "sub-sim1" / "beh" / "sub-sim1_task-discrimination_beh.tsv";
  const auto sidecar = dir / "bids" / "sub-sim1" / "beh" / "sub-sim1_task-discrimination_beh.json";
  ASSERT_TRUE(std::filesystem::exists(tsv));
  std::ifstream tsv_in(tsv);
  std::string header;
  std::getline(tsv_in, header);
  const auto side = nlohmann::json::parse(std::ifstream(sidecar));
  // Every column of the TSV is described in the sidecar.
  std::stringstream columns(header);
  std::string name;
  int described = 0;
  while (std::getline(columns, name, '\t')) {
    EXPECT_TRUE(side.contains(name)) << name;
    ++described;
  }
  EXPECT_GT(described, 10);
  EXPECT_EQ(side["stimulus_finger1"]["Units"], "kPa");
  EXPECT_TRUE(side["outcome_finger2"]["Levels"].contains("FP"));
  EXPECT_TRUE(std::filesystem::exists(dir / "bids" / "dataset_description.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "bids" / "participants.tsv"));
}

TEST(experiments_cli_experiment, simulated_localisation_scores_tumors) {
  ScratchDir dir;
  const std::string db = (dir / "loc.db").string();
  for (int seed = 1; seed <= 3; ++seed) {
    const auto r = run_palprig(
        {"experiment", "run", "--protocol", kLocalisation, "--participant", "sim:" + std::to_string(seed), "--db", db});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto r = run_palprig({"stats", "trials", db, "--by", "tumor", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  int tumors = 0;
  for (const auto& row : j["rows"]) {
    if (row["tumor"] == "-") continue;
    ++tumors;
    EXPECT_EQ(row["TP"].get<int>() + row["FN"].get<int>(), 3);
    if (row["tumor"] == "B") {
      EXPECT_EQ(row["TP"].get<int>(), 3) << "the 10 mm tumor B is always found";
    }
  }
  EXPECT_EQ(tumors, 3);
}

TEST(experiments_cli_experiment, a_person_answers_at_the_terminal) {
  ScratchDir dir;
  auto doc = nlohmann::json::parse(std::ifstream(kDiscrimination));
  doc["combinations"]["list_kPa"] = {{0, 30, 0}, {0, 0, 0}};
  doc["practice_trials"] = 0;
  doc["conditions"] = {{{"name", "three-finger"}, {"mode", "simultaneous"}}};
  doc["timing"]["inter_trial_s"] = 0;
  doc["randomisation"] = {{"scheme", "fixed"}};
  std::ofstream(dir / "two.json") << doc.dump();
  // Enter to start; "5" is refused and asked again; then the answers.
  const auto r = run_palprig({"experiment", "run", "--protocol", (dir / "two.json").string(), "--participant", "P01",
                              "--db", (dir / "p.db").string()},
                             "\n5\n2\n0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("Please type finger numbers"), std::string::npos);
  const auto db = dir / "p.db";
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials WHERE outcome1 = 'TN' AND outcome2 = 'TP' AND outcome3 = 'TN'"), 1);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials WHERE answer = '000'"), 1);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM participants WHERE code = 'P01' AND simulated = 0"), 1);
}

TEST(experiments_cli_experiment, end_of_input_stops_and_resume_continues) {
  ScratchDir dir;
  const std::string db = (dir / "p.db").string();
  auto r =
      run_palprig({"experiment", "run", "--protocol", kDiscrimination, "--participant", "P02", "--db", db}, "\n1\n2\n");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--resume"), std::string::npos);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials"), 2);
  r = run_palprig({"experiment", "run", "--protocol", kDiscrimination, "--participant", "P02", "--db", db}, "\n");
  EXPECT_EQ(r.exit_code, 2) << "starting anew over an unfinished session is refused";
  EXPECT_NE(r.err.find("--resume"), std::string::npos);
  r = run_palprig({"experiment", "run", "--protocol", kDiscrimination, "--participant", "P02", "--db", db, "--resume"},
                  "\n3\n");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("resumed at trial 3"), std::string::npos);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials"), 3);
  EXPECT_EQ(scalar(db, "SELECT max(position) FROM trials"), 2);
}

TEST(experiments_cli_experiment, bad_input_is_refused_before_any_stimulus) {
  ScratchDir dir;
  auto doc = nlohmann::json::parse(std::ifstream(kDiscrimination));
  doc["repetitons"] = 2;
  std::ofstream(dir / "typo.json") << doc.dump();
  auto r = run_palprig({"experiment", "run", "--protocol", (dir / "typo.json").string(), "--participant", "sim:1",
                        "--db", (dir / "x.db").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(testing::count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("typo.json: repetitons"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.db")) << "nothing is created for a refused protocol";

  doc = nlohmann::json::parse(std::ifstream(kDiscrimination));
  doc["repetitions"] = 2;
  doc["randomisation"]["min_distance"] = 20;
  std::ofstream(dir / "tight.json") << doc.dump();
  r = run_palprig({"experiment", "run", "--protocol", (dir / "tight.json").string(), "--participant", "sim:1", "--db",
                   (dir / "x.db").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("randomisation"), std::string::npos) << r.err;

  doc = nlohmann::json::parse(std::ifstream(kDiscrimination));
  doc["levels_kPa"] = {0, 10, 30, 80};
  std::ofstream(dir / "high.json") << doc.dump();
  r = run_palprig({"experiment", "run", "--protocol", (dir / "high.json").string(), "--participant", "sim:1", "--db",
                   (dir / "x.db").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("p_max"), std::string::npos) << r.err;

  std::ofstream(dir / "notadb.db") << "just some text, certainly not SQLite, long enough to have a header page....\n";
  r = run_palprig({"experiment", "run", "--protocol", kDiscrimination, "--participant", "sim:1", "--db",
                   (dir / "notadb.db").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not an SQLite database"), std::string::npos) << r.err;

  r = run_palprig(
      {"experiment", "run", "--protocol", kLocalisation, "--participant", "P01", "--db", (dir / "y.db").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--participant"), std::string::npos) << r.err;

  r = run_palprig({"stats", "trials", (dir / "missing.db").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(testing::count_lines(r.err), 1);
}

}  // namespace
}  // namespace palprig
