#include "experiments/threshold_session.hpp"

#include "experiments/session_pacer.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "study/random_source.hpp"

namespace palprig {

ThresholdSessionResult run_threshold_session(const ThresholdProtocol& protocol, std::vector<AdaptiveTrack>& tracks,
                                             StimulusOutput& output, ThresholdParticipant& participant,
                                             SessionClock& clock, const ThresholdSessionOptions& options) {
  ThresholdSessionResult result;
  SessionPacer pacer(clock, options.period_s, options.control);
  const ThresholdTiming& tm = protocol.timing;
  ChannelPressures felt{};
  try {
    output.vent(pacer.now_s());
    while (!participant.ready(pacer.now_s())) pacer.pass(output, felt);
    for (int position = options.start_position;; ++position) {
      const int index = choose_track(tracks, options.seed, position);
      if (index < 0) break;
      AdaptiveTrack& track = tracks[static_cast<std::size_t>(index)];
      const TrackSpec& spec = track.spec();

      ThresholdTrialInfo info;
      info.position = position;
      info.track = index;
      info.spec = &spec;
      info.method = protocol.method;
      info.level_kPa = track.next_level_kPa();
      for (std::size_t f = 0; f < kFingerCount; ++f) {
        info.active[f] = spec.fingers == FingerSet::three || static_cast<int>(f) == spec.finger;
      }
      ThresholdTrialRecord r;
      r.position = position;
      r.track = index;
      r.track_name = spec.name;
      r.fingers = spec.fingers == FingerSet::one ? "one" : "three";
      r.level_kPa = info.level_kPa;
      r.reference_kPa = protocol.reference_kPa;
      r.signal_interval = protocol.method == ThresholdMethod::two_afc
                              ? static_cast<int>(RandomSource(trial_seed(options.seed, position, 2)).below(2))
                              : 1;
      r.onset_s = pacer.now_s();
      participant.trial_started(info, r.onset_s);

      for (int interval = 0; interval < 2; ++interval) {
        ChannelPressures target{};
        const double p = protocol.reference_kPa + (interval == r.signal_interval ? info.level_kPa : 0.0);
        for (std::size_t f = 0; f < kFingerCount; ++f) target[f] = info.active[f] ? p : 0.0;
        const double start = pacer.now_s();
        output.hold(target, start);
        participant.interval_started(interval, start);
        double sum = 0;
        int count = 0;
        for (double t = start; t - start < tm.interval_s;) {
          t = pacer.pass(output, felt);
          FeltSample sample;
          sample.t_s = t;
          sample.felt_kPa = felt;
          sample.active = info.active;
          sample.record = output.last_record();
          participant.feel(interval, sample);
          // The record keeps the mean of the interval's second half (after the rise).
          if (t - start >= tm.interval_s / 2) {
            for (std::size_t f = 0; f < kFingerCount; ++f) {
              if (info.active[f]) {
                sum += felt[f];
                ++count;
              }
            }
          }
        }
        r.felt_kPa[static_cast<std::size_t>(interval)] = count ? sum / count : std::numeric_limits<double>::quiet_NaN();
        const double gap_start = pacer.now_s();
        output.vent(gap_start);
        if (interval == 0) {
          for (double t = gap_start; t - gap_start < tm.gap_s;) t = pacer.pass(output, felt);
        }
      }

      const double respond_start = pacer.now_s();
      std::optional<int> answer;
      for (double t = respond_start; t - respond_start < tm.response_timeout_s && !answer;) {
        t = pacer.pass(output, felt);
        answer = participant.answer(t);
        if (answer) r.response_time_s = t - respond_start;
      }
      r.answered = answer.has_value();
      if (r.answered) {
        r.response = *answer;
        r.correct = protocol.method == ThresholdMethod::two_afc ? r.response == r.signal_interval : r.response == 1;
        r.reversal = track.record(info.level_kPa, r.correct);
      } else {
        r.response_time_s = std::numeric_limits<double>::quiet_NaN();
      }
      if (options.on_trial) options.on_trial(r);
      ++result.trials;
      const double pause_start = pacer.now_s();
      for (double t = pause_start; t - pause_start < tm.inter_trial_s;) t = pacer.pass(output, felt);
    }
  } catch (const SessionStopped&) {
    result.stopped = true;
    return result;
  } catch (const RigFault& fault) {
    result.fault = fault.what();
    return result;
  }
  output.vent(pacer.now_s());
  result.completed = true;
  return result;
}

}  // namespace palprig
