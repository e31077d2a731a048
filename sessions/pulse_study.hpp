#pragma once
// A pulse-localisation session (issue 13, paper 000) end to end, as `palprig experiment run`
// starts it for a protocol with "task": "pulse": the simulated participant (sim:SEED) palpates
// each condition's scene through the rig and marks the pulse; each trial is committed as it
// completes; resume continues the stored order; one process per session. A person palpates with
// pen input, which only the GUI reads.
#include <atomic>

#include "experiments/pulse_task.hpp"
#include "sessions/study_session.hpp"

namespace palprig {

class PulseSessionListener {
 public:
  virtual ~PulseSessionListener() = default;
  virtual void session_started(const SessionStart&) {}
  virtual void trial_committed(const PulseTrialRecord&, int /*total*/) {}
};

// request.rig_file is required; request.model is not used (the pulse observer has its own).
// Throws InputError for refused input, before the rig moves (or when the store refuses).
SessionEnd run_pulse_study(const StudySessionRequest& request, PulseSessionListener& listener,
                           const std::atomic<int>* stop);

}  // namespace palprig
