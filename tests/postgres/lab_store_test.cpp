// The lab store against a real PostgreSQL server (one throwaway cluster per test, see
// with_server.sh): schema versioning, sessions from real palprig processes into the server
// through the bench journal, concurrent rigs, the server stopped mid-session, kill -9 and
// --resume, and copies between SQLite and PostgreSQL both ways.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "store/host_identity.hpp"
#include "store/postgres_schema.hpp"
#include "store/postgres_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/postgres/pg_test_support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::ChildProcess;
using testing::ScratchDir;

constexpr int kTrialsPerSession = 32;  // data/protocols/discrimination_002.json

int reported_trials(const std::string& out) {
  int n = 0;
  for (std::size_t pos = out.find("\ntrial "); pos != std::string::npos; pos = out.find("\ntrial ", pos + 1)) {
    if (out.find('\n', pos + 1) != std::string::npos) ++n;
  }
  return n;
}

// `stats trials --json` of a store, by every key so every group is compared.
std::string stats_json(const std::string& store) {
  const auto r = testing::run_palprig({"stats", "trials", store, "--by", "participant,condition,finger", "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

std::vector<std::string> session_args(const std::string& participant, const std::string& db,
                                      const std::string& journal) {
  return {"experiment",    "run",       "--protocol", palprig::testing::discrimination_protocol_file(),
          "--participant", participant, "--db",       db,
          "--journal",     journal};
}

void wait_for_trials(ChildProcess& child, int n) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (reported_trials(child.out()) < n && std::chrono::steady_clock::now() < deadline) child.pump(50);
  ASSERT_GE(reported_trials(child.out()), n) << "the session did not get going: " << child.out();
}

TEST(postgres_lab_store, schema_is_versioned_and_a_newer_one_is_refused) {
  PALPRIG_REQUIRE_PG_SERVER();
  const std::string uri = testing::fresh_database("schema_test");
  { PostgresTrialStore store(parse_pg_target(uri), TrialStore::Access::read_write); }
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), kPgSchemaVersion);
  // Opening again neither fails nor applies anything twice.
  { PostgresTrialStore store(parse_pg_target(uri), TrialStore::Access::read_write); }
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM palprig_schema"), kPgSchemaVersion);

  PgConnection(parse_pg_target(uri)).exec("INSERT INTO palprig_schema (version, applied_by) VALUES (99, 'future')");
  try {
    PostgresTrialStore store(parse_pg_target(uri), TrialStore::Access::read_only);
    FAIL() << "a newer schema was opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("newer palprig: schema 99"), std::string::npos) << e.what();
  }
  const auto cli = testing::run_palprig({"stats", "trials", uri});
  EXPECT_EQ(cli.exit_code, 2);
  EXPECT_NE(cli.err.find("palprig_schema.version"), std::string::npos) << cli.err;
}

TEST(postgres_lab_store, another_programs_database_is_refused) {
  PALPRIG_REQUIRE_PG_SERVER();
  const std::string uri = testing::fresh_database("foreign_test");
  PgConnection(parse_pg_target(uri)).exec("CREATE TABLE participants (name text)");
  EXPECT_THROW(PostgresTrialStore(parse_pg_target(uri), TrialStore::Access::read_write), InputError);
  EXPECT_EQ(
      testing::pg_scalar(uri, "SELECT count(*) FROM information_schema.tables WHERE table_name = 'palprig_schema'"), 0);
}

