#pragma once
// A study session end to end, as `palprig experiment run` and the GUI both start it: files
// loaded and checked, the rig opened and vented, the session started or resumed in the trial
// store, the participant made, every trial committed as it completes, the rig vented and
// closed at the end. What happens is reported to a SessionListener; the front end only shows
// it.
//
// Order of refusals: every file and the participant code are checked, and the store opened (a
// lab server that cannot be reached is refused here), before the rig is opened (InputError);
// the rig is opened before the session is stored, so an unreachable device leaves no empty
// session behind.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "experiments/participant.hpp"
#include "study/protocol.hpp"
#include "experiments/simulated_participant.hpp"
#include "study/trial_record.hpp"
#include "experiments/trial_runner.hpp"
#include "runtime/run_control.hpp"
#include "store/trial_store.hpp"

namespace palprig {

class TickObserver;  // controller/loop_runner.hpp
class Rig;           // controller/rig_lease.hpp

struct StudySessionRequest {
  std::filesystem::path protocol_file;
  // The protocol as a document instead of read from protocol_file (which then names it in
  // messages and resolves its relative paths): a training session's protocol, made for it
  // (sessions/training_session.hpp).
  std::optional<nlohmann::json> protocol_document;
  std::string participant_code;            // a person's code, or sim:SEED for the simulated observer
  std::string store_location;              // trial store (open_trial_store): SQLite file, created when missing,
                                           // or the lab's postgresql:// server
  std::filesystem::path journal_file;      // postgresql:// store: the bench journal; empty: default_journal_file()
  std::filesystem::path rig_file;          // the rig the stimuli go to
  std::filesystem::path calibration_file;  // empty: paper 002's models
  bool resume = false;                     // continue the unfinished session of participant and protocol
  std::optional<std::uint64_t> seed;       // of the generated order; default: derived from participant and protocol
  double speed = 0;  // simulated participant: 0 = as fast as possible on simulated time, else times real time
  SimulatedObserverModel model;  // simulated participant's parameters (its seed comes from sim:SEED)
  // The simulated observer answers for participant_code (a pilot trainee's code) with this
  // seed, as sim:SEED would; none: only a sim:SEED code is simulated.
  std::optional<std::uint64_t> simulated_seed;
  bool person_palpates = false;  // the front end gives a person a pen (GUI); a terminal does not
  // Every rig tick of the session (target, setpoint, monitor per finger, pen, faults) as
  // `palprig run --telemetry` writes it (.bin: binary, else CSV), on the session clock that
  // the stored onset_s of each trial uses. Empty: none. An existing non-empty file is refused
  // (a resumed session's earlier recording is never overwritten).
  std::filesystem::path telemetry_file;
  // Every rig tick of the session is also handed to this observer (wait-free, on the session
  // thread; it must outlive the session): the window's live gauges and traces. Null: none.
  TickObserver* tick_observer = nullptr;
  // The front end's opened rig (the window's), leased for the session; it must outlive the
  // session. Null: the session opens rig_file itself.
  Rig* rig = nullptr;
};

// Known once the session is opened in the store.
struct SessionStart {
  std::string protocol_name;
  ParticipantRecord participant;
  std::int64_t session_id = 0;
  bool resumed = false;
  int start_position = 0;  // the first trial to run (0-based)
  int total_trials = 0;
  std::uint64_t seed = 0;
  bool simulated = false;
  bool real_time_hardware = false;  // a hardware rig: the session runs on the wall clock
  int pushed_from_journal = 0;      // lab store: trials an earlier run left in the journal, pushed at the start
  // The steady_clock (CLOCK_MONOTONIC) moment of session time 0 when the session runs in real
  // time at speed 1 (a person's session), so a front end or a benchmark can place the stored
  // onsets on the clock its input events are stamped on; none on simulated or scaled time.
  std::optional<std::chrono::steady_clock::time_point> clock_origin;
};

struct SessionEnd {
  bool completed = false;  // every planned trial committed; the session is marked completed
  bool stopped = false;    // a stop was requested; committed trials kept, resumable
  std::string fault;       // non-empty when the rig faulted (channels vented); resumable
  // After a fault: "the last 2000 ticks before it: FILE" (beside the telemetry file, else beside
  // the store), or why that file could not be written.
  std::string fault_record;
  int committed_trials = 0;  // in the store for this session, including those before a resume
  int total_trials = 0;
  // Lab store: journal commits the server has not confirmed after a short wait at the end
  // (kept in the journal, pushed by the next session or `palprig store sync`).
  std::int64_t unpushed_trials = 0;
  std::filesystem::path journal_file;
  // The request's telemetry file when one was written; records written and dropped (a real-time
  // session drops rather than make the rig wait for the disk; a simulated one keeps all).
  std::filesystem::path telemetry_file;
  std::uint64_t telemetry_records = 0, telemetry_dropped = 0;
};

// What a front end shows. Calls come from the thread running the session.
class SessionListener {
 public:
  virtual ~SessionListener() = default;
  virtual void session_started(const SessionStart&) {}
  // The runner's state changes and stimulus changes (a break is RunnerState::rest).
  virtual void runner_event(const RunnerEvent&) {}
  // A trial begins: its stimulus is about to be presented.
  virtual void trial_started(const PlannedTrial&, const Condition&) {}
  // A trial is committed to the store (its own transaction); `total` trials are planned.
  virtual void trial_committed(const TrialRecord&, int /*total*/) {}
  // After a committed trial, what the participant is told about it, when the protocol asks
  // for feedback (study/trial_feedback.hpp); never called otherwise.
  virtual void participant_feedback(int /*position*/, const std::string& /*text*/) {}
  virtual void session_ended(const SessionEnd&) {}
};

// Makes the person who answers once the protocol is known (terminal, GUI). Not called for a
// simulated participant (sim:SEED), which the session makes itself.
using PersonFactory = std::function<std::unique_ptr<Participant>(const Protocol&)>;

// Runs the session to its end, a stop (control.stop_requested()) or a rig fault. Throws
// InputError for refused input (before anything moves, or when the store refuses the session).
// control.paused() vents and holds the session at the trial in progress; unpaused, it goes on
// with it (experiments/session_loop.hpp).
SessionEnd run_study_session(const StudySessionRequest& request, const PersonFactory& person, SessionListener& listener,
                             const RunControl& control);

// The simulated observer's seed for a session resumed at `start_position`: moved on by the
// trials done, so the answers differ from those of the lost attempt.
std::uint64_t resumed_simulation_seed(std::uint64_t seed, int start_position) noexcept;

}  // namespace palprig
