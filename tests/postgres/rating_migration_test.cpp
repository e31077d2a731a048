// The lab store's schema 3 (trials.confidence, trials.stimulus_end_s) on a real PostgreSQL
// server (with_server.sh; skipped with the reason when none can start): a version-2 server
// holding trials is read as it is, migrated by the first writer keeping every trial, and the
// ratings of a rated session travel through the journal and `store copy` both ways.
#include <gtest/gtest.h>

#include <string>
#include <vector>

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

namespace palprig {
namespace {

using testing::ScratchDir;

std::string plain_protocol() { return (testing::protocols_dir() / "discrimination_002.json").string(); }
std::string rated_protocol() { return (testing::protocols_dir() / "discrimination_002_confidence.json").string(); }

std::string rating_stats(const std::string& store) {
  const auto r = testing::run_palprig({"stats", "trials", store, "--by", "participant,condition,finger", "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

// Every value of the schema-1/2 columns of the given participants' trials.
std::string rating_digest(const std::string& uri, const std::string& codes) {
  std::string columns;
  for (std::size_t i = 0; i < kTrialConfidence; ++i) columns += ", t." + std::string(kTrialColumns[i].name);
  return PgConnection(parse_pg_target(uri))
      .exec("SELECT md5(string_agg(ROW(t.id, t.session_id" + columns +
            ")::text, '|' ORDER BY t.id)) FROM trials t JOIN sessions s ON s.id = t.session_id "
            "JOIN participants p ON p.id = s.participant_id WHERE p.code IN (" +
            codes + ")")
      .text(0, 0);
}

TEST(PostgresRatingMigration, Version2ServerIsReadAsItIsThenMigratedAndRatingsTravel) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string file = (dir / "bench.db").string();
  for (const std::string participant : {"sim:31", "sim:32"}) {
    const auto run = testing::run_palprig(
        {"experiment", "run", "--protocol", plain_protocol(), "--participant", participant, "--db", file, "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  // A server an older palprig made (schema 2), holding those trials.
  const std::string uri = testing::old_server_holding("rating_2_3", 2, file);
  ASSERT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), 2);
  ASSERT_EQ(testing::pg_scalar(uri,
                               "SELECT count(*) FROM information_schema.columns WHERE table_name = 'trials' "
                               "AND column_name IN ('confidence', 'stimulus_end_s')"),
            0);
  const std::string old_trials = rating_digest(uri, "'sim:31', 'sim:32'");
  // A reader opens it as it is: the same statistics as the file's, nothing migrated. (The
  // file has stimulus ends and reached times the version-2 server could not take, so only the onset figures and
  // the measures are compared.)
  const auto without_after = [](const std::string& json) {
    auto j = nlohmann::json::parse(json);
    for (auto& row : j["rows"]) {
      row.erase("rt_after_stimulus_mean_s");
      row.erase("rt_after_stimulus_sd_s");
      row.erase("rt_from_reached_mean_s");
      row.erase("rt_from_reached_sd_s");
    }
    return j.dump();
  };
  const std::string before = rating_stats(uri);
  EXPECT_EQ(without_after(before), without_after(rating_stats(file)));
  EXPECT_TRUE(nlohmann::json::parse(before)["rows"][0]["rt_after_stimulus_mean_s"].is_null()) << before;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), 2);

  // A writer migrates it: a rated session through the bench journal.
  const auto run = testing::run_palprig({"experiment", "run", "--protocol", rated_protocol(), "--participant", "sim:33",
                                         "--db", uri, "--journal", (dir / "journal.db").string(), "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), kPgSchemaVersion);
  EXPECT_EQ(rating_digest(uri, "'sim:31', 'sim:32'"), old_trials);  // every older trial, value for value
  EXPECT_EQ(testing::pg_scalar(uri,
                               "SELECT count(*) FROM trials t JOIN sessions s ON s.id = t.session_id "
                               "JOIN participants p ON p.id = s.participant_id WHERE p.code IN ('sim:31', 'sim:32') "
                               "AND (t.confidence IS NOT NULL OR t.stimulus_end_s IS NOT NULL)"),
            0);
  const std::int64_t rated_trials =
      testing::pg_scalar(uri,
                         "SELECT count(*) FROM trials t JOIN sessions s ON s.id = t.session_id JOIN participants p ON "
                         "p.id = s.participant_id WHERE p.code = 'sim:33' AND t.answered = 1");
  ASSERT_GT(rated_trials, 0);
  EXPECT_EQ(testing::pg_scalar(uri,
                               "SELECT count(*) FROM trials WHERE confidence BETWEEN 1 AND 4 AND "
                               "stimulus_end_s IS NOT NULL"),
            rated_trials);
  // The journal (SQLite) holds the same ratings.
  SqliteTrialStore journal(dir / "journal.db", TrialStore::Access::read_only);
  int journal_rated = 0;
  for (const StoredTrial& t : journal.read_trials(true)) journal_rated += t.confidence ? 1 : 0;
  EXPECT_EQ(journal_rated, rated_trials);

  // store copy server -> file and back carries both columns.
  const std::string back = (dir / "back.db").string();
  const auto down = testing::run_palprig({"store", "copy", "--from", uri, "--to", back});
  ASSERT_EQ(down.exit_code, 0) << down.err;
  EXPECT_EQ(rating_stats(back), rating_stats(uri));
  SqliteTrialStore copy(back, TrialStore::Access::read_only);
  int copied_rated = 0;
  for (const StoredTrial& t : copy.read_trials(true)) {
    copied_rated += t.confidence ? 1 : 0;
    if (t.participant == "sim:33") {
      EXPECT_TRUE(t.stimulus_end_s.has_value());
    }
  }
  EXPECT_EQ(copied_rated, rated_trials);
  const std::string again = testing::fresh_database("rating_copy_up");
  const auto up = testing::run_palprig({"store", "copy", "--from", back, "--to", again});
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_EQ(rating_stats(again), rating_stats(uri));
  EXPECT_EQ(testing::pg_scalar(again, "SELECT count(*) FROM trials WHERE confidence IS NOT NULL"), rated_trials);
}

}  // namespace
}  // namespace palprig