TEST(postgres_lab_store, same_seed_gives_the_same_statistics_in_sqlite_and_postgresql) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("same_stats");
  const std::string file = (dir / "bench.db").string();
  for (const std::string participant : {"sim:11", "sim:12"}) {
    const auto to_file =
        testing::run_palprig({"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(),
                              "--participant", participant, "--db", file, "--quiet"});
    ASSERT_EQ(to_file.exit_code, 0) << to_file.err;
    const auto to_server = testing::run_palprig(
        {"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(), "--participant",
         participant, "--db", uri, "--journal", (dir / "journal.db").string(), "--quiet"});
    ASSERT_EQ(to_server.exit_code, 0) << to_server.err;
    EXPECT_EQ(to_server.err, "");
  }
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), 2 * kTrialsPerSession);
  const std::string sqlite_stats = stats_json(file);
  EXPECT_NE(sqlite_stats.find("\"rows\""), std::string::npos) << sqlite_stats;
  EXPECT_EQ(stats_json(uri), sqlite_stats);
  // Every session says where it ran.
  PgConnection c(parse_pg_target(uri));
  const PgResult r = c.exec("SELECT DISTINCT host_name, rig_id FROM sessions");
  ASSERT_EQ(r.rows(), 1);
  EXPECT_EQ(r.text(0, 0), this_host_name());
  EXPECT_FALSE(r.text(0, 1).empty());
}

TEST(postgres_lab_store, three_rigs_at_once_all_land_complete) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("three_rigs");
  std::vector<std::unique_ptr<ChildProcess>> rigs;
  for (int i = 1; i <= 3; ++i) {
    auto args =
        session_args("sim:" + std::to_string(100 + i), uri, (dir / ("journal" + std::to_string(i) + ".db")).string());
    args.push_back("--quiet");
    rigs.push_back(std::make_unique<ChildProcess>(args));
  }
  for (auto& rig : rigs) {
    const auto r = rig->finish();
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 3);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), 3 * kTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(DISTINCT (session_id, position)) FROM trials"),
            3 * kTrialsPerSession);
  // Enrolment numbers were handed out one at a time: 1, 2, 3.
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(DISTINCT number) FROM participants WHERE number BETWEEN 1 AND 3"), 3);
}

TEST(postgres_lab_store, server_stopped_mid_session_the_session_finishes_and_every_trial_lands_once) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("server_stop");
  const std::string journal = (dir / "journal.db").string();
  auto args = session_args("sim:21", uri, journal);
  for (const char* a : {"--speed", "25"}) args.push_back(a);
  ChildProcess child(args);
  wait_for_trials(child, 4);
  ASSERT_EQ(testing::server_ctl("stop"), 0);
  wait_for_trials(child, 12);  // the session goes on while the server is down
  ASSERT_EQ(testing::server_ctl("start"), 0);
  const auto r = child.finish();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("completed: 32 trials"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("lab server unreachable"), std::string::npos) << r.err;
  // The server came back before the end: the pusher sent the backlog without being asked.
  EXPECT_NE(r.err.find("lab server back"), std::string::npos) << r.err;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), kTrialsPerSession);

  // The push (the pusher's, once the server was back; `store sync` pushes whatever is left).
  const auto sync = testing::run_palprig({"store", "sync", "--from", journal, "--to", uri});
  ASSERT_EQ(sync.exit_code, 0) << sync.err;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), kTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(DISTINCT position) FROM trials"), kTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
  // Pushing again stores nothing twice.
  const auto again = testing::run_palprig({"store", "sync", "--from", journal, "--to", uri});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find(" 0 trials pushed"), std::string::npos) << again.out;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), kTrialsPerSession);
  EXPECT_EQ(stats_json(uri), stats_json(journal));
}

TEST(postgres_lab_store, kill_9_mid_session_and_resume_loses_and_duplicates_nothing_on_the_server) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("kill_resume");
  const std::string journal = (dir / "journal.db").string();
  int reported = 0;
  {
    auto args = session_args("sim:31", uri, journal);
    for (const char* a : {"--speed", "50"}) args.push_back(a);
    ChildProcess child(args);
    wait_for_trials(child, 6);
    ASSERT_EQ(::kill(child.pid(), SIGKILL), 0);
    EXPECT_EQ(child.wait(), 128 + SIGKILL);
    while (child.pump(0)) {}
    reported = reported_trials(child.out());
  }
  ASSERT_LT(reported, kTrialsPerSession) << "the kill came too late to test anything";
  const auto resumed =
      testing::run_palprig({"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(),
                            "--participant", "sim:31", "--db", uri, "--journal", journal, "--resume", "--quiet"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  // It resumed after the last trial the bench ran, journal included.
  const auto at = resumed.out.find("resumed at trial ");
  ASSERT_NE(at, std::string::npos) << resumed.out;
  EXPECT_GE(std::stoi(resumed.out.substr(at + 17)), reported + 1) << resumed.out;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), kTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(DISTINCT position) FROM trials"), kTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(position) FROM trials"), kTrialsPerSession - 1);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions"), 1);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
}

