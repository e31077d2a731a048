// The TrialStore interface as stats, export and sessions use it: the location picks the
// implementation, and what one trial commits is what the readers get back.
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "sessions/session_setup.hpp"
#include "store/trial_store.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

TEST(experiments_trial_store_interface, a_path_opens_an_sqlite_file_and_a_server_uri_goes_to_the_server) {
  ScratchDir dir;
  const std::string file = (dir / "t.db").string();
  {
    const auto store = open_trial_store(file, TrialStore::Access::read_write);
    EXPECT_EQ(store->location(), file);
    EXPECT_EQ(store->enrol("anna", false).number, 1);
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(file));
  const auto reader = open_trial_store(file, TrialStore::Access::read_only);
  EXPECT_EQ(reader->find_participant("anna")->number, 1);

  EXPECT_TRUE(is_server_store_location("postgresql://lab/palprig"));
  EXPECT_FALSE(is_server_store_location("postgresql.db"));
  // A server URI opens the PostgreSQL lab store; nothing listens on port 1, so
  // both accesses are refused inputs naming the server, before any journal or file is made.
  for (const auto access : {TrialStore::Access::read_only, TrialStore::Access::read_write}) {
    try {
      open_trial_store("postgresql://palprig@127.0.0.1:1/palprig", access);
      FAIL() << "an unreachable server was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "host 127.0.0.1 port 1 database palprig");
      EXPECT_EQ(e.where(), "connection");
    }
  }
  EXPECT_FALSE(std::filesystem::exists("postgresql:"));  // no file of that name was created
}

TEST(experiments_trial_store_interface, readers_get_back_what_a_trial_committed) {
  ScratchDir dir;
  const Protocol p = load_protocol(testing::protocols_dir() / "localisation_002.json");
  const auto store = open_trial_store((dir / "t.db").string(), TrialStore::Access::read_write);
  SessionRequest request;
  request.participant_code = "P1";
  const OpenedSession s = open_session(*store, p, request);
  TrialRecord r;
  r.planned = s.plan.trials[0];
  r.condition = "three-finger";
  r.mode = PresentationMode::scene;
  r.answered = true;
  r.response_time_s = 42.5;
  const auto& t = p.localisation.cases.at(0).tumors;
  r.marks = {{t[0].x_mm, t[0].y_mm}, {5, 5}};  // one hit, one false mark
  r.localisation = score_localisation(t, r.marks, p.localisation.tolerance_mm);
  store->commit_trial(s.session_id, r);

  const auto sessions = store->list_sessions();
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions[0].participant.code, "P1");
  EXPECT_EQ(sessions[0].status, "running");
  EXPECT_EQ(store->protocol_snapshot(s.session_id), p.snapshot);

  int seen = 0;
  store->scan_scored_trials(TrialFamily::localisation, true, [&](const ScoredTrial& trial) {
    ++seen;
    EXPECT_EQ(trial.session_id, s.session_id);
    EXPECT_EQ(trial.condition, "three-finger");
    EXPECT_DOUBLE_EQ(trial.response_time_s, 42.5);
    EXPECT_EQ(trial.false_marks, 1);
    ASSERT_EQ(trial.tumors.size(), t.size());
    int hits = 0;
    for (const ScoredTumor& tumor : trial.tumors) hits += tumor.outcome == Outcome::tp ? 1 : 0;
    EXPECT_EQ(hits, 1);
  });
  EXPECT_EQ(seen, 1);
  store->scan_scored_trials(TrialFamily::discrimination, true, [&](const ScoredTrial&) { ++seen; });
  EXPECT_EQ(seen, 1);

  const auto trials = store->read_trials(true);
  ASSERT_EQ(trials.size(), 1u);
  EXPECT_EQ(trials[0].participant, "P1");
  EXPECT_EQ(trials[0].mode, "scene");
  EXPECT_EQ(trials[0].false_marks, 1);
  ASSERT_EQ(trials[0].marks.size(), 2u);
  EXPECT_EQ(trials[0].marks[0].tumor, t[0].name);
  EXPECT_FALSE(trials[0].marks[1].tumor.has_value());
  EXPECT_DOUBLE_EQ(trials[0].marks[1].x_mm, 5.0);
  EXPECT_EQ(trials[0].tumor_outcomes.size(), t.size());
}

}  // namespace
}  // namespace palprig
