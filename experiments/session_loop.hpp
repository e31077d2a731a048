#pragma once
// The session loop: feeds the runner the clock's time, tells the participant what the fingers
// feel, passes on readiness and answers, and services the rig every period, until the
// session is done, a stop is requested, or the rig faults. No terminal or GUI knowledge.
#include <string>

#include "experiments/participant.hpp"
#include "experiments/session_clock.hpp"
#include "experiments/trial_runner.hpp"
#include "runtime/run_control.hpp"

namespace palprig {

struct SessionLoopOptions {
  double period_s = 0.005;  // how often the runner and rig are serviced
  // The operator's handle: a stop request stops (vents; the current trial is not kept); a
  // pause (RunControl::set_paused(true); TrialRunner::pause: vents, holds the session, the trial in progress is not
  // kept); back to false: resume. The runner then waits in `ready` until the participant says
  // ready again, as at the start of the session and after a break: the experimenter's Continue
  // alone does not put a stimulus under fingers that may have left the actuators. The held
  // trial is then presented again from its start. The rig is serviced all along. Null: none.
  const RunControl* control = nullptr;
  const StimulusOutput* output = nullptr;  // for the rig's last tick record (pen position)
};

struct SessionLoopResult {
  bool completed = false;  // every planned trial done
  bool stopped = false;    // a stop was requested
  std::string fault;       // non-empty when the rig faulted (channels vented)
};

SessionLoopResult run_session_loop(TrialRunner& runner, Participant& participant, SessionClock& clock,
                                   const SessionLoopOptions& options);

}  // namespace palprig
