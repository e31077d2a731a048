#include "experiments/trial_runner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace palprig {

const char* to_string(RunnerState s) noexcept {
  switch (s) {
    case RunnerState::ready: return "ready";
    case RunnerState::present: return "present";
    case RunnerState::respond: return "respond";
    case RunnerState::inter_trial: return "inter-trial";
    case RunnerState::rest: return "break";
    case RunnerState::done: return "done";
  }
  return "ready";
}

TrialRunner::TrialRunner(const Protocol& protocol, const SessionPlan& plan, int start_position, StimulusOutput& output,
                         RunnerListener& listener, CaseSource* cases, InputSource* pen)
    : protocol_(protocol),
      plan_(plan),
      output_(output),
      listener_(listener),
      cases_(cases),
      pen_(pen),
      position_(start_position),
      reached_s_(std::numeric_limits<double>::quiet_NaN()),
      felt_prev_t_s_(std::numeric_limits<double>::quiet_NaN()) {
  if (protocol.task == TaskKind::localisation && (cases == nullptr || pen == nullptr)) {
    throw BadInput("a localisation session needs its cases and a pen input");
  }
  if (position_ >= total_trials()) state_ = RunnerState::done;
}

const PlannedTrial* TrialRunner::current_trial() const noexcept {
  if (position_ < 0 || position_ >= total_trials()) return nullptr;
  return &plan_.trials[static_cast<std::size_t>(position_)];
}

void TrialRunner::enter(RunnerState s, double t_s) {
  state_ = s;
  state_since_s_ = t_s;
  RunnerEvent e;
  e.kind = RunnerEvent::Kind::state_changed;
  e.state = s;
  e.t_s = t_s;
  e.position = current_trial() ? position_ : -1;
  e.active = active_;
  listener_.on_event(e);
}

void TrialRunner::set_active(const FingerFlags& active, double t_s) {
  if (active == active_ && state_ == RunnerState::present) return;
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    if (active[f] && !active_[f]) active_since_s_[f] = t_s;
  }
  active_ = active;
  const PlannedTrial& t = *current_trial();
  if (protocol_.task == TaskKind::discrimination) {
    const auto& combination = protocol_.combinations.at(static_cast<std::size_t>(t.combination));
    ChannelPressures target{};
    for (std::size_t f = 0; f < kFingerCount; ++f) target[f] = active[f] ? combination.pressure_kPa[f] : 0.0;
    output_.hold(target, t_s);
  }
  RunnerEvent e;
  e.kind = RunnerEvent::Kind::stimulus_changed;
  e.state = state_;
  e.t_s = t_s;
  e.position = position_;
  e.active = active_;
  listener_.on_event(e);
}

double TrialRunner::sequence_length_s() const {
  const Timing& tm = protocol_.timing;
  return kFingerCount * tm.sequential_step_s + (kFingerCount - 1) * tm.sequential_gap_s;
}

double TrialRunner::presentation_length_s(PresentationMode mode) const {
  return mode == PresentationMode::sequential ? sequence_length_s() : protocol_.timing.max_present_s;
}

void TrialRunner::begin(double t_s) {
  if (state_ != RunnerState::ready) return;
  start_trial(t_s);
}

void TrialRunner::start_trial(double t_s) {
  felt_sum_.fill(0.0);
  felt_count_.fill(0);
  onset_s_ = t_s;
  reached_s_ = std::numeric_limits<double>::quiet_NaN();
  active_ = {};
  state_ = RunnerState::present;  // set before enter() so set_active sees the presenting state
  const PlannedTrial& t = *current_trial();
  const PresentationMode mode = protocol_.conditions.at(static_cast<std::size_t>(t.condition)).mode;
  if (mode == PresentationMode::scene) {
    case_ = &cases_->case_of(t);
    scene_ = &cases_->scene_of(t);
  }
  enter(RunnerState::present, t_s);
  switch (mode) {
    case PresentationMode::simultaneous: set_active({true, true, true}, t_s); break;
    case PresentationMode::sequential: set_active({true, false, false}, t_s); break;
    case PresentationMode::scene:
      output_.palpate(*scene_, *pen_, t_s);
      set_active({true, true, true}, t_s);
      break;
  }
}

void TrialRunner::sample_felt(double t_s) {
  const ChannelPressures felt = output_.service(t_s);
  felt_now_ = felt;
  if (state_ == RunnerState::present) {
    for (std::size_t f = 0; f < kFingerCount; ++f) {
      if (active_[f]) {
        felt_sum_[f] += felt[f];
        ++felt_count_[f];
      }
    }
    note_reached(felt, t_s);
  }
  felt_prev_ = felt;
  felt_prev_t_s_ = t_s;
}

