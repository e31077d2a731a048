// One trial database shared by several real `palprig experiment run` processes at once: a new
// file's schema is created once, one participant gets one session, and one session is run by
// one process. The loser gets one line naming the file and the other process, exit 2, and
// nothing stored is lost.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::ChildProcess;
using testing::CommandResult;
using testing::count_lines;
using testing::ScratchDir;

std::vector<std::string> run_args(const std::string& participant, const std::string& db,
                                  const std::vector<std::string>& extra = {}, bool quiet = true) {
  std::vector<std::string> args{
      "experiment",    "run",       "--protocol", palprig::testing::discrimination_protocol_file(),
      "--participant", participant, "--db",       db};
  if (quiet) args.push_back("--quiet");
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

std::int64_t scalar(const std::string& db, const std::string& sql) {
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
  auto q = store.database().prepare(sql);
  return q.step() ? q.integer(0) : -1;
}

// Starts all children before waiting on any, so they race for real.
std::vector<CommandResult> run_together(const std::vector<std::vector<std::string>>& commands) {
  std::vector<std::unique_ptr<ChildProcess>> children;
  children.reserve(commands.size());
  for (const auto& args : commands) children.push_back(std::make_unique<ChildProcess>(args));
  std::vector<CommandResult> results;
  results.reserve(children.size());
  for (auto& child : children) results.push_back(child->finish());
  return results;
}

bool wait_for_output(ChildProcess& child, const std::string& text, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (child.out().find(text) == std::string::npos && std::chrono::steady_clock::now() < end) {
    if (!child.pump(50)) break;
  }
  return child.out().find(text) != std::string::npos;
}

TEST(ConcurrentStore, ProcessesStartingOnOneNewFileCreateTheSchemaOnce) {
  for (int round = 0; round < 3; ++round) {
    ScratchDir dir;
    const std::string db = (dir / ("new" + std::to_string(round) + ".db")).string();
    std::vector<std::vector<std::string>> commands;
    for (int p = 1; p <= 5; ++p) commands.push_back(run_args("sim:" + std::to_string(10 * round + p), db));
    const auto results = run_together(commands);
    for (const auto& r : results) EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(scalar(db, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 5);
    EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials"), 5 * 32);
    EXPECT_EQ(scalar(db, "SELECT count(DISTINCT number) FROM participants"), 5);
  }
}

TEST(ConcurrentStore, SameParticipantStartedTwiceAtOnceGetsOneSession) {
  ScratchDir dir;
  const std::string db = (dir / "twice.db").string();
  // Real time x20: the session lasts well beyond the race, so the second start meets it running.
  auto results = run_together({run_args("sim:7", db, {"--speed", "20"}), run_args("sim:7", db, {"--speed", "20"})});
  // Both ran to their end: exactly one completed the session, the other was refused.
  int completed = 0, refused = 0;
  for (const auto& r : results) {
    if (r.exit_code == 0) ++completed;
    if (r.exit_code == 2) {
      ++refused;
      EXPECT_EQ(count_lines(r.err), 1) << r.err;
      EXPECT_NE(r.err.find(db), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("sim:7"), std::string::npos) << r.err;
    }
  }
  EXPECT_EQ(completed, 1) << results[0].err << results[1].err;
  EXPECT_EQ(refused, 1) << results[0].err << results[1].err;
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM sessions"), 1);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials"), 32);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM participants"), 1);
}

TEST(ConcurrentStore, TwoResumesAtOnceRunTheSessionOnce) {
  ScratchDir dir;
  const std::string db = (dir / "resume.db").string();
  {
    // A session stopped after a few trials (SIGTERM: a clean stop, resumable).
    ChildProcess first(run_args("sim:8", db, {"--speed", "50"}, false));
    ASSERT_TRUE(wait_for_output(first, "session 1", 30)) << first.out();
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (first.out().find("trial 3/") == std::string::npos && std::chrono::steady_clock::now() < end) first.pump(50);
    ::kill(first.pid(), SIGTERM);
    const auto r = first.finish();
    ASSERT_EQ(r.exit_code, 1) << r.err;
  }
  const std::int64_t kept = scalar(db, "SELECT count(*) FROM trials");
  ASSERT_GE(kept, 3);
  ASSERT_LT(kept, 32);

  auto results = run_together(
      {run_args("sim:8", db, {"--resume", "--speed", "20"}), run_args("sim:8", db, {"--resume", "--speed", "20"})});
  int completed = 0, refused = 0;
  for (const auto& r : results) {
    if (r.exit_code == 0) ++completed;
    if (r.exit_code == 2) {
      ++refused;
      EXPECT_EQ(count_lines(r.err), 1) << r.err;
      EXPECT_NE(r.err.find(db), std::string::npos) << r.err;
      EXPECT_EQ(r.err.find("UNIQUE"), std::string::npos) << r.err;
    }
  }
  EXPECT_EQ(completed, 1) << results[0].err << results[1].err;
  EXPECT_EQ(refused, 1) << results[0].err << results[1].err;
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials"), 32);
  EXPECT_EQ(scalar(db, "SELECT count(DISTINCT position) FROM trials"), 32);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM session_locks"), 0) << "the finished session still holds its lock";
}

