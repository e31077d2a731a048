#pragma once
// The threshold session: runs interleaved adaptive tracks on a StimulusOutput (on a rig through
// the controller's tick_direct: hysteresis compensation and the safety stage, like every
// trial). Each trial: the track is chosen, its level read, two intervals presented (pressure on
// the track's fingers for interval_s, vented gap_s between), the answer awaited for
// response_timeout_s, the answer scored and recorded in the track, the trial handed to
// `on_trial` (the store commits it, with every track's state, before the next trial starts),
// then a vented inter-trial pause. An unanswered trial is recorded but leaves the track
// unchanged (the level is presented again).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/participant.hpp"
#include "experiments/session_clock.hpp"
#include "experiments/stimulus_output.hpp"
#include "runtime/run_control.hpp"
#include "study/threshold_protocol.hpp"
#include "study/threshold_record.hpp"

namespace palprig {

struct ThresholdTrialInfo {
  int position = 0;
  int track = 0;
  const TrackSpec* spec = nullptr;
  ThresholdMethod method = ThresholdMethod::two_afc;
  double level_kPa = 0;  // the increment (a person is not told)
  FingerFlags active{};  // fingers carrying the stimulus
};

class ThresholdParticipant {
 public:
  virtual ~ThresholdParticipant() = default;
  virtual bool ready(double t_s) = 0;  // before the first trial
  virtual void trial_started(const ThresholdTrialInfo& trial, double t_s) = 0;
  virtual void interval_started(int interval, double t_s) = 0;
  virtual void feel(int interval, const FeltSample& sample) = 0;
  // Asked every pass after the second interval; 2afc: 0 or 1, yes-no: 1 yes, 0 no.
  virtual std::optional<int> answer(double t_s) = 0;
};

struct ThresholdSessionOptions {
  std::uint64_t seed = 1;
  int start_position = 0;  // trials already committed
  double period_s = 0.005;
  const RunControl* control = nullptr;  // a stop request vents and stops; null: none
  std::function<void(const ThresholdTrialRecord&)> on_trial;
};

struct ThresholdSessionResult {
  bool completed = false, stopped = false;
  std::string fault;
  int trials = 0;  // recorded in this run
};

ThresholdSessionResult run_threshold_session(const ThresholdProtocol& protocol, std::vector<AdaptiveTrack>& tracks,
                                             StimulusOutput& output, ThresholdParticipant& participant,
                                             SessionClock& clock, const ThresholdSessionOptions& options);

}  // namespace palprig
