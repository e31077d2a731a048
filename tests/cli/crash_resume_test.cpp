// The crash-safety promise, on a real process: SIGKILL a running `palprig experiment run`
// mid-session; every trial it reported as done is in the database (at most the trial in
// progress is lost), the database is intact, and --resume continues at the next trial of the
// stored order and completes the session.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ChildProcess;
using testing::ScratchDir;

int reported_trials(const std::string& out) {
  // A trial's line is printed after its transaction committed; count complete lines only.
  int n = 0;
  std::size_t pos = 0;
  while ((pos = out.find("\ntrial ", pos)) != std::string::npos) {
    if (out.find('\n', pos + 1) != std::string::npos) ++n;
    ++pos;
  }
  return n;
}

std::int64_t scalar(SqliteTrialStore& store, const std::string& sql) {
  auto q = store.database().prepare(sql);
  return q.step() ? q.integer(0) : -1;
}

TEST(experiments_crash_resume, sigkill_mid_session_loses_at_most_the_trial_in_progress) {
  ScratchDir dir;
  const std::string db = (dir / "crash.db").string();
  const std::string protocol = (testing::protocols_dir() / "discrimination_002.json").string();
  int reported = 0;
  {
    // 50 times real time: a session of about 4.5 simulated minutes takes a few seconds.
    ChildProcess child(
        {"experiment", "run", "--protocol", protocol, "--participant", "sim:5", "--db", db, "--speed", "50"});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (reported_trials(child.out()) < 5 && std::chrono::steady_clock::now() < deadline) child.pump(50);
    ASSERT_GE(reported_trials(child.out()), 5) << "the session did not get going: " << child.out();
    ASSERT_EQ(::kill(child.pid(), SIGKILL), 0);
    EXPECT_EQ(child.wait(), 128 + SIGKILL);
    while (child.pump(0)) {}
    reported = reported_trials(child.out());
  }
  std::int64_t committed = 0;
  {
    SqliteTrialStore store(db, TrialStore::Access::read_only);
    auto check = store.database().prepare("PRAGMA integrity_check");
    ASSERT_TRUE(check.step());
    EXPECT_EQ(check.text(0), "ok");
    committed = scalar(store, "SELECT count(*) FROM trials");
    EXPECT_GE(committed, reported) << "a trial reported as done was lost";
    EXPECT_LE(committed, reported + 1) << "more than the trial in progress was committed unreported";
    EXPECT_LT(committed, 32) << "the kill came too late to test anything";
    EXPECT_EQ(scalar(store, "SELECT max(position) FROM trials"), committed - 1) << "committed trials are contiguous";
    EXPECT_EQ(scalar(store, "SELECT count(*) FROM sessions WHERE status = 'running'"), 1);
    // Every committed trial is whole: scored on all three fingers.
    EXPECT_EQ(scalar(store,
                     "SELECT count(*) FROM trials WHERE answered = 1 AND (outcome1 IS NULL OR outcome2 IS NULL "
                     "OR outcome3 IS NULL)"),
              0);
  }

  const auto resumed = testing::run_palprig(
      {"experiment", "run", "--protocol", protocol, "--participant", "sim:5", "--db", db, "--resume", "--quiet"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("resumed at trial " + std::to_string(committed + 1)), std::string::npos) << resumed.out;

  SqliteTrialStore store(db, TrialStore::Access::read_only);
  EXPECT_EQ(scalar(store, "SELECT count(*) FROM trials"), 32);
  EXPECT_EQ(scalar(store, "SELECT count(DISTINCT position) FROM trials"), 32);
  EXPECT_EQ(scalar(store, "SELECT count(*) FROM sessions"), 1);
  EXPECT_EQ(scalar(store, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
  // The resumed part followed the stored order exactly.
  EXPECT_EQ(scalar(store,
                   "SELECT count(*) FROM trials t JOIN planned_trials p ON p.session_id = t.session_id AND "
                   "p.position = t.position WHERE p.combination = t.combination AND p.condition = t.condition "
                   "AND p.practice = t.practice"),
            32);
}

}  // namespace
}  // namespace palprig
