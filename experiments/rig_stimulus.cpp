#include "experiments/rig_stimulus.hpp"

#include <string>

namespace palprig {

RigStimulus::RigStimulus(const TickConfig& config, RigBackend& backend)
    : config_(config), backend_(backend), state_(make_tick_state(config)) {}

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
  backend_.vent();
  throw RigFault(why + "; all channels vented");
}

ChannelPressures RigStimulus::service(double t_s) {
  if (state_.fault != FaultCode::none) fault(std::string("rig faulted earlier: ") + to_string(state_.fault));
  // The tick's time only moves forward; a repeated call at the same time re-sends the setpoint.
  const double t = state_.started && t_s < state_.last_t_s ? state_.last_t_s : t_s;
  TickResult result;
  if (mode_ == Mode::scene) {
    result = tick(state_, config_, *scene_, pen_->latest(t), t);
  } else {
    // Venting goes through the same stage at 0 kPa so the safety stage sees every setpoint.
    result = tick_direct(state_, config_, mode_ == Mode::hold ? target_kPa_ : ChannelPressures{}, t);
  }
  if (state_.fault != FaultCode::none) fault(std::string("safety stage: ") + to_string(state_.fault));
  if (backend_.write(result.setpoint_kPa, t) != BackendStatus::ok) {
    state_.enter_fault(FaultCode::backend_error);
    fault(std::string("rig backend: ") + backend_.last_error());
  }
  ChannelPressures monitor{};
  if (backend_.read_monitors(monitor, t) != BackendStatus::ok) {
    state_.enter_fault(FaultCode::backend_error);
    fault(std::string("rig backend: ") + backend_.last_error());
  }
  last_ = result.record;
  return monitor;
}

}  // namespace palprig
