#pragma once
// A store for the analyst's suites (tests/cli/analyst_*_test.cpp, which build in the analyst-only
// build too): one discrimination session of paper 002's protocol written through the study floor
// alone (no rig, no session runner), committed as a session commits, one transaction per trial.
#include <filesystem>
#include <functional>

#include "store/sqlite_trial_store.hpp"
#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "tests/support/discrimination_trials.hpp"

namespace palprig::testing {

// DIR/analyst.db: participant P01, seed 7; every trial answered exactly but those whose planned
// position `answer_all` picks, answered with every finger.
inline std::filesystem::path write_analyst_store(const std::filesystem::path& dir,
                                                 const std::function<bool(int position)>& answer_all) {
  const Protocol p =
      load_protocol(std::filesystem::path(PALPRIG_SOURCE_DIR) / "data/protocols/discrimination_002.json");
  auto db = dir / "analyst.db";
  SqliteTrialStore store(db, TrialStore::Access::read_write);
  const ParticipantRecord who = store.enrol("P01", false);
  const SessionPlan plan = make_session_plan(p, who.number, 7);
  const std::int64_t id = store.create_session(who, p, plan, SessionSetup{});
  for (const PlannedTrial& planned : plan.trials)
    store.commit_trial(id, discrimination_trial(p, planned, answer_all(planned.position)));
  store.complete_session(id);
  return db;
}

}  // namespace palprig::testing
