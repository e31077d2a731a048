// trials.stimulus_reached_s (schema 4): when the stimulus reached the fingers, stored beside the
// commanded onset; a round trip through the store, its scans, statistics and exports; a schema-3
// file (what the palprig before it wrote) read as it is, then migrated in one transaction keeping
// every trial value for value (a real session storing it: tests/experiments/stimulus_reached_test.cpp).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "store/session_rows.hpp"
#include "store/sqlite_db.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_export.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"
#include "tests/support/discrimination_trials.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

void reached_raw_sql(const std::filesystem::path& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
  sqlite3_close(db);
}

Protocol reached_protocol() {
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "reached", "task": "discrimination", "levels_kPa": [0, 30],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 30, 0], [0, 0, 0]]},
    "conditions": [{"name": "three", "mode": "simultaneous"}, {"name": "one", "mode": "sequential"}],
    "randomisation": {"scheme": "fixed"}, "repetitions": 3})");
  return parse_protocol(doc, "reached.json", ".");
}

// Onset 10 s x position, answered 1.5 s + position/10 later; reached 40 ms after the onset
// where a finger carries a level (0/30/0), never for 0/0/0; position 2 times out.
TrialRecord reached_trial_of(const Protocol& p, const PlannedTrial& planned) {
  TrialRecord r = testing::discrimination_trial(p, planned, false);  // answered with the truth
  if (planned.position == 2) {                                       // timed out
    r.answered = false;
    r.answer = {};
    r.finger_outcomes = {};
  }
  r.stimulus_end_s = r.onset_s + 1.0;
  if (r.stimulus_kPa[1] > 0) r.stimulus_reached_s = r.onset_s + 0.040;
  r.response_time_s = r.answered ? 1.5 + 0.1 * planned.position : std::nan("");
  return r;
}

std::filesystem::path store_with_one_session(const ScratchDir& dir, const Protocol& p, const SessionPlan& plan) {
  auto file = dir / "t.db";
  SqliteTrialStore store(file, TrialStore::Access::read_write);
  const auto session = store.create_session(store.enrol("P01", false), p, plan, {});
  for (const PlannedTrial& t : plan.trials) store.commit_trial(session, reached_trial_of(p, t));
  return file;
}

TEST(store_reached_column, stimulus_reached_round_trips_through_reads_scans_and_statistics) {
  ScratchDir dir;
  const Protocol p = reached_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 7);
  const auto file = store_with_one_session(dir, p, plan);
  SqliteTrialStore reader(file, TrialStore::Access::read_only);
  const auto trials = reader.read_trials(true);
  ASSERT_EQ(trials.size(), plan.trials.size());
  int reached = 0;
  for (const StoredTrial& t : trials) {
    const TrialRecord want = reached_trial_of(p, plan.trials[static_cast<std::size_t>(t.position)]);
    if (std::isnan(want.stimulus_reached_s)) {
      EXPECT_FALSE(t.stimulus_reached_s.has_value()) << t.position;
      EXPECT_FALSE(t.rt_from_reached_s.has_value()) << t.position;
      continue;
    }
    ASSERT_TRUE(t.stimulus_reached_s.has_value()) << t.position;
    EXPECT_DOUBLE_EQ(*t.stimulus_reached_s, want.stimulus_reached_s);
    if (t.answered) {
      ++reached;
      ASSERT_TRUE(t.rt_from_reached_s.has_value());
      EXPECT_NEAR(*t.rt_from_reached_s, want.response_time_s - 0.040, 1e-12);
      EXPECT_NEAR(*t.rt_from_reached_s, response_time_from_reached_s(want), 1e-12);
    } else {
      EXPECT_FALSE(t.rt_from_reached_s.has_value());
    }
  }
  ASSERT_GT(reached, 2);
  double sum = 0;
  int n = 0;
  reader.scan_scored_trials(TrialFamily::discrimination, true, [&](const ScoredTrial& t) {
    if (std::isfinite(t.rt_from_reached_s)) {
      sum += t.rt_from_reached_s;
      ++n;
      EXPECT_NEAR(t.rt_from_reached_s, t.response_time_s - 0.040, 1e-12);
    }
  });
  EXPECT_EQ(n, reached);
  // stats trials: the mean from the reached time, in the CSV and JSON beside the onset's.
  SummaryOptions all;
  all.include_practice = true;
  const TrialSummary s = summarise_trials(reader, all);
  ASSERT_EQ(s.rows.size(), 1u);
  EXPECT_NEAR(s.rows[0].mean_rt_from_reached_s, sum / n, 1e-12);
  const auto json = summary_json(s, 0.95);
  EXPECT_NEAR(json["rows"][0]["rt_from_reached_mean_s"].get<double>(), sum / n, 1e-12);
  EXPECT_TRUE(json["rows"][0]["rt_from_reached_sd_s"].is_number());
  const std::string csv = summary_csv(s);
  EXPECT_NE(csv.substr(0, csv.find('\n')).find(",rt_from_reached_mean_s,rt_from_reached_sd_s"), std::string::npos)
      << csv;
}