void TrialRunner::note_reached(const ChannelPressures& felt, double t_s) {
  // Discrimination only: a scene's level follows the pen, so "half the commanded level" has no
  // single value to cross.
  if (!std::isnan(reached_s_) || protocol_.task != TaskKind::discrimination) return;
  const PlannedTrial& t = *current_trial();
  const auto& level_kPa = protocol_.combinations.at(static_cast<std::size_t>(t.combination)).pressure_kPa;
  double first_s = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    if (!active_[f] || !(level_kPa[f] > 0)) continue;
    const double half_kPa = 0.5 * level_kPa[f];
    if (!(felt[f] >= half_kPa)) continue;
    // Crossed since the last sample: placed on the line between the two samples (the monitor is
    // read once per loop pass), never before the finger's stimulus was commanded on.
    double crossed_s = t_s;
    if (std::isfinite(felt_prev_t_s_) && felt_prev_t_s_ < t_s && felt_prev_[f] < half_kPa) {
      crossed_s = felt_prev_t_s_ + (half_kPa - felt_prev_[f]) / (felt[f] - felt_prev_[f]) * (t_s - felt_prev_t_s_);
    }
    first_s = std::min(first_s, std::max(crossed_s, active_since_s_[f]));
  }
  if (std::isfinite(first_s)) reached_s_ = first_s;
}

void TrialRunner::update_presentation(double t_s) {
  const PlannedTrial& t = *current_trial();
  const PresentationMode mode = protocol_.conditions.at(static_cast<std::size_t>(t.condition)).mode;
  const double elapsed = t_s - onset_s_;
  if (mode == PresentationMode::sequential) {
    const Timing& tm = protocol_.timing;
    if (elapsed >= sequence_length_s()) {
      end_stimulus(onset_s_ + sequence_length_s(), t_s);
      enter(RunnerState::respond, t_s);
      return;
    }
    // Which slot of step, gap, step, gap, step are we in?
    const double period = tm.sequential_step_s + tm.sequential_gap_s;
    const auto finger = static_cast<std::size_t>(std::floor(elapsed / period));
    const bool on = elapsed - static_cast<double>(finger) * period < tm.sequential_step_s;
    FingerFlags active{};
    if (on && finger < kFingerCount) active[finger] = true;
    set_active(active, t_s);
    return;
  }
  if (elapsed >= protocol_.timing.max_present_s) {
    end_stimulus(onset_s_ + protocol_.timing.max_present_s, t_s);
    enter(RunnerState::respond, t_s);
  }
}

void TrialRunner::end_stimulus(double planned_end_s, double t_s) {
  // Recorded at the planned end, not at the (possibly later) pass that noticed it: a caller's
  // coarse steps do not lengthen the stimulus the after-stimulus RT is measured from. The rig
  // is vented now (its clock only goes forward).
  stimulus_end_s_ = planned_end_s;
  set_active({}, t_s);
  output_.vent(t_s);
}

void TrialRunner::advance(double t_s) {
  // Several transitions may fall due in one call when the caller's steps are coarse.
  for (int guard = 0; guard < 8; ++guard) {
    const RunnerState before = state_;
    switch (state_) {
      case RunnerState::ready:
      case RunnerState::done: break;
      case RunnerState::present: update_presentation(t_s); break;
      case RunnerState::respond:
        if (!timeout_held_ && t_s - state_since_s_ >= protocol_.timing.response_timeout_s) finish_trial(nullptr, t_s);
        break;
      case RunnerState::inter_trial:
        if (t_s - state_since_s_ >= protocol_.timing.inter_trial_s) {
          const PlannedTrial& finished = plan_.trials[static_cast<std::size_t>(position_)];
          ++position_;
          if (position_ >= total_trials())
            enter(RunnerState::done, t_s);
          else if (finished.break_after)
            enter(RunnerState::rest, t_s);
          else
            start_trial(t_s);
        }
        break;
      case RunnerState::rest:
        if (t_s - state_since_s_ >= protocol_.timing.break_s) enter(RunnerState::ready, t_s);
        break;
    }
    if (state_ == before) break;
  }
  sample_felt(t_s);
}

