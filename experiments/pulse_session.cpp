#include "experiments/pulse_session.hpp"

#include <algorithm>

#include "experiments/session_pacer.hpp"

#include <cmath>
#include <limits>

#include "models/pulse_localisation.hpp"
#include "study/adaptive_track.hpp"
#include "study/pulse_scene.hpp"
#include "study/random_source.hpp"

namespace palprig {

PulseSessionResult run_pulse_session(const PulseProtocol& protocol, const std::vector<SceneFile>& scenes,
                                     StimulusOutput& output, PulseParticipant& participant, SessionClock& clock,
                                     const PulseSessionOptions& options) {
  PulseSessionResult result;
  const std::vector<int> order = pulse_trial_order(protocol, options.seed);
  SessionPacer pacer(clock, options.period_s, options.control);
  participant.session_clock(clock);
  ChannelPressures felt{};
  auto pass = [&]() { return pacer.pass(output, felt); };
  auto pause_asked = [&] { return pacer.pause_requested(); };
  // The participant's go-ahead (the rig is serviced, vented, meanwhile). The simulated observer
  // is ready at once: no pass, no time, so its sessions are unchanged by this wait.
  auto wait_ready = [&](int position) {
    bool told = false;
    while (!participant.ready(clock.now_s())) {
      if (!told && options.on_waiting) options.on_waiting(position, false);
      told = true;
      pass();
      if (pause_asked()) return false;  // paused again before the Ready: hold first
    }
    return true;
  };
  // A pause: vent at once and hold (servicing the vented rig) until it is lifted.
  auto hold = [&](int position) {
    output.vent(clock.now_s());
    if (options.on_waiting) options.on_waiting(position, true);
    while (pause_asked()) pass();
  };
  try {
    bool need_ready = true;  // before the first trial and after a pause
    for (int position = options.start_position; position < static_cast<int>(order.size());) {
      if (pause_asked()) {
        hold(position);
        need_ready = true;
      }
      if (need_ready) {
        if (!wait_ready(position)) continue;
        need_ready = false;
      }
      const auto c = static_cast<std::size_t>(order[static_cast<std::size_t>(position)]);
      const PulseCondition& condition = protocol.conditions[c];
      PulseTrialRecord r;
      r.position = position;
      r.condition = condition.name;
      SceneFile generated;
      if (condition.generated) {
        r.scene_seed = condition.generated_seed ? *condition.generated_seed
                                                : trial_seed(options.seed, position, 3) >> 1;  // 0..2^63-1
        generated = generated_pulse_scene(*r.scene_seed, *condition.generated);
      }
      const Scene& scene = condition.generated ? *generated.scene : *scenes.at(c).scene;
      r.onset_s = clock.now_s();
      if (options.on_trial_started)
        options.on_trial_started(PulseTrialStart{position, static_cast<int>(c), r.scene_seed, r.onset_s});
      InputSource& pen = participant.trial_started(position, condition, scene, r.onset_s);
      output.palpate(scene, pen, r.onset_s);
      std::optional<Mark> mark;
      bool interrupted = false;
      for (double t = r.onset_s; t - r.onset_s < protocol.max_present_s + protocol.response_timeout_s && !mark;) {
        t = pass();
        if (pause_asked()) {
          interrupted = true;  // the trial is held: not scored, presented again from its start
          break;
        }
        if (t - r.onset_s >= protocol.max_present_s) output.vent(t);
        FeltSample sample;
        sample.t_s = t;
        sample.felt_kPa = felt;
        sample.active = {true, true, true};
        sample.record = output.last_record();
        participant.feel(sample);
        mark = participant.answer(t);
        // Timed when given (never before this presentation's onset), not when taken.
        if (mark) r.response_time_s = std::clamp(participant.answer_given_at_s().value_or(t), r.onset_s, t) - r.onset_s;
      }
      output.vent(clock.now_s());
      if (interrupted) continue;  // the loop's top holds the pause, then waits for the Ready
      r.answered = mark.has_value();
      r.distance_mm = std::numeric_limits<double>::quiet_NaN();
      if (mark) {
        r.mark_x_mm = mark->x_mm;
        r.mark_y_mm = mark->y_mm;
        const PulseMarkScore score = score_pulse_mark(*scene.pulse(), Point2_mm{mark->x_mm, mark->y_mm},
                                                      protocol.hit_radius_mm, condition.artery);
        r.distance_mm = score.distance_mm;
        r.hit = score.hit;
        if (score.artery >= 0) r.artery = scene.pulse()->artery(static_cast<std::size_t>(score.artery)).spec().name;
      } else {
        r.response_time_s = std::numeric_limits<double>::quiet_NaN();
      }
      if (options.on_trial) options.on_trial(r);
      ++position;
      // The inter-trial interval; a pause here cuts it short (the trial is committed).
      const double pause = clock.now_s();
      for (double t = pause; t - pause < protocol.inter_trial_s && !pause_asked();) t = pass();
    }
  } catch (const SessionStopped&) {
    result.stopped = true;
    return result;
  } catch (const RigFault& fault) {
    result.fault = fault.what();
    return result;
  }
  result.completed = true;
  return result;
}

}  // namespace palprig