TEST(ConcurrentStore, ASecondStartWhileTheFirstRunsNamesTheRunningProcess) {
  ScratchDir dir;
  const std::string db = (dir / "held.db").string();
  ChildProcess first(run_args("sim:9", db, {"--speed", "5"}));
  ASSERT_TRUE(wait_for_output(first, "session 1", 30)) << first.out();
  for (const std::vector<std::string>& extra : {std::vector<std::string>{}, std::vector<std::string>{"--resume"}}) {
    const auto second = testing::run_palprig(run_args("sim:9", db, extra));
    EXPECT_EQ(second.exit_code, 2) << second.out << second.err;
    EXPECT_EQ(count_lines(second.err), 1) << second.err;
    EXPECT_NE(second.err.find("process " + std::to_string(first.pid())), std::string::npos) << second.err;
  }
  ::kill(first.pid(), SIGKILL);  // a crash leaves its lock row behind ...
  first.wait();
  // ... which names a dead process: the next --resume takes the session over.
  const auto resumed = testing::run_palprig(run_args("sim:9", db, {"--resume"}));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM trials"), 32);
}

TEST(ConcurrentStore, ResumeRefusalsNameTheNextStep) {
  ScratchDir dir;
  const std::string db = (dir / "stopped.db").string();
  {
    ChildProcess first(run_args("sim:11", db, {"--speed", "50"}, false));
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (first.out().find("trial 2/") == std::string::npos && std::chrono::steady_clock::now() < end) first.pump(50);
    ::kill(first.pid(), SIGTERM);
    ASSERT_EQ(first.finish().exit_code, 1);
  }
  // Starting anew over the stopped session: it exists, and --resume continues it.
  const auto again = testing::run_palprig(run_args("sim:11", db));
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_EQ(count_lines(again.err), 1) << again.err;
  EXPECT_NE(again.err.find("already has an unfinished session"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("run the same command again with --resume"), std::string::npos) << again.err;
  EXPECT_EQ(again.err.find("no unfinished session"), std::string::npos) << "reads as if there were none: " << again.err;
  // --resume for someone with nothing to resume: say how to start.
  const auto none = testing::run_palprig(run_args("sim:12", db, {"--resume"}));
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("without --resume"), std::string::npos) << none.err;
}

// Threshold and pulse sessions keep their trials in tables of their own but are held the same
// way: a second start or --resume while the first process runs is refused naming it; after a
// kill -9 the --resume takes the session over and finishes it.
void expect_task_session_held_by_one_process(const std::string& protocol, const std::string& trial_table) {
  ScratchDir dir;
  const std::string db = (dir / "held.db").string();
  auto args = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> a{"experiment",    "run",   "--protocol", (testing::protocols_dir() / protocol).string(),
                               "--participant", "sim:9", "--db",       db,
                               "--quiet"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ChildProcess first(args({"--speed", "5"}));
  ASSERT_TRUE(wait_for_output(first, "session 1", 30)) << first.out() << first.err();
  for (const std::vector<std::string>& extra : {std::vector<std::string>{}, std::vector<std::string>{"--resume"}}) {
    const auto second = testing::run_palprig(args(extra));
    EXPECT_EQ(second.exit_code, 2) << protocol << ": " << second.out << second.err;
    EXPECT_EQ(count_lines(second.err), 1) << second.err;
    EXPECT_NE(second.err.find("process " + std::to_string(first.pid())), std::string::npos) << second.err;
  }
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM sessions"), 1) << "the refused start stored a session";
  ::kill(first.pid(), SIGKILL);
  first.wait();
  const auto resumed = testing::run_palprig(args({"--resume"}));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
  EXPECT_EQ(scalar(db, "SELECT count(*) FROM session_locks"), 0) << "a completed session keeps its lock row";
  EXPECT_EQ(scalar(db, "SELECT max(position) + 1 - count(*) FROM " + trial_table), 0) << "positions 0..n-1";
}

TEST(ConcurrentStore, AThresholdSessionIsHeldByOneProcess) {
  expect_task_session_held_by_one_process("threshold_1up3down.json", "threshold_trials");
}

TEST(ConcurrentStore, APulseSessionIsHeldByOneProcess) {
  expect_task_session_held_by_one_process("pulse_localisation_000.json", "pulse_trials");
}

}  // namespace
}  // namespace palprig
