#pragma once
// A pulse-localisation session (paper 000) end to end, as `palprig experiment run`
// starts it for a protocol with "task": "pulse": the simulated participant (sim:SEED) palpates
// each condition's scene through the rig and marks the pulse; each trial is committed as it
// completes; resume continues the stored order; one process per session. A person palpates with
// pen input, which only the GUI reads: the GUI passes a PulsePersonFactory (the command line
// passes none and a person is refused with its one line).
#include <functional>
#include <memory>

#include "experiments/pulse_session.hpp"
#include "sessions/study_session.hpp"

namespace palprig {

class PulseSessionListener {
 public:
  virtual ~PulseSessionListener() = default;
  virtual void session_started(const SessionStart&) {}
  // A trial is presented (again from its start after a pause).
  virtual void trial_started(const PulseTrialStart&, const PulseCondition&) {}
  // The session waits: paused (vented, holding the trial) or for the participant's ready.
  virtual void waiting(int /*position*/, bool /*paused*/) {}
  virtual void trial_committed(const PulseTrialRecord&, int /*total*/) {}
  virtual void session_ended(const SessionEnd&) {}
};

// Makes the person who palpates and marks (the GUI's); not called for sim:SEED.
using PulsePersonFactory = std::function<std::unique_ptr<PulseParticipant>(const PulseProtocol&)>;

// request.rig_file is required; request.model is not used (the pulse observer has its own).
// Throws InputError for refused input, before the rig moves (or when the store refuses).
// `control`: the operator's stop and pause (experiments/pulse_session.hpp's PulseSessionOptions).
SessionEnd run_pulse_study(const StudySessionRequest& request, const PulsePersonFactory& person,
                           PulseSessionListener& listener, const RunControl& control);

}  // namespace palprig
