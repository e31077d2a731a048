// The optional confidence rating and the response time after the stimulus, end to end through
// `palprig experiment run` (a person typing at the terminal, the simulated observer), `stats
// trials` and `export`.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "experiments/simulated_participant.hpp"
#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

const std::string kConfidence = (testing::protocols_dir() / "discrimination_002_confidence.json").string();

// Two trials, fixed order, one condition, short timings: what a test can type ahead.
std::string two_trial_protocol(const ScratchDir& dir, bool with_confidence) {
  auto doc = nlohmann::json::parse(std::ifstream(kConfidence));
  doc["combinations"]["list_kPa"] = {{0, 30, 0}, {0, 0, 0}};
  doc["practice_trials"] = 0;
  doc["conditions"] = {{{"name", "three-finger"}, {"mode", "simultaneous"}}};
  doc["timing"] = {{"max_present_s", 0.3}, {"inter_trial_s", 0}, {"response_timeout_s", 30}};
  doc["randomisation"] = {{"scheme", "fixed"}};
  if (!with_confidence) doc.erase("confidence");
  const auto path = dir / (with_confidence ? "rated.json" : "plain.json");
  std::ofstream(path) << doc.dump();
  return path.string();
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Rows of a CSV/TSV as header -> value maps.
std::vector<std::map<std::string, std::string>> table(const std::string& text, char sep) {
  std::stringstream in(text);
  std::string line;
  std::getline(in, line);
  const auto header = palprig::testing::split_cells(line, sep);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto cells = palprig::testing::split_cells(line, sep);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

TEST(experiments_confidence_cli, a_person_types_answers_and_ratings_at_the_terminal) {
  ScratchDir dir;
  const std::string protocol = two_trial_protocol(dir, true);
  const auto db = dir / "p.db";
  // Enter to start; trial 1: "2", rating "7" refused (4 levels) and asked again, then "3";
  // trial 2: "0", rating "x" refused, then "1".
  const auto r = run_palprig({"experiment", "run", "--protocol", protocol, "--participant", "P01", "--db", db.string()},
                             "\n2\n7\n3\n0\nx\n1\n");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("How confident are you? Type 1-4 (1 = guess, 2 = unsure, 3 = fairly sure, 4 = sure)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Please type one number from 1 to 4."), std::string::npos);

  SqliteTrialStore store(db, TrialStore::Access::read_only);
  const auto trials = store.read_trials(true);
  ASSERT_EQ(trials.size(), 2u);
  EXPECT_EQ(trials[0].answer, "010");
  EXPECT_EQ(trials[0].confidence, 3);
  EXPECT_EQ(trials[1].answer, "000");
  EXPECT_EQ(trials[1].confidence, 1);
  for (const StoredTrial& t : trials) {
    ASSERT_TRUE(t.stimulus_end_s.has_value());
    ASSERT_TRUE(t.rt_after_stimulus_s.has_value());
    // Typed ahead, the answers came during the stimulus or just after it: never negative, and
    // onset RT = (stimulus end - onset) + RT after the stimulus.
    EXPECT_GE(*t.rt_after_stimulus_s, 0.0);
    EXPECT_LE(*t.stimulus_end_s - t.onset_s, 0.3 + 1e-9);
    EXPECT_NEAR(*t.response_time_s, *t.stimulus_end_s - t.onset_s + *t.rt_after_stimulus_s, 1e-9);
  }

  // stats trials: the after-stimulus RT next to the onset RT, the mean rating and count rated.
  auto s = run_palprig({"stats", "trials", db.string(), "--by", "condition", "--json"});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const auto j = nlohmann::json::parse(s.out);
  ASSERT_EQ(j["rows"].size(), 1u);
  const auto& row = j["rows"][0];
  EXPECT_EQ(row["rated"], 2);
  EXPECT_DOUBLE_EQ(row["confidence_mean"].get<double>(), 2.0);
  EXPECT_TRUE(row["rt_after_stimulus_mean_s"].is_number());
  EXPECT_NEAR(row["rt_after_stimulus_mean_s"].get<double>(),
              (*trials[0].rt_after_stimulus_s + *trials[1].rt_after_stimulus_s) / 2, 1e-9);
  EXPECT_NEAR(row["rt_mean_s"].get<double>(), (*trials[0].response_time_s + *trials[1].response_time_s) / 2, 1e-9);
  s = run_palprig({"stats", "trials", db.string(), "--by", "condition"});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_NE(s.out.find("RT after stim mean s"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("confidence mean"), std::string::npos) << s.out;

  // Long CSV: three rows per trial, each with the rating and the after-stimulus RT.
  auto e = run_palprig({"export", db.string(), "--format", "csv", "--out", (dir / "csv").string()});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto csv = table(read_text(dir / "csv" / "trials_long.csv"), ',');
  ASSERT_EQ(csv.size(), 6u);
  for (std::size_t i = 0; i < csv.size(); ++i) {
    const StoredTrial& t = trials[i / 3];
    EXPECT_EQ(csv[i].at("confidence"), std::to_string(*t.confidence));
    EXPECT_NEAR(std::stod(csv[i].at("rt_after_stimulus_s")), *t.rt_after_stimulus_s, 1e-4);
  }

  // BIDS: the columns, and the sidecar with the protocol's levels and labels.
  e = run_palprig({"export", db.string(), "--format", "bids", "--out", (dir / "bids").string()});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto beh = dir / "bids" / "sub-P01" / "beh";
  const auto tsv = table(read_text(beh / "sub-P01_task-discriminationconfidence_beh.tsv"), '\t');
  ASSERT_EQ(tsv.size(), 2u);
  EXPECT_EQ(tsv[0].at("confidence"), "3");
  EXPECT_EQ(tsv[1].at("confidence"), "1");
  EXPECT_NEAR(std::stod(tsv[1].at("rt_after_stimulus")), *trials[1].rt_after_stimulus_s, 1e-4);
  const auto side = nlohmann::json::parse(read_text(beh / "sub-P01_task-discriminationconfidence_beh.json"));
  EXPECT_EQ(side["confidence"]["Levels"]["1"], "guess");
  EXPECT_EQ(side["confidence"]["Levels"]["4"], "sure");
  EXPECT_EQ(side["rt_after_stimulus"]["Units"], "s");
}

TEST(experiments_confidence_cli, without_the_field_nothing_is_asked_stored_or_shown) {
  ScratchDir dir;
  const auto db = dir / "p.db";
  const auto r = run_palprig(
      {"experiment", "run", "--protocol", two_trial_protocol(dir, false), "--participant", "P01", "--db", db.string()},
      "\n2\n0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(r.out.find("How confident"), std::string::npos);
  SqliteTrialStore store(db, TrialStore::Access::read_only);
  for (const StoredTrial& t : store.read_trials(true)) EXPECT_FALSE(t.confidence.has_value());
  const auto s = run_palprig({"stats", "trials", db.string(), "--json"});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(s.out.find("confidence_mean"), std::string::npos);
  EXPECT_NE(s.out.find("rt_after_stimulus_mean_s"), std::string::npos);
  auto e = run_palprig({"export", db.string(), "--format", "csv", "--out", (dir / "csv").string()});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  for (const auto& row : table(read_text(dir / "csv" / "trials_long.csv"), ',')) EXPECT_EQ(row.at("confidence"), "");
  e = run_palprig({"export", db.string(), "--format", "bids", "--out", (dir / "bids").string()});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto tsv = read_text(dir / "bids" / "sub-P01" / "beh" / "sub-P01_task-discriminationconfidence_beh.tsv");
  EXPECT_EQ(tsv.find("confidence"), std::string::npos);
}

TEST(experiments_confidence_cli, simulated_ratings_are_higher_on_correct_trials_and_draw_no_random_numbers) {
  ScratchDir dir;
  auto doc = nlohmann::json::parse(std::ifstream(kConfidence));
  doc["repetitions"] = 4;
  const auto rated = dir / "rated.json";
  std::ofstream(rated) << doc.dump();
  doc.erase("confidence");
  const auto plain = dir / "plain.json";
  std::ofstream(plain) << doc.dump();
  for (const auto& [protocol, db] : {std::pair{rated, dir / "rated.db"}, std::pair{plain, dir / "plain.db"}}) {
    const auto r = run_palprig({"experiment", "run", "--protocol", protocol.string(), "--participant", "sim:5", "--db",
                                db.string(), "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  SqliteTrialStore with(dir / "rated.db", TrialStore::Access::read_only),
      without(dir / "plain.db", TrialStore::Access::read_only);
  const auto a = with.read_trials(true), b = without.read_trials(true);
  ASSERT_EQ(a.size(), b.size());
  double correct_sum = 0, wrong_sum = 0;
  int correct_n = 0, wrong_n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // Asking for a rating changes nothing else the observer does (same answers, same times).
    EXPECT_EQ(a[i].answer, b[i].answer) << i;
    EXPECT_EQ(a[i].response_time_s, b[i].response_time_s) << i;
    EXPECT_FALSE(b[i].confidence.has_value());
    if (!a[i].answered) continue;
    ASSERT_TRUE(a[i].confidence.has_value()) << i;
    EXPECT_GE(*a[i].confidence, 1);
    EXPECT_LE(*a[i].confidence, 4);
    if (a[i].answer == a[i].truth)
      correct_sum += *a[i].confidence, ++correct_n;
    else
      wrong_sum += *a[i].confidence, ++wrong_n;
  }
  ASSERT_GT(correct_n, 0);
  ASSERT_GT(wrong_n, 0) << "the observer should err sometimes (10 vs 0 kPa is near its criterion)";
  EXPECT_GT(correct_sum / correct_n, wrong_sum / wrong_n);
}

TEST(experiments_confidence_cli, confidence_from_margin_rises_with_the_margin) {
  EXPECT_EQ(confidence_from_margin(0.0, 4), 1);
  EXPECT_EQ(confidence_from_margin(-1.0, 4), 1);
  EXPECT_EQ(confidence_from_margin(10.0, 4), 4);
  EXPECT_EQ(confidence_from_margin(std::numeric_limits<double>::infinity(), 9), 9);
  int last = 1;
  for (double m = 0; m < 5; m += 0.05) {
    const int c = confidence_from_margin(m, 5);
    EXPECT_GE(c, last);
    last = c;
  }
  EXPECT_EQ(last, 5);
}

}  // namespace
}  // namespace palprig
