#pragma once
// TrialRunner: the state machine of a session, with no knowledge of Qt, the terminal or the
// clock. The caller feeds it the time (seconds on a monotonic clock) and the participant's
// actions; it drives the StimulusOutput, times responses from stimulus onset (and notes when the
// stimulus ended, for the response time after the stimulus), scores answers
// and reports events and completed trials to a listener (the CLI, the GUI, the trial store).
//
//   ready ──begin──> present ──(stimulus over)──> respond ──(answer | timeout)──> inter_trial
//                       └────────────(answer)─────────────────────────────────────┘
//   inter_trial ──> present (next trial) | rest (break) ──> ready | done
//
// present   the stimulus is on: all three fingers (simultaneous), one finger after the other
//           (sequential: step, gap, step, gap, step) or the scene under the pen (localisation);
//           an answer is accepted at any time
// respond   the stimulus is off, the answer is still awaited (until response_timeout_s)
// inter_trial  vented pause; the trial has been handed to the listener (committed) on entry
// rest      a break of break_s (0: none), then ready waits for the participant
#include <functional>
#include <optional>
#include <vector>

#include "inputs/input_source.hpp"
#include "study/protocol.hpp"
#include "study/scoring.hpp"
#include "study/session_plan.hpp"
#include "experiments/stimulus_output.hpp"
#include "study/trial_record.hpp"

namespace palprig {

enum class RunnerState { ready, present, respond, inter_trial, rest, done };

const char* to_string(RunnerState s) noexcept;

// Whether a participant answers while the stimulus is still on: during a scene (localisation
// marks are made while palpating); during a simultaneous presentation when the protocol's
// timing.answer_during_stimulus says so (paper 002's three-finger trials stay until the answer);
// never during a sequence (answered after its last finger; an answer typed ahead is held by the
// session loop until then). The GUI enables its answer buttons by this same rule.
bool answers_during_presentation(const Protocol& protocol, PresentationMode mode) noexcept;

// A participant's answer: the fingers with a tumor (discrimination) or marks (localisation),
// and the confidence rating 1..levels when the protocol asks for one (handed over with the
// answer in one piece; the runner stores none that is out of range or not asked for).
struct Response {
  FingerFlags tumor_under{};
  std::vector<Mark> marks;
  std::optional<int> confidence;
  // When the participant gave the answer (session clock), if before it reached the runner: a
  // confidence rating is given after the finger answer, and an answer typed during a sequence
  // waits for its end. The response time is measured to this moment, not to the rating's.
  std::optional<double> given_at_s;
};

struct RunnerEvent {
  enum class Kind { state_changed, stimulus_changed, trial_completed };
  Kind kind = Kind::state_changed;
  RunnerState state = RunnerState::ready;
  double t_s = 0;
  int position = -1;     // the current trial's position, -1 when none
  FingerFlags active{};  // stimulus_changed: fingers carrying a stimulus now
};

class RunnerListener {
 public:
  virtual ~RunnerListener() = default;
  virtual void on_event(const RunnerEvent&) {}
  // Called once per completed trial, before the inter-trial pause starts; the trial store
  // commits here, so an exception stops the session without losing earlier trials.
  virtual void on_trial_completed(const TrialRecord& trial) = 0;
};

// Localisation: the case each trial palpates and its scene (experiments/trial_cases.hpp makes
// each one once: a listed scene, or a generated case made again from its seed).
class CaseSource {
 public:
  virtual ~CaseSource() = default;
  // Valid until the next call (the session presents one trial at a time).
  virtual const LocalisationCase& case_of(const PlannedTrial& trial) = 0;
  virtual const Scene& scene_of(const PlannedTrial& trial) = 0;
};

class TrialRunner {
 public:
  // Runs plan.trials from start_position (a resumed session starts past the committed ones).
  // For localisation, `cases` gives each trial's scene and `pen` is what the participant
  // palpates with.
  TrialRunner(const Protocol& protocol, const SessionPlan& plan, int start_position, StimulusOutput& output,
              RunnerListener& listener, CaseSource* cases = nullptr, InputSource* pen = nullptr);