void TrialRunner::pause(double t_s) {
  switch (state_) {
    case RunnerState::done: return;
    // Waiting for the participant: nothing to drop, but the pause is still entered (vent, and
    // the state event that tells a front end the loop holds).
    case RunnerState::ready:
    // Presenting or waiting for the answer: the trial is dropped, the same position is presented
    // again.
    case RunnerState::present:
    case RunnerState::respond: break;
    case RunnerState::inter_trial:
      ++position_;  // committed on entry to inter_trial: go on with the next one
      break;
    case RunnerState::rest: break;
  }
  active_ = {};
  output_.vent(t_s);
  enter(position_ >= total_trials() ? RunnerState::done : RunnerState::ready, t_s);
}

bool answers_during_presentation(const Protocol& protocol, PresentationMode mode) noexcept {
  switch (mode) {
    case PresentationMode::scene: return true;
    case PresentationMode::simultaneous: return protocol.timing.answer_during_stimulus;
    case PresentationMode::sequential: return false;
  }
  return false;
}

bool TrialRunner::takes_answers() const noexcept {
  if (state_ == RunnerState::respond) return true;
  if (state_ != RunnerState::present) return false;
  const PlannedTrial* t = current_trial();
  return t &&
         answers_during_presentation(protocol_, protocol_.conditions.at(static_cast<std::size_t>(t->condition)).mode);
}

bool TrialRunner::respond(const Response& response, double t_s) {
  if (!takes_answers()) return false;
  if (response.confidence && !protocol_.confidence.valid(*response.confidence)) return false;
  finish_trial(&response, t_s);
  return true;
}

void TrialRunner::finish_trial(const Response* response, double t_s) {
  const PlannedTrial& t = *current_trial();
  const Condition& condition = protocol_.conditions.at(static_cast<std::size_t>(t.condition));
  TrialRecord r;
  r.planned = t;
  r.condition = condition.name;
  r.mode = condition.mode;
  r.onset_s = onset_s_;
  r.answered = response != nullptr;
  // The moment the participant answered: when it reached the runner, or earlier when the
  // participant says so (a rating given after the finger answer; an answer typed during a
  // sequence), never before this presentation's onset.
  const double answered_t_s = response && response->given_at_s ? std::clamp(*response->given_at_s, onset_s_, t_s) : t_s;
  r.response_time_s = r.answered ? answered_t_s - onset_s_ : std::numeric_limits<double>::quiet_NaN();
  // An answer during the presentation ends the stimulus at the answer's time (or at its
  // planned end, when that passed before the loop noticed it). With a rating after the finger
  // answer the actuators stay on until the rating is in; the end recorded is the finger answer.
  r.stimulus_end_s = state_ == RunnerState::present
                         ? std::min(answered_t_s, onset_s_ + presentation_length_s(condition.mode))
                         : stimulus_end_s_;
  // Reached only if before the answer (an answer ahead of the stimulus did not respond to it).
  r.stimulus_reached_s = reached_s_ <= answered_t_s ? reached_s_ : std::numeric_limits<double>::quiet_NaN();
  if (response && protocol_.confidence.asked()) r.confidence = response->confidence;
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    r.felt_kPa[f] = felt_count_[f] ? felt_sum_[f] / felt_count_[f] : std::numeric_limits<double>::quiet_NaN();
  }
  if (protocol_.task == TaskKind::discrimination) {
    const auto& combination = protocol_.combinations.at(static_cast<std::size_t>(t.combination));
    r.combination_label = combination.label;
    r.stimulus_kPa = combination.pressure_kPa;
    r.truth = combination.tumor;
    if (response) {
      r.answer = response->tumor_under;
      r.finger_outcomes = score_discrimination(r.truth, r.answer);
    }
  } else {
    r.case_name = case_->name;
    r.case_seed = case_->seed;
    r.case_difficulty = case_->difficulty;
    r.case_tumors = static_cast<int>(case_->tumors.size());
    if (response) {
      r.marks = response->marks;
      r.localisation = score_localisation(case_->tumors, r.marks, protocol_.localisation.tolerance_mm);
    }
  }
  active_ = {};
  output_.vent(t_s);
  listener_.on_trial_completed(r);
  RunnerEvent e;
  e.kind = RunnerEvent::Kind::trial_completed;
  e.state = state_;
  e.t_s = t_s;
  e.position = position_;
  listener_.on_event(e);
  enter(RunnerState::inter_trial, t_s);
}

void TrialRunner::abort(double t_s) {
  active_ = {};
  output_.vent(t_s);
  if (state_ != RunnerState::done) enter(RunnerState::done, t_s);
}

}  // namespace palprig
