#include "experiments/session_loop.hpp"

#include "experiments/session_pacer.hpp"

#include <optional>

namespace palprig {

SessionLoopResult run_session_loop(TrialRunner& runner, Participant& participant, SessionClock& clock,
                                   const SessionLoopOptions& options) {
  SessionLoopResult result;
  int started_position = -1;
  bool paused = false;
  std::optional<Response> pending;  // an answer the runner does not take yet
  SessionPacer pacer(clock, options.period_s, options.control);
  participant.session_clock(clock);
  try {
    while (runner.state() != RunnerState::done) {
      const double t = pacer.now_s();
      // The runner's own stop (it vents): the pass is the pacer's, the servicing is the runner's.
      if (pacer.stop_requested()) {
        runner.abort(t);
        result.stopped = true;
        return result;
      }
      const bool pause_asked = pacer.pause_requested();
      if (pause_asked != paused) {
        paused = pause_asked;
        if (paused) {
          runner.pause(t);
          started_position = -1;  // the held trial is presented (and announced) again
        }
        // On resume the runner stays in `ready`: the participant's go-ahead begins the trial.
      }
      runner.hold_timeout(!paused && participant.answering());
      runner.advance(t);
      if (paused) {
        pacer.wait_next();
        continue;
      }
      const RunnerState s = runner.state();
      if (s == RunnerState::ready && participant.ready(t)) runner.begin(t);
      if (runner.state() == RunnerState::present || runner.state() == RunnerState::respond) {
        // Tell the participant once per trial that it began (the onset is the present entry).
        if (started_position != runner.next_position()) {
          started_position = runner.next_position();
          pending.reset();  // an answer belongs to the trial it was given in
          const PlannedTrial& trial = *runner.current_trial();
          if (const Scene* scene = runner.current_scene(); scene && runner.protocol().task == TaskKind::localisation)
            participant.scene_presented(*scene);
          participant.trial_started(trial, runner.protocol().conditions.at(static_cast<std::size_t>(trial.condition)),
                                    t);
        }
        FeltSample felt;
        felt.t_s = t;
        felt.felt_kPa = runner.felt_kPa();
        felt.active = runner.active_fingers();
        felt.record = options.output ? options.output->last_record() : nullptr;
        participant.feel(felt);
        // An answer given before the runner takes answers (typed during a sequence) waits for
        // the end of the presentation; the participant is not asked again meanwhile (a terminal's
        // next typed line belongs to the next trial).
        if (!pending) {
          pending = participant.answer(t);
          if (pending && !pending->given_at_s) pending->given_at_s = t;  // timed when given, not when taken
        }
        if (pending && runner.takes_answers()) {
          runner.respond(*pending, t);  // a refused one (an invalid rating) is dropped
          pending.reset();
        }
      }
      pacer.wait_next();
    }
  } catch (const RigFault& fault) {
    result.fault = fault.what();
    return result;
  }
  result.completed = true;
  return result;
}

}  // namespace palprig