  RunnerState state() const noexcept { return state_; }
  const PlannedTrial* current_trial() const noexcept;  // the trial presented or next; null when done
  int next_position() const noexcept { return position_; }
  int total_trials() const noexcept { return static_cast<int>(plan_.trials.size()); }
  FingerFlags active_fingers() const noexcept { return active_; }
  // What the fingers felt at the last advance() (the regulators' monitor readings).
  const ChannelPressures& felt_kPa() const noexcept { return felt_now_; }
  const Protocol& protocol() const noexcept { return protocol_; }
  // Localisation: the scene and case of the trial presented (null before the first, and for
  // discrimination).
  const Scene* current_scene() const noexcept { return scene_; }
  const LocalisationCase* current_case() const noexcept { return case_; }

  // The participant is ready: leaves `ready` and presents the next trial.
  void begin(double t_s);
  // Time passes: presentation steps, timeouts and pauses; also services the rig. Call often.
  void advance(double t_s);
  // True when an answer is taken now: in `respond`, and during the presentation of a condition
  // whose stimulus stays until the answer (answers_during_presentation).
  bool takes_answers() const noexcept;
  // While the participant completes an answer (a confidence rating after the finger answer),
  // the response timeout waits: a finger answer given in time is never lost to a slow rating.
  void hold_timeout(bool hold) noexcept { timeout_held_ = hold; }
  // An answer. Accepted when takes_answers() (returns true), ignored otherwise. A confidence
  // rating outside 1..levels (or one the protocol does not ask for) is refused: returns false
  // and the trial goes on, so no invalid rating is ever stored.
  bool respond(const Response& response, double t_s);
  // Stop now (operator or signal): vents; the trial in progress is not recorded.
  void abort(double t_s);
  // The experimenter pauses: vents now and holds the session in `ready`. A trial in progress
  // is not recorded and is presented again from its start by the next begin(); a trial
  // already committed (inter-trial pause) is not repeated; a break is cut short.
  void pause(double t_s);

 private:
  void enter(RunnerState s, double t_s);
  void start_trial(double t_s);
  void update_presentation(double t_s);
  void set_active(const FingerFlags& active, double t_s);
  void finish_trial(const Response* response, double t_s);
  void sample_felt(double t_s);
  void note_reached(const ChannelPressures& felt, double t_s);
  void end_stimulus(double planned_end_s, double t_s);
  double sequence_length_s() const;
  double presentation_length_s(PresentationMode mode) const;

  const Protocol& protocol_;
  const SessionPlan& plan_;
  StimulusOutput& output_;
  RunnerListener& listener_;
  CaseSource* cases_;
  const Scene* scene_ = nullptr;
  const LocalisationCase* case_ = nullptr;
  InputSource* pen_;

  RunnerState state_ = RunnerState::ready;
  int position_ = 0;
  double state_since_s_ = 0;
  double onset_s_ = 0;
  double stimulus_end_s_ = 0;
  bool timeout_held_ = false;  // when the runner left `present` (set on leaving it)
  FingerFlags active_{};
  std::array<double, kFingerCount> felt_sum_{};
  std::array<int, kFingerCount> felt_count_{};
  ChannelPressures felt_now_{};
  // When the stimulus reached the fingers (TrialRecord::stimulus_reached_s): each finger's last
  // monitor sample (to interpolate the half-level crossing between samples) and when the
  // finger's stimulus was commanded on (a crossing is never placed before it).
  double reached_s_ = 0;      // NaN until reached in the current presentation
  double felt_prev_t_s_ = 0;  // NaN before the first sample
  ChannelPressures felt_prev_{};
  std::array<double, kFingerCount> active_since_s_{};
};

}  // namespace palprig
