#include "experiments/session_loop.hpp"

namespace palprig {

SessionLoopResult run_session_loop(TrialRunner& runner, Participant& participant, SessionClock& clock,
                                   const SessionLoopOptions& options) {
  SessionLoopResult result;
  int started_position = -1;
  double next_s = clock.now_s();
  try {
    while (runner.state() != RunnerState::done) {
      const double t = clock.now_s();
      if (options.stop && options.stop->load() != 0) {
        runner.abort(t);
        result.stopped = true;
        return result;
      }
      runner.advance(t);
      const RunnerState s = runner.state();
      if (s == RunnerState::ready && participant.ready(t)) runner.begin(t);
      if (runner.state() == RunnerState::present || runner.state() == RunnerState::respond) {
        // Tell the participant once per trial that it began (the onset is the present entry).
        if (started_position != runner.next_position()) {
          started_position = runner.next_position();
          const PlannedTrial& trial = *runner.current_trial();
          participant.trial_started(trial, runner.protocol().conditions.at(static_cast<std::size_t>(trial.condition)), t);
        }
        FeltSample felt;
        felt.t_s = t;
        felt.felt_kPa = runner.felt_kPa();
        felt.active = runner.active_fingers();
        felt.record = options.output ? options.output->last_record() : nullptr;
        participant.feel(felt);
        if (auto answer = participant.answer(t)) runner.respond(*answer, t);
      }
      next_s += options.period_s;
      clock.wait_until(next_s);
    }
  } catch (const RigFault& fault) {
    result.fault = fault.what();
    return result;
  }
  result.completed = true;
  return result;
}

}  // namespace palprig
