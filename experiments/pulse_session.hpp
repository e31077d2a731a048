#pragma once
// The pulse-localisation session on a rig: each trial presents its condition's scene under the
// participant's pen through the StimulusOutput (the tick's pulse stage renders the beat), waits
// for a mark, scores it (models/pulse_localisation: score_pulse_mark) and hands the record to
// on_trial. The protocol, order and records are study/pulse_*; the simulated participant is
// experiments/simulated_pulse_observer.hpp.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "experiments/participant.hpp"
#include "experiments/session_clock.hpp"
#include "experiments/stimulus_output.hpp"
#include "runtime/run_control.hpp"
#include "formats/scene_file.hpp"
#include "study/pulse_protocol.hpp"
#include "study/pulse_record.hpp"

namespace palprig {

class PulseParticipant {
 public:
  virtual ~PulseParticipant() = default;
  // Before the first trial and after a pause: true when the participant wants to go on (a
  // person's Ready). The simulated observer is always ready, so its sessions pass no time here.
  virtual bool ready(double /*t_s*/) { return true; }
  // Trial `position` begins on this scene (again from its start after a pause); returns the pen
  // the participant palpates with. An answer belongs to the position it was given for.
  virtual InputSource& trial_started(int position, const PulseCondition& condition, const Scene& scene, double t_s) = 0;
  virtual void feel(const FeltSample& sample) = 0;
  virtual std::optional<Mark> answer(double t_s) = 0;
  // The clock the session runs on, before the first trial (as Participant::session_clock).
  virtual void session_clock(const SessionClock&) {}
  // When the mark answer() just returned was given (session time), if before the pass that took
  // it (an input event's own time); none: at that pass.
  virtual std::optional<double> answer_given_at_s() const { return std::nullopt; }
};

// A trial about to be presented: what a front end needs to show its scene (a generated
// condition's scene is generated_pulse_scene(scene_seed, difficulty)).
struct PulseTrialStart {
  int position = 0;
  int condition = 0;  // index into protocol.conditions
  std::optional<std::uint64_t> scene_seed;
  double onset_s = 0;
};

struct PulseSessionOptions {
  std::uint64_t seed = 1;
  int start_position = 0;
  double period_s = 0.002;  // the pulse is a 72 BPM wave: service the rig often
  // The operator's handle: a stop request vents and stops (the trial in progress is not kept);
  // a pause, with the discrimination session's semantics (experiments/session_loop.hpp): vents
  // at once and holds the trial in progress, which is presented again from its start once the
  // pause is lifted and the participant is ready; a pause in the inter-trial interval (the trial
  // is committed) cuts it short. Nothing committed is lost. Null: none.
  const RunControl* control = nullptr;
  std::function<void(const PulseTrialRecord&)> on_trial;
  std::function<void(const PulseTrialStart&)> on_trial_started;
  // The session waits: `paused` true once a pause is taken (vented, holding); false while it
  // waits for the participant's ready (before the first trial and after a pause).
  std::function<void(int position, bool paused)> on_waiting;
};

struct PulseSessionResult {
  bool completed = false, stopped = false;
  std::string fault;
};

// scenes[i] belongs to protocol.conditions[i].
PulseSessionResult run_pulse_session(const PulseProtocol& protocol, const std::vector<SceneFile>& scenes,
                                     StimulusOutput& output, PulseParticipant& participant, SessionClock& clock,
                                     const PulseSessionOptions& options);

}  // namespace palprig
