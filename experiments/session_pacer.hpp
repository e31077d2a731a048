#pragma once
// The one pass every session loop makes (discrimination and localisation through the trial
// runner, thresholds, pulse localisation): a stop request vents and ends the session; the rig is
// serviced; the loop waits for the next period on an absolute schedule (no drift). Written once
// so a stop behaves the same in every task kind.
#include "experiments/session_clock.hpp"
#include "experiments/stimulus_output.hpp"
#include "runtime/run_control.hpp"

namespace palprig {

// Thrown by SessionPacer::pass after a stop request has vented the output; the session returns
// "stopped" (the trial in progress is not kept).
struct SessionStopped {};

class SessionPacer {
 public:
  // `control`: a stop request (SIGINT/SIGTERM, the terminal's q, the window's Abort) ends the
  // session; may be null.
  SessionPacer(SessionClock& clock, double period_s, const RunControl* control)
      : clock_(clock), period_s_(period_s), control_(control), next_s_(clock.now_s()) {}

  double now_s() { return clock_.now_s(); }
  bool stop_requested() const noexcept { return control_ && control_->stop_requested(); }
  bool pause_requested() const noexcept { return control_ && control_->paused(); }
  // The next period's deadline, then wait for it.
  void wait_next() {
    next_s_ += period_s_;
    clock_.wait_until(next_s_);
  }
  // One pass: on a stop request, vent and throw SessionStopped; otherwise service the output
  // (`felt`: what the fingers feel now) and wait for the next period. Returns the pass's time.
  double pass(StimulusOutput& output, ChannelPressures& felt) {
    const double t = clock_.now_s();
    if (stop_requested()) {
      output.vent(t);
      throw SessionStopped{};
    }
    felt = output.service(t);
    wait_next();
    return t;
  }

 private:
  SessionClock& clock_;
  double period_s_;
  const RunControl* control_;
  double next_s_;
};

}  // namespace palprig
