#include "experiments/rig_stimulus.hpp"

#include "controller/loop_runner.hpp"

#include <string>

namespace palprig {

RigStimulus::RigStimulus(const TickConfig& config, RigBackend& backend, double rate_hz)
    : rig_(config, backend, RigStepOptions{rate_hz, false}) {
  if (rig_.arm() != BackendStatus::ok) fault(std::string("rig backend: ") + rig_.fault().detail());
}

RigStimulus::~RigStimulus() { rig_.disarm(); }

void RigStimulus::hold(const ChannelPressures& target_kPa, double t_s) {
  mode_ = Mode::hold;
  target_kPa_ = target_kPa;
  service(t_s);
}

void RigStimulus::palpate(const Scene& scene, InputSource& pen, double t_s) {
  mode_ = Mode::scene;
  scene_ = &scene;
  pen_ = &pen;
  service(t_s);
}

void RigStimulus::vent(double t_s) {
  mode_ = Mode::vented;
  target_kPa_ = {};
  service(t_s);
}

void RigStimulus::fault(const std::string& why) {
  rig_.disarm();
  throw RigFault(why + "; all channels vented");
}

ChannelPressures RigStimulus::service(double t_s) {
  if (rig_.faulted()) fault(std::string("rig faulted earlier: ") + to_string(rig_.fault()));
  // The tick's time only moves forward; a repeated call at the same time re-sends the setpoint.
  const TickState& state = rig_.tick_state();
  const double t = state.started && t_s < state.last_t_s ? state.last_t_s : t_s;
  // Venting goes through the same stage at 0 kPa so the safety stage sees every setpoint.
  const StepResult& result = mode_ == Mode::scene
                                 ? rig_.step(*scene_, pen_->latest(t), t)
                                 : rig_.step_direct(mode_ == Mode::hold ? target_kPa_ : ChannelPressures{}, t);
  if (rig_.faulted()) {
    if (rig_.fault() == FaultCode::backend_error) fault(std::string("rig backend: ") + rig_.fault().detail());
    fault(std::string("safety stage: ") + to_string(rig_.fault()));
  }
  last_ = result.tick.record;
  if (telemetry_) {
    if (telemetry_->failed()) fault("telemetry: " + telemetry_->failure());
    if (keep_every_record_)
      telemetry_->push_wait(last_);
    else
      telemetry_->try_push(last_);
  }
  if (observer_) observer_->on_tick(last_);
  return result.monitor_kPa;
}

}  // namespace palprig