TEST(postgres_lab_store, kill_9_while_the_server_is_down_then_resume_pushes_the_journal_first) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("kill_offline");
  const std::string journal = (dir / "journal.db").string();
  int reported = 0;
  {
    auto args = session_args("sim:32", uri, journal);
    for (const char* a : {"--speed", "25"}) args.push_back(a);
    ChildProcess child(args);
    wait_for_trials(child, 3);
    ASSERT_EQ(testing::server_ctl("stop"), 0);
    wait_for_trials(child, 9);  // these live only in the journal
    ASSERT_EQ(::kill(child.pid(), SIGKILL), 0);
    child.wait();
    while (child.pump(0)) {}
    reported = reported_trials(child.out());
  }
  ASSERT_LT(reported, kTrialsPerSession) << "the kill came too late to test anything";
  ASSERT_EQ(testing::server_ctl("start"), 0);
  const std::int64_t on_server_before = testing::pg_scalar(uri, "SELECT count(*) FROM trials");
  EXPECT_LT(on_server_before, reported) << "the journal had nothing unpushed: the test tests nothing";
  const auto resumed =
      testing::run_palprig({"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(),
                            "--participant", "sim:32", "--db", uri, "--journal", journal, "--resume", "--quiet"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("trials left in the journal"), std::string::npos) << resumed.out;
  const auto at = resumed.out.find("resumed at trial ");
  ASSERT_NE(at, std::string::npos) << resumed.out;
  EXPECT_GE(std::stoi(resumed.out.substr(at + 17)), reported + 1) << resumed.out;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), kTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(DISTINCT position) FROM trials"), kTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
  EXPECT_EQ(stats_json(uri), stats_json(journal));
}

TEST(postgres_lab_store, copy_sqlite_to_postgresql_and_back_keeps_every_trial_once) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("copy_both_ways");
  const std::string file = (dir / "bench.db").string(), back = (dir / "back.db").string();
  for (const std::string participant : {"sim:41", "sim:42"}) {
    const auto r =
        testing::run_palprig({"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(),
                              "--participant", participant, "--db", file, "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto up = testing::run_palprig({"store", "copy", "--from", file, "--to", uri});
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_NE(up.out.find("2 sessions (2 new), 64 trials copied"), std::string::npos) << up.out;
  const auto twice = testing::run_palprig({"store", "copy", "--from", file, "--to", uri});
  ASSERT_EQ(twice.exit_code, 0) << twice.err;
  EXPECT_NE(twice.out.find("2 sessions (0 new), 0 trials copied"), std::string::npos) << twice.out;
  const auto down = testing::run_palprig({"store", "copy", "--from", uri, "--to", back});
  ASSERT_EQ(down.exit_code, 0) << down.err;
  EXPECT_NE(down.out.find("64 trials copied"), std::string::npos) << down.out;

  const std::string original = stats_json(file);
  EXPECT_EQ(stats_json(uri), original);
  EXPECT_EQ(stats_json(back), original);
  // The export of the copy is the export of the original, byte for byte.
  for (const auto& [store, out] : {std::pair{file, dir / "x1"}, std::pair{back, dir / "x2"}}) {
    const auto r = testing::run_palprig({"export", store, "--out", out.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  std::ifstream a(dir / "x1" / "trials_long.csv"), b(dir / "x2" / "trials_long.csv");
  const std::string ta((std::istreambuf_iterator<char>(a)), {}), tb((std::istreambuf_iterator<char>(b)), {});
  EXPECT_FALSE(ta.empty());
  EXPECT_EQ(ta, tb);
}

}  // namespace
}  // namespace palprig
