#pragma once
// TrialStore: where a study's participants, sessions and trials live (docs/architecture.md, "Data"), as an
// interface, so the session code, stats and export do not care whether the store is an SQLite
// file (SqliteTrialStore, store/sqlite_trial_store.hpp) or a lab server.
//
// Every implementation keeps these promises:
//   - commit_trial is one transaction: killing the process loses at most the trial in progress;
//   - a session's generated order is stored (create_session) before its first trial;
//   - trials of a session are committed in position order, so a resumed session continues at
//     StoredSession::completed_trials;
//   - refusals of the store itself (missing, foreign or newer store) throw InputError naming
//     the location.
// open_trial_store(location, access) picks the implementation from the location's form.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "study/trial_record.hpp"
#include "study/training_record.hpp"
#include "statistics/outcome.hpp"

namespace palprig {

struct ParticipantRecord {
  std::int64_t id = 0;
  std::string code;
  int number = 0;  // 1-based enrolment order
  bool simulated = false;
};

struct SessionSetup {
  std::string rig_id, rig_backend, calibration;
  nlohmann::json participant_model = nullptr;  // the simulated participant's parameters; null for people
  std::string protocol_dir = {};               // folder of the protocol file (resolves a scene path)
};

struct StoredSession {
  std::int64_t id = 0;
  ParticipantRecord participant;
  nlohmann::json protocol_snapshot;
  std::string protocol_dir;
  std::string status;  // "running" or "completed"
  SessionPlan plan;
  int completed_trials = 0;  // trials committed; the next position to run
};

// One line per session for readers (stats, export): no plan, no protocol text.
struct SessionOverview {
  std::int64_t id = 0;
  ParticipantRecord participant;
  std::string protocol_name, task, bids_task;
  std::string status;
};

// Which trials a scan returns: discrimination (finger values) or localisation (scene) trials.
enum class TrialFamily { discrimination, localisation };

struct ScoredTumor {
  std::string_view tumor;
  Outcome outcome = Outcome::fn;  // TP: detected, FN: missed
};

// The scoring columns of one trial, as `stats trials` reads them. Views are valid only during
// the visitor call that receives them.
struct ScoredTrial {
  std::int64_t trial_id = 0, session_id = 0;
  std::string_view condition;
  std::optional<std::string_view> combination_label;  // discrimination; absent for localisation
  bool answered = false;
  double response_time_s = 0;      // NaN when none was stored
  double rt_after_stimulus_s = 0;  // from the stimulus end to the answer; NaN when unknown
  double rt_from_reached_s = 0;    // from when the stimulus reached the fingers to the answer; NaN when unknown
  std::optional<int> confidence;   // the rating, when asked and given
  std::array<std::optional<Outcome>, kFingerCount> finger_outcomes{};  // discrimination, when answered
  std::span<const ScoredTumor> tumors;                                 // localisation, when answered
  std::int64_t false_marks = 0;                                        // localisation, when answered
  // Localisation: the case palpated ("" in trials stored before the column: the session's one
  // scene) and how many tumors it holds (none: unknown, stored before the column).
  std::string_view case_name;
  std::optional<int> case_tumors;
};

struct StoredMark {
  int mark = 0;  // 0-based, in the order marked
  double x_mm = 0, y_mm = 0;
  std::optional<std::string> tumor;  // the tumor it hit; none for a false mark
};

// One stored trial with its session and participant, as export writes it. Text columns that
// were stored empty read back as "" (truth, answer, combination label, outcomes).
struct StoredTrial {
  std::string participant;
  bool simulated = false;
  int participant_number = 0;
  std::int64_t session = 0;
  std::string protocol, task, bids_task;
  std::int64_t id = 0;
  int position = 0, block = 0;
  std::string condition, mode;
  bool practice = false;
  int combination = -1;
  std::string combination_label;
  std::array<std::optional<double>, kFingerCount> stimulus_kPa{}, felt_kPa{};
  std::string truth, answer;  // "010"; answer empty when unanswered
  bool answered = false;
  std::optional<double> response_time_s;
  double onset_s = 0;
  std::optional<double> stimulus_end_s;       // NULL in stores older than the column
  std::optional<double> rt_after_stimulus_s;  // response_time_after_stimulus_s; none when not answered or unknown
  std::optional<double> stimulus_reached_s;   // NULL: never reached, a scene, or a store older than the column
  std::optional<double> rt_from_reached_s;    // response_time_from_reached_s; none when not answered or unknown
  std::optional<int> confidence;
  std::array<std::string, kFingerCount> outcome{};  // "TP", "FN", "TN", "FP" or ""
  std::optional<std::int64_t> false_marks;
  std::string completed_utc;
  std::vector<std::pair<std::string, std::string>> tumor_outcomes;  // localisation: (tumor, TP|FN), by tumor
  std::vector<StoredMark> marks;                                    // localisation, by mark
  // Localisation: the case (none in trials stored before the columns).
  std::optional<std::string> case_name, case_difficulty;
  std::optional<std::uint64_t> case_seed;
  std::optional<int> case_tumors;
};

class TrialStore {
 public:
  enum class Access { read_only, read_write };

