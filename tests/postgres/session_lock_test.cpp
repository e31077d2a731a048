// One process per session on the lab server (advisory lock + session_locks row), and the
// schema's second migration on a server that already holds trials. Real server (with_server.sh),
// real palprig processes, kill -9 for real.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "core/input_error.hpp"
#include "store/host_identity.hpp"
#include "store/postgres_schema.hpp"
#include "store/postgres_session_rows.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/sqlite_db.hpp"
#include "store/sqlite_session_rows.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/postgres/pg_test_support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::ChildProcess;
using testing::ScratchDir;

constexpr int kLockTrialsPerSession = 32;  // data/protocols/discrimination_002.json

std::string protocol_file() { return (testing::protocols_dir() / "discrimination_002.json").string(); }

std::vector<std::string> run_args(const std::string& participant, const std::string& uri, const std::string& journal,
                                  std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"experiment", "run",  "--protocol", protocol_file(), "--participant",
                                participant,  "--db", uri,          "--journal",     journal};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

bool wait_for_output(ChildProcess& child, const std::string& text, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (child.out().find(text) == std::string::npos && std::chrono::steady_clock::now() < end) {
    if (!child.pump(50)) break;
  }
  return child.out().find(text) != std::string::npos;
}

// A session created through the store (enrolled, planned, claimed), as open_session does.
std::int64_t start_session(TrialStore& store, const std::string& code) {
  const Protocol protocol = load_protocol(protocol_file());
  const ParticipantRecord who = store.enrol(code, true);
  const SessionPlan plan = make_session_plan(protocol, who.number, 7);
  return store.create_session(who, protocol, plan, SessionSetup{"rig-test", "simulated", "", nullptr, "."});
}

std::string refusal(TrialStore& store, std::int64_t session_id) {
  try {
    store.claim_session(session_id);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PostgresSessionLock, ASecondClaimNamesTheHolderAndTheLockEndsWithItsConnection) {
  PALPRIG_REQUIRE_PG_SERVER();
  const std::string uri = testing::fresh_database("lock_claims");
  auto first = std::make_unique<PostgresTrialStore>(parse_pg_target(uri), TrialStore::Access::read_write);
  PostgresTrialStore second(parse_pg_target(uri), TrialStore::Access::read_write);
  const std::int64_t session = start_session(*first, "sim:1");  // created, hence claimed

  const std::string refused = refusal(second, session);
  EXPECT_NE(refused.find("process " + std::to_string(::getpid()) + " on " + this_host_name()), std::string::npos)
      << refused;
  EXPECT_NE(refused.find("pg_terminate_backend("), std::string::npos) << refused;
  EXPECT_THROW(second.refuse_if_running_elsewhere(session), InputError);
  EXPECT_NO_THROW(first->claim_session(session));  // its own claim again: still its own

  // The holder's connection ends without a word (as with kill -9 or a lost bench): the server
  // drops the lock, and the row it left behind no longer refuses anyone.
  const std::int64_t backend = first->connection().exec("SELECT pg_backend_pid()").integer(0, 0);
  PgConnection(parse_pg_target(uri)).exec("SELECT pg_terminate_backend(" + std::to_string(backend) + ")");
  for (int i = 0; i < 100 && testing::pg_scalar(uri, "SELECT count(*) FROM pg_stat_activity WHERE pid = " +
                                                         std::to_string(backend)) > 0;
       ++i) {
    ::usleep(20000);  // the terminated backend leaves pg_stat_activity (and its locks) shortly after
  }
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM session_locks"), 1);  // the stale row
  EXPECT_NO_THROW(second.claim_session(session));
  EXPECT_NO_THROW(second.refuse_if_running_elsewhere(session));
  first.reset();  // its destructor meets a dead connection and must not throw

  // Released: completion and release_session free the session for the next process.
  PostgresTrialStore third(parse_pg_target(uri), TrialStore::Access::read_write);
  EXPECT_NE(refusal(third, session), "");
  second.release_session(session);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM session_locks"), 0);
  EXPECT_NO_THROW(third.claim_session(session));
  third.complete_session(session);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM session_locks"), 0);
  const std::string completed = refusal(second, session);
  EXPECT_NE(completed.find("has just completed it"), std::string::npos) << completed;
}

TEST(PostgresSessionLock, TheSameParticipantStartedTwiceAtOnceGetsOneSession) {
  PALPRIG_REQUIRE_PG_SERVER();
  const std::string uri = testing::fresh_database("lock_twice");
  PostgresTrialStore first(parse_pg_target(uri), TrialStore::Access::read_write);
  PostgresTrialStore second(parse_pg_target(uri), TrialStore::Access::read_write);
  start_session(first, "sim:2");
  try {
    start_session(second, "sim:2");
    FAIL() << "a second unfinished session of one participant was created";
  } catch (const InputError& e) {
    // The first still runs it: the refusal names that process rather than suggesting --resume.
    EXPECT_NE(std::string(e.what()).find("process " + std::to_string(::getpid())), std::string::npos) << e.what();
  }
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions"), 1);
}

TEST(PostgresSessionLock, ASecondBenchIsRefusedWhileTheFirstRunsAndTakesOverAfterKill9) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string uri = testing::fresh_database("lock_benches");
  const std::string journal1 = (dir / "bench1.sqlite").string(), journal2 = (dir / "bench2.sqlite").string();
  ChildProcess first(run_args("sim:9", uri, journal1, {"--speed", "5"}));
  ASSERT_TRUE(wait_for_output(first, "trial 1/", 60)) << first.out();
  for (const std::vector<std::string>& extra : {std::vector<std::string>{}, std::vector<std::string>{"--resume"}}) {
    const auto second = testing::run_palprig(run_args("sim:9", uri, journal2, extra));
    EXPECT_EQ(second.exit_code, 2) << second.out << second.err;
    EXPECT_EQ(palprig::testing::count_lines(second.err), 1) << second.err;
    EXPECT_NE(second.err.find("process " + std::to_string(first.pid()) + " on " + this_host_name()), std::string::npos)
        << second.err;
  }
  ::kill(first.pid(), SIGKILL);  // its connection ends with it: the server drops the lock
  first.wait();
  // The same bench resumes (its journal holds what the server may not have yet).
  const auto resumed = testing::run_palprig(run_args("sim:9", uri, journal1, {"--resume", "--quiet"}));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), kLockTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(DISTINCT position) FROM trials"), kLockTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM session_locks"), 0);
}

