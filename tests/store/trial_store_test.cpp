// The SQLite trial store: schema identity, refusals, sessions, per-trial commits, resume data.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <fstream>

#include "sessions/session_setup.hpp"
#include "store/sqlite_trial_store.hpp"
#include "core/input_error.hpp"
#include "tests/support/discrimination_trials.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

using testing::discrimination_trial;

void raw_sql(const std::filesystem::path& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
}

TEST(experiments_trial_store, new_database_is_marked_and_in_wal_mode) {
  ScratchDir dir;
  {
    SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
    EXPECT_EQ(store.database().pragma_integer("application_id"), kTrialStoreApplicationId);
    EXPECT_EQ(store.database().pragma_integer("user_version"), kTrialStoreSchemaVersion);
    auto mode = store.database().prepare("PRAGMA journal_mode");
    ASSERT_TRUE(mode.step());
    EXPECT_EQ(mode.text(0), "wal");
  }
  // Reopening an existing store works, read-only too.
  SqliteTrialStore again(dir / "t.db", TrialStore::Access::read_write);
  SqliteTrialStore reader(dir / "t.db", TrialStore::Access::read_only);
  EXPECT_EQ(reader.database().pragma_integer("user_version"), kTrialStoreSchemaVersion);
}

TEST(experiments_trial_store, refuses_foreign_newer_and_non_sqlite_files) {
  ScratchDir dir;
  raw_sql(dir / "other.db", "CREATE TABLE t (x);");
  try {
    SqliteTrialStore s(dir / "other.db", TrialStore::Access::read_write);
    FAIL() << "a foreign database was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "PRAGMA application_id");
  }

  { SqliteTrialStore s(dir / "newer.db", TrialStore::Access::read_write); }
  raw_sql(dir / "newer.db", "PRAGMA user_version = 99;");
  try {
    SqliteTrialStore s(dir / "newer.db", TrialStore::Access::read_write);
    FAIL() << "a newer database was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "PRAGMA user_version");
    EXPECT_NE(e.expected().find("99"), std::string::npos);
  }

  std::ofstream(dir / "text.db") << "participant,rt\n1,2\nthis is not a database at all, just text\n";
  EXPECT_THROW(SqliteTrialStore(dir / "text.db", TrialStore::Access::read_write), InputError);
  EXPECT_THROW(open_trial_store((dir / "missing.db").string(), TrialStore::Access::read_only), InputError);
  EXPECT_THROW(SqliteTrialStore(dir / "no" / "such" / "folder.db", TrialStore::Access::read_write), InputError);
}

TEST(experiments_trial_store, session_order_and_trials_round_trip) {
  ScratchDir dir;
  const Protocol p = load_protocol(testing::protocols_dir() / "discrimination_002.json");
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  SessionRequest request;
  request.participant_code = "P01";
  request.setup = {"sim-default", "simulated", "paper002", nullptr, testing::protocols_dir().string()};
  const OpenedSession opened = open_session(store, p, request);
  EXPECT_EQ(opened.participant.number, 1);
  EXPECT_EQ(opened.start_position, 0);

  for (int i = 0; i < 5; ++i) {
    store.commit_trial(opened.session_id,
                       discrimination_trial(p, opened.plan.trials[static_cast<std::size_t>(i)], i == 3));
  }
  const StoredSession loaded = store.load_session(opened.session_id);
  EXPECT_EQ(loaded.completed_trials, 5);
  EXPECT_EQ(loaded.status, "running");
  EXPECT_EQ(loaded.plan.seed, opened.plan.seed);
  EXPECT_EQ(loaded.plan.condition_order, opened.plan.condition_order);
  ASSERT_EQ(loaded.plan.trials.size(), opened.plan.trials.size());
  for (std::size_t i = 0; i < loaded.plan.trials.size(); ++i) {
    EXPECT_EQ(loaded.plan.trials[i].combination, opened.plan.trials[i].combination);
    EXPECT_EQ(loaded.plan.trials[i].practice, opened.plan.trials[i].practice);
    EXPECT_EQ(loaded.plan.trials[i].break_after, opened.plan.trials[i].break_after);
  }
  EXPECT_EQ(loaded.protocol_snapshot, p.snapshot);

  // Per-finger outcomes are stored as the paper's TP/FN/TN/FP.
  auto q =
      store.database().prepare("SELECT outcome1, outcome2, outcome3, truth, answer FROM trials WHERE position = 3");
  ASSERT_TRUE(q.step());
  const auto& c = p.combinations[static_cast<std::size_t>(opened.plan.trials[3].combination)];
  for (int f = 0; f < 3; ++f) EXPECT_EQ(q.text(f), c.tumor[static_cast<std::size_t>(f)] ? "TP" : "FP");
  EXPECT_EQ(q.text(4), "111");
}

TEST(experiments_trial_store, resume_rules) {
  ScratchDir dir;
  const Protocol p = load_protocol(testing::protocols_dir() / "discrimination_002.json");
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  SessionRequest request;
  request.participant_code = "P07";
  const OpenedSession first = open_session(store, p, request);
  store.commit_trial(first.session_id, discrimination_trial(p, first.plan.trials[0], false));
  store.commit_trial(first.session_id, discrimination_trial(p, first.plan.trials[1], false));

  // A second start without --resume is refused, naming the way out.
  try {
    open_session(store, p, request);
    FAIL() << "an unfinished session was silently replaced";
  } catch (const InputError& e) {
    EXPECT_NE(e.expected().find("`resume`"), std::string::npos);
    EXPECT_NE(e.expected().find("after 2 of 32"), std::string::npos);
  }
  request.resume = true;
  const OpenedSession resumed = open_session(store, p, request);
  EXPECT_TRUE(resumed.resumed);
  EXPECT_EQ(resumed.session_id, first.session_id);
  EXPECT_EQ(resumed.start_position, 2);

  // A protocol that changed since the session started is refused.
  nlohmann::json changed = p.snapshot;
  changed["timing"]["inter_trial_s"] = 1.0;
  const Protocol edited = parse_protocol(changed, p.source, testing::protocols_dir());
  EXPECT_THROW(open_session(store, edited, request), InputError);

  // Nothing to resume for someone else.
  request.participant_code = "P08";
  EXPECT_THROW(open_session(store, p, request), InputError);

  // After completion a new session may start; the participant keeps the number.
  store.complete_session(first.session_id);
  request.participant_code = "P07";
  request.resume = false;
  const OpenedSession again = open_session(store, p, request);
  EXPECT_NE(again.session_id, first.session_id);
  EXPECT_EQ(again.participant.number, 1);
}

TEST(experiments_trial_store, participants_are_numbered_in_enrolment_order) {
  ScratchDir dir;
  SqliteTrialStore store(dir / "t.db", TrialStore::Access::read_write);
  EXPECT_EQ(store.enrol("anna", false).number, 1);
  EXPECT_EQ(store.enrol("sim:3", true).number, 2);
  EXPECT_EQ(store.enrol("anna", false).number, 1);
  EXPECT_TRUE(store.find_participant("sim:3")->simulated);
  EXPECT_FALSE(store.find_participant("nobody").has_value());
}

}  // namespace
}  // namespace palprig