  virtual ~TrialStore() = default;
  TrialStore() = default;
  TrialStore(const TrialStore&) = delete;
  TrialStore& operator=(const TrialStore&) = delete;

  // The file or address the store was opened from, for messages (never a password).
  virtual const std::string& location() const noexcept = 0;

  // --- participants
  // The participant of this code, enrolled with the next number when new.
  virtual ParticipantRecord enrol(const std::string& code, bool simulated) = 0;
  virtual std::optional<ParticipantRecord> find_participant(const std::string& code) = 0;

  // --- sessions
  // The session of this participant and protocol that was started but not completed.
  virtual std::optional<std::int64_t> find_unfinished_session(const ParticipantRecord& who,
                                                              const std::string& protocol_name) = 0;
  // Stores the session, its protocol snapshot and its whole planned order in one transaction;
  // refuses (InputError) when this participant already has an unfinished session with this
  // protocol (e.g. one another process created a moment ago). The new session is claimed.
  virtual std::int64_t create_session(const ParticipantRecord& who, const Protocol& protocol, const SessionPlan& plan,
                                      const SessionSetup& setup) = 0;
  // Throws InputError when there is no such session or its trials are not positions 0..n-1.
  // One process per session: claiming refuses (InputError) a session a live process holds or
  // that was completed; a holder that died is stale and taken over. Released by
  // complete_session, release_session and the store's destructor.
  virtual void claim_session(std::int64_t session_id) = 0;
  // The refusal claim_session would give, without claiming.
  virtual void refuse_if_running_elsewhere(std::int64_t session_id) = 0;
  virtual void release_session(std::int64_t session_id) = 0;
  virtual StoredSession load_session(std::int64_t session_id) = 0;
  virtual void complete_session(std::int64_t session_id) = 0;

  // --- trials
  // One transaction per trial (the crash-safety promise).
  virtual void commit_trial(std::int64_t session_id, const TrialRecord& trial) = 0;
  // Many trials in one transaction (imports, benchmarks, tests).
  virtual void commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials) = 0;

  // --- reading (stats, export)
  virtual std::vector<SessionOverview> list_sessions() = 0;
  // The protocol file as it was stored with the session.
  virtual nlohmann::json protocol_snapshot(std::int64_t session_id) = 0;
  // Calls `visit` for every trial of the family in commit order, practice trials only when
  // asked. Streams: a million trials are never held in memory at once.
  virtual void scan_scored_trials(TrialFamily family, bool include_practice,
                                  const std::function<void(const ScoredTrial&)>& visit) = 0;
  // Every trial (practice ones when asked), ordered by participant number, session, position.
  virtual std::vector<StoredTrial> read_trials(bool include_practice) = 0;
  // One session's trials (practice included), by position: a console showing a session to
  // resume reads these, not the whole store.
  virtual std::vector<StoredTrial> read_session_trials(std::int64_t session_id) = 0;
  // The number the next enrolled participant gets (1 in an empty store).
  virtual int next_participant_number() = 0;

  // --- training (a store older than schema 5 / 6 read as it is has none)
  // Enrols the trainee in the curriculum (again: nothing changes).
  virtual void enrol_trainee(const std::string& code, const std::string& curriculum) = 0;
  virtual std::vector<TraineeRecord> trainees() = 0;
  // The trainee's training sessions (every curriculum), in the order they were started.
  virtual std::vector<TrainingSessionRecord> training_sessions(const std::string& trainee) = 0;
  // In one transaction: the session noted as the trainee's (running) and its cases reserved for
  // them; refuses (InputError) a case this trainee was given before.
  virtual void begin_training_session(const TrainingSessionRecord& record) = 0;
  virtual void complete_training_session(std::int64_t session_id, const nlohmann::json& scores, bool met_benchmark) = 0;
};

// Opens the store at `location`. Today: a path is an SQLite file (created with its schema when
// read_write and missing). A `postgresql://` or `postgres://` URI names a PostgreSQL store; a
// build without it refuses the URI with InputError. read_only refuses a missing store.
std::unique_ptr<TrialStore> open_trial_store(const std::string& location, TrialStore::Access access);

// True when `location` is a URI of a server store rather than a file path.
bool is_server_store_location(std::string_view location) noexcept;

}  // namespace palprig
