#pragma once
// Starting or resuming a session against the trial store, and the listener that commits each
// completed trial as it happens.
//
// New session: the participant is enrolled (numbered in order of enrolment), the order is
// generated from a seed (given, or derived from participant code and protocol name so the same
// pair always gets the same order) and stored with the protocol snapshot before trial 1.
// Resume: the unfinished session of that participant and protocol continues at the first
// trial not committed, with the stored protocol and order; a protocol file that changed since
// is refused. Starting anew while an unfinished session exists is refused (use --resume).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "experiments/trial_runner.hpp"
#include "store/trial_store.hpp"

namespace palprig {

struct OpenedSession {
  Protocol protocol;  // as stored with the session
  SessionPlan plan;
  std::int64_t session_id = 0;
  ParticipantRecord participant;
  int start_position = 0;
  bool resumed = false;
  int ordinal = 1;  // this participant's n-th session with this protocol (session_ordinal)
};

struct SessionRequest {
  std::string participant_code;
  bool simulated = false;
  bool resume = false;
  std::optional<std::uint64_t> seed;  // default: derived from participant and protocol
  SessionSetup setup;                 // rig, calibration, participant model
};

// Throws InputError (file, field, reason) for every refusal above.
OpenedSession open_session(TrialStore& store, const Protocol& protocol, const SessionRequest& request);

// The one new-or-resume assembly every task kind uses (discrimination and localisation here,
// threshold_setup and pulse_setup): the task says how far a stored session got, how to load
// one (keeping its own parts, e.g. the plan or the tracks' state) and how to create one.
struct StoredSessionHead {
  std::int64_t id = 0;
  ParticipantRecord participant;
  std::uint64_t seed = 0;
  int completed_trials = 0;
  nlohmann::json protocol_snapshot;
};
struct TaskSessionSteps {
  std::function<std::string(std::int64_t)> progress;    // "stopped after 12 of 32 trials"
  std::function<StoredSessionHead(std::int64_t)> load;  // the unfinished session being resumed
  std::function<std::int64_t(const ParticipantRecord&, std::uint64_t seed)> create;  // a new one
};
struct OpenedSessionHead {
  std::int64_t session_id = 0;
  ParticipantRecord participant;
  std::uint64_t seed = 0;
  int start_position = 0;
  bool resumed = false;
  int ordinal = 1;
};
// Resume (claimed; a changed protocol file refused) or start anew (participant enrolled, seed
// given or derived, session created); every refusal is an InputError.
OpenedSessionHead open_task_session(TrialStore& store, const std::string& protocol_name,
                                    const nlohmann::json& file_snapshot, const std::string& protocol_file,
                                    const SessionRequest& request, const TaskSessionSteps& steps);

// The rules above, shared by every task (discrimination, threshold, pulse): the unfinished
// session of this participant and protocol when resuming, claimed by this process (one process
// per session); nothing when starting anew. `progress` says how far an unfinished session got
// ("stopped after 12 of 32 trials") for the refusal to start it again.
std::optional<std::int64_t> session_to_resume(TrialStore& store, const std::string& participant_code,
                                              const std::string& protocol_name, bool resume,
                                              const std::function<std::string(std::int64_t)>& progress);

// On resume: refuses a protocol file that changed since the session started.
void refuse_changed_protocol(std::int64_t session_id, const nlohmann::json& stored_snapshot,
                             const nlohmann::json& file_snapshot, const std::string& protocol_file);

// Threshold and pulse sessions have their own SQLite tables; the PostgreSQL lab server stores
// discrimination and localisation trials only. Refuses a server location (InputError on the
// `store` field) before anything is opened, rather than creating a local file named after it.
void refuse_server_store_for_task_session(const std::string& store_location);

// The default seed of a participant's `ordinal`-th session with a protocol: the first is a hash
// of code and protocol name (the same pair always gets the same first order), each later one a
// different seed derived from it, so a trainee's second session of a rehearsal protocol is not
// the first again, and a fresh store gives the same sequence of sessions.
std::uint64_t default_session_seed(const std::string& participant_code, const std::string& protocol_name,
                                   int ordinal = 1);
// How many sessions (any status) this participant has in the store with this protocol name, of
// ids up to `up_to_session` when given: a new session's ordinal is this plus one.
int sessions_with_protocol(TrialStore& store, const std::string& participant_code, const std::string& protocol_name,
                           std::optional<std::int64_t> up_to_session = std::nullopt);
// The simulated participant's seed in its `ordinal`-th session with a protocol (the first keeps
// sim:SEED's seed, so stored pilots and documented figures stay as they were).
std::uint64_t session_simulation_seed(std::uint64_t sim_seed, int ordinal) noexcept;

// Commits each completed trial in its own transaction and forwards events to the UI.
class SessionRecorder final : public RunnerListener {
 public:
  SessionRecorder(TrialStore& store, std::int64_t session_id, std::function<void(const RunnerEvent&)> on_event = {},
                  std::function<void(const TrialRecord&)> on_trial = {})
      : store_(store), session_id_(session_id), on_event_(std::move(on_event)), on_trial_(std::move(on_trial)) {}

  void on_event(const RunnerEvent& e) override {
    if (on_event_) on_event_(e);
  }
  void on_trial_completed(const TrialRecord& trial) override {
    store_.commit_trial(session_id_, trial);
    ++committed_;
    if (on_trial_) on_trial_(trial);
  }
  int committed() const noexcept { return committed_; }

 private:
  TrialStore& store_;
  std::int64_t session_id_;
  std::function<void(const RunnerEvent&)> on_event_;
  std::function<void(const TrialRecord&)> on_trial_;
  int committed_ = 0;
};

}  // namespace palprig
