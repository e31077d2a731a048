// The lab store's schema 5 (trials.stimulus_reached_s: when the stimulus reached the fingers)
// on a real PostgreSQL server (with_server.sh; skipped with the reason when none can start): a
// version-4 server holding trials is read as it is, migrated by the first writer in one
// transaction keeping every trial value for value, and the reached times of a new session travel
// through the bench journal and `store copy` both ways.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "store/postgres_schema.hpp"
#include "store/postgres_session_rows.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/session_rows.hpp"
#include "store/sqlite_db.hpp"
#include "store/sqlite_session_rows.hpp"
#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/postgres/pg_test_support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

std::string reached_stats(const std::string& store) {
  const auto r = testing::run_palprig({"stats", "trials", store, "--by", "participant,condition,finger", "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

// Every value of the columns before stimulus_reached_s of the given participants' trials.
std::string reached_digest(const std::string& uri, const std::string& codes) {
  std::string columns;
  for (std::size_t i = 0; i < kTrialColumnsBeforeReached; ++i) columns += ", t." + std::string(kTrialColumns[i].name);
  return PgConnection(parse_pg_target(uri))
      .exec("SELECT md5(string_agg(ROW(t.id, t.session_id" + columns +
            ")::text, '|' ORDER BY t.id)) FROM trials t JOIN sessions s ON s.id = t.session_id "
            "JOIN participants p ON p.id = s.participant_id WHERE p.code IN (" +
            codes + ")")
      .text(0, 0);
}

std::int64_t reached_count(const std::string& uri, const std::string& code) {
  return testing::pg_scalar(uri,
                            "SELECT count(*) FROM trials t JOIN sessions s ON s.id = t.session_id JOIN participants p "
                            "ON p.id = s.participant_id WHERE p.code = '" +
                                code + "' AND t.stimulus_reached_s IS NOT NULL");
}

TEST(PostgresReachedMigration, Version4ServerIsReadAsItIsThenMigratedAndReachedTimesTravel) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string file = (dir / "bench.db").string();
  for (const std::string participant : {"sim:41", "sim:42"}) {
    const auto run =
        testing::run_palprig({"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(),
                              "--participant", participant, "--db", file, "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  // A server the palprig before this column made (schema 4), holding those trials: the push
  // leaves out the times it has no column for.
  const std::string uri = testing::old_server_holding("reached_4_5", 4, file);
  ASSERT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), 4);
  ASSERT_EQ(testing::pg_scalar(uri,
                               "SELECT count(*) FROM information_schema.columns WHERE table_name = 'trials' "
                               "AND column_name = 'stimulus_reached_s'"),
            0);
  const std::int64_t old_count = testing::pg_scalar(uri, "SELECT count(*) FROM trials");
  ASSERT_GT(old_count, 0);
  const std::string old_trials = reached_digest(uri, "'sim:41', 'sim:42'");
  // A reader reads it as it is: the same statistics as the file's but for the reached times.
  const auto without_reached = [](const std::string& json) {
    auto j = nlohmann::json::parse(json);
    for (auto& row : j["rows"]) {
      row.erase("rt_from_reached_mean_s");
      row.erase("rt_from_reached_sd_s");
    }
    return j.dump();
  };
  const std::string before = reached_stats(uri);
  EXPECT_EQ(without_reached(before), without_reached(reached_stats(file)));
  EXPECT_TRUE(nlohmann::json::parse(before)["rows"][0]["rt_from_reached_mean_s"].is_null()) << before;
  EXPECT_FALSE(nlohmann::json::parse(reached_stats(file))["rows"][0]["rt_from_reached_mean_s"].is_null());
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), 4) << "a reader never migrates";

  // A writer migrates it: a session through the bench journal.
  const auto run = testing::run_palprig({"experiment", "run", "--protocol",
                                         palprig::testing::discrimination_protocol_file(), "--participant", "sim:43",
                                         "--db", uri, "--journal", (dir / "journal.db").string(), "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), kPgSchemaVersion);
  EXPECT_EQ(testing::pg_scalar(uri,
                               "SELECT count(*) FROM trials t JOIN sessions s ON s.id = t.session_id JOIN "
                               "participants p ON p.id = s.participant_id WHERE p.code IN ('sim:41', 'sim:42')"),
            old_count);
  EXPECT_EQ(reached_digest(uri, "'sim:41', 'sim:42'"), old_trials);  // every older trial, value for value
  EXPECT_EQ(reached_count(uri, "sim:41") + reached_count(uri, "sim:42"), 0);
  const std::int64_t reached = reached_count(uri, "sim:43");
  ASSERT_GT(reached, 0);
  // The journal (SQLite) holds the same reached times.
  SqliteTrialStore journal(dir / "journal.db", TrialStore::Access::read_only);
  int journal_reached = 0;
  for (const StoredTrial& t : journal.read_trials(true)) journal_reached += t.stimulus_reached_s ? 1 : 0;
  EXPECT_EQ(journal_reached, reached);

  // store copy server -> file and back carries the column; the statistics agree to the bit.
  const std::string back = (dir / "back.db").string();
  const auto down = testing::run_palprig({"store", "copy", "--from", uri, "--to", back});
  ASSERT_EQ(down.exit_code, 0) << down.err;
  EXPECT_EQ(reached_stats(back), reached_stats(uri));
  const std::string again = testing::fresh_database("reached_copy_up");
  const auto up = testing::run_palprig({"store", "copy", "--from", back, "--to", again});
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_EQ(reached_stats(again), reached_stats(uri));
  EXPECT_EQ(reached_count(again, "sim:43"), reached);
}

}  // namespace
}  // namespace palprig
