#pragma once
// A trainee's next training session as one library call, for `palprig train next` and the
// window's Training view: run at their present level (or resume the one they left). Where a
// trainee stands, their curves and benchmarks are store/training_history.hpp (no rig needed).
//
// A training session is a localisation (or pulse) session whose protocol is made for it
// (study/training.hpp: plan_training_session, with cases the trainee never had), run through
// the one session call (run_study_session / run_pulse_study) and stored like any session; its
// training row (level, cases, scores, benchmark met) is kept beside it in the same store
// (store/trial_store.hpp), so `store copy` and the lab server carry a trainee's history to any rig.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sessions/pulse_study.hpp"
#include "sessions/study_session.hpp"
#include "store/training_history.hpp"
#include "study/curriculum.hpp"
#include "study/training.hpp"

namespace palprig {

// What the next session of a trainee is, before it runs.
struct TrainingPlanView {
  std::string trainee, curriculum;
  int level = 0;
  std::string level_name;
  int session_number = 0;          // the trainee's session in this curriculum, 1-based
  bool resumed = false;            // the unfinished session is continued
  std::vector<std::string> cases;  // case names, in order (for a resumed session: its cases)
  bool pulse = false;
};

struct TrainingRequest {
  std::filesystem::path curriculum_file;
  std::string trainee;
  std::string store_location;
  std::filesystem::path journal_file;  // a postgresql:// store: the bench journal
  // "sim:SEED": a simulated trainee answers (a pilot), learning as the curriculum's pilot says;
  // empty: the trainee themself (a person, through the front end's person factory).
  std::string participant;
  // With sim:SEED: a fixed skill instead of the pilot's rising one (1: fully skilled, a simulated
  // expert for a benchmark).
  std::optional<double> simulated_skill;
  std::optional<std::string> level;  // run this level instead of the present one (experts, a benchmark)
  std::filesystem::path rig_file, calibration_file, telemetry_file;
  double speed = 0;              // simulated trainee: 0 as fast as simulated time allows, else times real time
  bool person_palpates = false;  // the front end gives a person a pen (the window)
  TickObserver* tick_observer = nullptr;
  // The front end's opened rig (the window's), leased for the session (StudySessionRequest::rig).
  Rig* rig = nullptr;
};

// The front end's part: who answers when the trainee is a person, what it is told.
struct TrainingFrontEnd {
  PersonFactory person;                                  // localisation levels; empty: a person is refused
  PulsePersonFactory pulse_person;                       // pulse levels
  SessionListener* listener = nullptr;                   // localisation levels' session events
  PulseSessionListener* pulse_listener = nullptr;        // pulse levels' session events
  std::function<void(const TrainingPlanView&)> planned;  // the session about to run (nothing moved yet)
};

struct TrainingOutcome {
  TrainingPlanView plan;
  SessionEnd end;
  bool scored = false;  // the session completed and was scored
  SessionScores scores;
  BenchmarkResult benchmark;
  TrainingStanding before, after;
};

// The trainee's next session, planned and nothing run yet: what the front end shows before it
// starts (the window sets its participant screen up with `protocol`). Refused (InputError,
// nothing stored or moved) for a curriculum that does not load, a trainee not enrolled in it, a
// trainee who passed every level (unless a level is asked for), or a pulse level on the lab
// server (pulse trials are kept in SQLite files only). An unfinished session of the trainee is
// the one planned (resumed). Reads the store; writes only to score a session whose process ended
// after it completed, or to note as the trainee's a session started without its training row.
struct PreparedTraining {
  Curriculum curriculum;
  std::filesystem::path curriculum_file;  // absolute
  TrainingPlanView plan;
  nlohmann::json protocol;        // the session's protocol document (study/protocol.hpp or pulse_protocol.hpp)
  std::vector<std::string> keys;  // the cases' keys, in order
  std::optional<TrainingSessionRecord> unfinished;
  int cases_practised = 0;  // by the trainee before this session (the pilot's learning)
  std::optional<std::uint64_t> simulated_seed;
};
PreparedTraining prepare_training_session(const TrainingRequest& request);

// Runs a prepared session: the front end's `planned` is told, the session runs through
// run_study_session / run_pulse_study (a person without a front end that can ask them is refused
// there), and a completed session is scored against its level's benchmark. `control`: the
// operator's stop and pause, as run_study_session's.
TrainingOutcome run_training_session(const TrainingRequest& request, const PreparedTraining& prepared,
                                     const TrainingFrontEnd& front, const RunControl& control);
// Both in one call (`palprig train next`).
TrainingOutcome run_training_session(const TrainingRequest& request, const TrainingFrontEnd& front,
                                     const RunControl& control);

}  // namespace palprig