// The trial columns a version-1 server has (every value of an older trial, compared across
// migrations that append columns).
std::string version1_trial_columns() {
  std::string s;
  for (std::size_t i = 0; i < kTrialConfidence; ++i) s += (i ? ", t." : "t.") + std::string(kTrialColumns[i].name);
  return s;
}

TEST(PostgresSchemaMigration, Version1ServerHoldingTrialsMigratesToVersion2AndKeepsEveryTrial) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  // Trials from real sessions, in a file ...
  const std::string file = (dir / "bench.db").string();
  for (const std::string participant : {"sim:21", "sim:22"}) {
    const auto run = testing::run_palprig(
        {"experiment", "run", "--protocol", protocol_file(), "--participant", participant, "--db", file, "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  // ... pushed onto a server whose schema is still version 1 (what an older palprig created).
  const std::string uri = testing::old_server_holding("migrate_1_2", 1, file);
  ASSERT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), 1);
  ASSERT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), 2 * kLockTrialsPerSession);
  ASSERT_EQ(
      testing::pg_scalar(uri, "SELECT count(*) FROM information_schema.tables WHERE table_name = 'session_locks'"), 0);
  const auto stats = [](const std::string& store) {
    const auto r = testing::run_palprig({"stats", "trials", store, "--by", "participant,condition,finger", "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  // Every stored value of the older trials, to compare after the migration.
  const auto digest = [&uri] {
    return PgConnection(parse_pg_target(uri))
        .exec("SELECT md5(string_agg(ROW(t.id, t.session_id, " + version1_trial_columns() +
              ")::text, '|' ORDER BY t.id)) FROM trials t JOIN sessions s ON s.id = t.session_id "
              "JOIN participants p ON p.id = s.participant_id WHERE p.code IN ('sim:21', 'sim:22')")
        .text(0, 0);
  };
  const std::string old_trials = digest();
  // A reader opens the older server as it is (nothing is written) ...
  const std::string before = stats(uri);
  // The file was written by this palprig, with the stimulus ends (and reached times) a version-1 server cannot
  // hold: everything but the response time after the stimulus agrees.
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
  EXPECT_EQ(without_after(before), without_after(stats(file)));
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), 1);

  // ... a writer migrates it: a session runs (and is locked) on the migrated server.
  const auto run = testing::run_palprig({"experiment", "run", "--protocol", protocol_file(), "--participant", "sim:23",
                                         "--db", uri, "--journal", (dir / "journal.sqlite").string(), "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT max(version) FROM palprig_schema"), kPgSchemaVersion);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM palprig_schema"), kPgSchemaVersion);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM trials"), 3 * kLockTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri,
                               "SELECT count(*) FROM trials t JOIN sessions s ON s.id = t.session_id "
                               "JOIN participants p ON p.id = s.participant_id WHERE p.code IN ('sim:21', 'sim:22')"),
            2 * kLockTrialsPerSession);
  EXPECT_EQ(testing::pg_scalar(uri, "SELECT count(*) FROM session_locks"), 0);  // released at completion
  EXPECT_EQ(digest(), old_trials);                                              // the older trials, value for value
}

}  // namespace
}  // namespace palprig
