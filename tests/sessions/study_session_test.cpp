// A study session through the session API (sessions/study_session.hpp), as the command line
// and the GUI call it: what the listener hears, what the store keeps, a resume, and the person
// at a terminal answering through a pipe.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <sstream>

#include "experiments/terminal_participant.hpp"
#include "core/input_error.hpp"
#include "sessions/study_session.hpp"
#include "store/trial_store.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

// Records what a front end would show; asks for a stop after `stop_after` commits.
class RecordingListener final : public SessionListener {
 public:
  explicit RecordingListener(RunControl* stop = nullptr, int stop_after = -1) : stop_(stop), stop_after_(stop_after) {}
  void session_started(const SessionStart& s) override { starts.push_back(s); }
  void trial_started(const PlannedTrial& t, const Condition&) override { started.push_back(t.position); }
  void trial_committed(const TrialRecord& t, int total) override {
    committed.push_back(t.planned.position);
    total_trials = total;
    if (stop_ && static_cast<int>(committed.size()) == stop_after_) stop_->request_stop();
  }
  void session_ended(const SessionEnd& e) override { ends.push_back(e); }

  std::vector<SessionStart> starts;
  std::vector<int> started, committed;
  std::vector<SessionEnd> ends;
  int total_trials = 0;

 private:
  RunControl* stop_;
  int stop_after_;
};

StudySessionRequest simulated_request(const ScratchDir& dir) {
  StudySessionRequest r;
  r.protocol_file = testing::protocols_dir() / "discrimination_002.json";
  r.participant_code = "sim:11";
  r.store_location = (dir / "s.db").string();
  r.rig_file = testing::source_dir() / "data" / "rigs" / "simulated.json";
  return r;
}

TEST(experiments_study_session, a_simulated_session_is_reported_and_stored_trial_by_trial) {
  ScratchDir dir;
  RecordingListener listener;
  const SessionEnd end = run_study_session(simulated_request(dir), {}, listener, RunControl{});
  EXPECT_TRUE(end.completed);
  ASSERT_EQ(listener.starts.size(), 1u);
  EXPECT_TRUE(listener.starts[0].simulated);
  EXPECT_FALSE(listener.starts[0].resumed);
  const int total = listener.starts[0].total_trials;
  EXPECT_GT(total, 0);
  EXPECT_EQ(end.committed_trials, total);
  ASSERT_EQ(static_cast<int>(listener.committed.size()), total);
  ASSERT_EQ(static_cast<int>(listener.started.size()), total);
  for (int i = 0; i < total; ++i) {
    EXPECT_EQ(listener.started[static_cast<std::size_t>(i)], i);
    EXPECT_EQ(listener.committed[static_cast<std::size_t>(i)], i);
  }
  ASSERT_EQ(listener.ends.size(), 1u);
  EXPECT_TRUE(listener.ends[0].completed);

  const auto store = open_trial_store((dir / "s.db").string(), TrialStore::Access::read_only);
  const auto sessions = store->list_sessions();
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions[0].status, "completed");
  EXPECT_EQ(sessions[0].participant.code, "sim:11");
  EXPECT_EQ(static_cast<int>(store->read_trials(true).size()), total);
}

TEST(experiments_study_session, a_stopped_session_resumes_where_it_stopped) {
  ScratchDir dir;
  RunControl stop;
  RecordingListener first(&stop, 3);
  const SessionEnd stopped = run_study_session(simulated_request(dir), {}, first, stop);
  EXPECT_FALSE(stopped.completed);
  EXPECT_TRUE(stopped.stopped);
  EXPECT_EQ(stopped.committed_trials, 3);

  // Starting anew over the unfinished session is refused; resuming continues at trial 4.
  RecordingListener refused;
  EXPECT_THROW(run_study_session(simulated_request(dir), {}, refused, RunControl{}), InputError);
  stop.restart();
  StudySessionRequest again = simulated_request(dir);
  again.resume = true;
  RecordingListener second;
  const SessionEnd end = run_study_session(again, {}, second, stop);
  EXPECT_TRUE(end.completed);
  ASSERT_EQ(second.starts.size(), 1u);
  EXPECT_TRUE(second.starts[0].resumed);
  EXPECT_EQ(second.starts[0].start_position, 3);
  ASSERT_FALSE(second.committed.empty());
  EXPECT_EQ(second.committed.front(), 3);
  EXPECT_EQ(end.committed_trials, second.starts[0].total_trials);
}

TEST(experiments_study_session, a_person_needs_a_front_end_that_can_ask_them) {
  ScratchDir dir;
  StudySessionRequest r = simulated_request(dir);
  r.participant_code = "P01";
  RecordingListener listener;
  try {
    run_study_session(r, {}, listener, RunControl{});
    FAIL() << "a person was accepted without a way to ask them";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "participant");
  }
  EXPECT_TRUE(listener.starts.empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "s.db"));  // refused before the store was opened
}

TEST(experiments_terminal_participant, typed_lines_become_answers_and_q_stops) {
  const Protocol p = load_protocol(testing::protocols_dir() / "discrimination_002.json");
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::ostringstream prompts;
  RunControl stop;
  TerminalParticipant person(p, prompts, stop, fds[0]);
  EXPECT_FALSE(person.ready(0));  // nothing typed yet: never blocks
  EXPECT_NE(prompts.str().find("Ready?"), std::string::npos);
  const std::string typed = "\n23\nx\n0\nq\n";
  ASSERT_EQ(::write(fds[1], typed.data(), typed.size()), static_cast<ssize_t>(typed.size()));
  EXPECT_TRUE(person.ready(0));
  const auto a = person.answer(0);
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->tumor_under, (FingerFlags{false, true, true}));
  EXPECT_FALSE(person.answer(0).has_value());  // "x" is refused with a hint
  EXPECT_NE(prompts.str().find("Please type finger numbers"), std::string::npos);
  const auto none = person.answer(0);
  ASSERT_TRUE(none.has_value());
  EXPECT_EQ(none->tumor_under, (FingerFlags{false, false, false}));
  EXPECT_FALSE(stop.stop_requested());
  EXPECT_FALSE(person.answer(0).has_value());  // "q"
  EXPECT_TRUE(stop.stopped_by_operator());
  ::close(fds[0]);
  ::close(fds[1]);
}

}  // namespace
}  // namespace palprig