TEST(store_reached_column, exports_carry_the_reached_time_and_the_response_time_from_it) {
  ScratchDir dir;
  const Protocol p = reached_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 7);
  const auto file = store_with_one_session(dir, p, plan);
  SqliteTrialStore reader(file, TrialStore::Access::read_only);
  export_long_csv(reader, dir / "out", {});
  std::ifstream in(dir / "out" / "trials_long.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_NE(header.find(",rt_after_stimulus_s,confidence,stimulus_reached_s,rt_from_reached_s"), std::string::npos)
      << header;
  std::string line;
  int with_time = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (line.back() == ',') cells.emplace_back();
    ASSERT_GE(cells.size(), 2u);
    // The reached time and the RT from it, before the last column (the localisation case).
    const std::string& reached = cells[cells.size() - 3];
    const std::string& rt = cells[cells.size() - 2];
    if (reached != "n/a") {
      ++with_time;
      EXPECT_NEAR(std::fmod(std::stod(reached), 10.0), 0.040, 1e-4) << line;
      if (rt != "n/a") {
        EXPECT_NEAR(std::stod(rt) - std::floor(std::stod(rt) * 10 + 1e-9) / 10, 0.06, 1e-4) << line;
      }
    } else {
      EXPECT_EQ(rt, "n/a") << line;
    }
  }
  EXPECT_GT(with_time, 0);
  // BIDS: one column each, described in the sidecar with its unit.
  export_bids(reader, dir / "bids", {});
  bool found = false;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir / "bids")) {
    if (e.path().extension() != ".tsv" || e.path().filename().string().find("_beh") == std::string::npos) continue;
    std::ifstream tsv(e.path());
    std::string head;
    std::getline(tsv, head);
    EXPECT_NE(head.find("\trt_after_stimulus\tstimulus_reached\trt_from_reached"), std::string::npos) << head;
    auto json_path = e.path();
    json_path.replace_extension(".json");
    const auto side = nlohmann::json::parse(std::ifstream(json_path));
    EXPECT_EQ(side["stimulus_reached"]["Units"], "s");
    EXPECT_EQ(side["rt_from_reached"]["Units"], "s");
    found = true;
  }
  EXPECT_TRUE(found);
}

// Every stored value of every trial but the new column, to compare across the migration.
std::string digest(const std::filesystem::path& file) {
  Database db(file, Database::Mode::read_only);
  std::string columns;
  for (std::size_t i = 0; i < kTrialColumnsBeforeReached; ++i)
    columns += ", quote(" + std::string(kTrialColumns[i].name) + ")";
  std::string all;
  auto rows = db.prepare("SELECT id" + columns + " FROM trials ORDER BY id");
  while (rows.step()) {
    for (std::size_t c = 0; c <= kTrialColumnsBeforeReached; ++c)
      all += std::string(rows.text_view(static_cast<int>(c))) + ",";
    all += "\n";
  }
  return all;
}

TEST(store_reached_column, a_schema3_file_is_read_as_it_is_then_migrated_keeping_every_trial) {
  ScratchDir dir;
  const Protocol p = reached_protocol();
  const SessionPlan plan = make_session_plan(p, 1, 7);
  const auto file = store_with_one_session(dir, p, plan);
  // What the palprig before schema 4 wrote: the same tables without the last column.
  reached_raw_sql(file, "ALTER TABLE trials DROP COLUMN stimulus_reached_s; PRAGMA user_version = 3;");
  const std::string before = digest(file);
  const std::size_t n = plan.trials.size();
  std::string stats_before;
  {
    SqliteTrialStore reader(file, TrialStore::Access::read_only);
    EXPECT_EQ(reader.database().pragma_integer("user_version"), 3);
    for (const StoredTrial& t : reader.read_trials(true)) {
      EXPECT_FALSE(t.stimulus_reached_s.has_value());
      EXPECT_FALSE(t.rt_from_reached_s.has_value());
      EXPECT_TRUE(t.stimulus_end_s.has_value()) << "the schema-2 columns are still read";
    }
    reader.scan_scored_trials(TrialFamily::discrimination, true,
                              [](const ScoredTrial& t) { EXPECT_TRUE(std::isnan(t.rt_from_reached_s)); });
    SummaryOptions all;
    all.include_practice = true;
    const TrialSummary s = summarise_trials(reader, all);
    EXPECT_TRUE(std::isnan(s.rows.at(0).mean_rt_from_reached_s));
    stats_before = summary_json(s, 0.95).dump();
  }
  {
    SqliteTrialStore again(file, TrialStore::Access::read_only);
    EXPECT_EQ(again.database().pragma_integer("user_version"), 3) << "a reader never migrates";
  }
  SqliteTrialStore writer(file, TrialStore::Access::read_write);
  EXPECT_EQ(writer.database().pragma_integer("user_version"), kTrialStoreSchemaVersion);
  EXPECT_EQ(digest(file), before) << "every trial kept, value for value";
  ASSERT_EQ(writer.read_trials(true).size(), n);
  for (const StoredTrial& t : writer.read_trials(true)) EXPECT_FALSE(t.stimulus_reached_s.has_value());
  SummaryOptions all;
  all.include_practice = true;
  EXPECT_EQ(summary_json(summarise_trials(writer, all), 0.95).dump(), stats_before);
  // The migrated file takes the new column.
  const auto session = writer.create_session(writer.enrol("P02", false), p, plan, {});
  writer.commit_trial(session, reached_trial_of(p, plan.trials[0]));
  auto q = writer.database().prepare("SELECT stimulus_reached_s FROM trials WHERE session_id = ?1");
  q.bind(1, session);
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.is_null(0), std::isnan(reached_trial_of(p, plan.trials[0]).stimulus_reached_s));
}

}  // namespace
}  // namespace palprig
