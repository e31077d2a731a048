#pragma once
// Participant: who answers the trials. The session loop asks it, on every pass, whether it is
// ready to go on and whether it has answered, and tells it what the fingers feel. A person at
// the terminal (experiments/terminal_participant.hpp), the simulated observer and the GUI implement it.
#include <optional>

#include "inputs/input_source.hpp"
#include "controller/telemetry.hpp"
#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "experiments/trial_runner.hpp"

namespace palprig {

// What reaches the participant's fingers at one moment of a trial.
struct FeltSample {
  double t_s = 0;
  ChannelPressures felt_kPa{};              // actuator pressures (monitor readings)
  FingerFlags active{};                     // fingers carrying the stimulus now
  const TelemetryRecord* record = nullptr;  // the rig's last tick (pen position), when available
};

class SessionClock;  // experiments/session_clock.hpp

class Participant {
 public:
  virtual ~Participant() = default;
  // The clock the session runs on, before the first pass (it outlives the session loop): a
  // participant that knows when an answer was given on steady_clock (an input event's own
  // time) gives it as Response::given_at_s through SessionClock::at_steady.
  virtual void session_clock(const SessionClock&) {}
  // In `ready` (session start, after a break): true when the participant wants to go on.
  virtual bool ready(double t_s) = 0;
  // A localisation trial's scene, just before trial_started: each trial may present a new case.
  virtual void scene_presented(const Scene&) {}
  // A trial begins (stimulus onset at t_s).
  virtual void trial_started(const PlannedTrial& trial, const Condition& condition, double t_s) = 0;
  // Every loop pass while the trial runs (present and respond).
  virtual void feel(const FeltSample& sample) = 0;
  // The answer, once given (asked every pass while the trial runs).
  virtual std::optional<Response> answer(double t_s) = 0;
  // True while an answer is being completed (the finger answer given, its confidence rating
  // awaited): the response timeout waits (TrialRunner::hold_timeout).
  virtual bool answering() { return false; }
  // The pen this participant palpates with (localisation); null when it has none.
  virtual InputSource* pen() { return nullptr; }
};

}  // namespace palprig
