#include "rigs/simulated_rig.hpp"

namespace palprig {

SimulatedRig::SimulatedRig(const std::array<PlantParams, kFingerCount>& plants, double p_max_kPa)
    : RigBackend(p_max_kPa), plants_{PneumaticPlant(plants[0]), PneumaticPlant(plants[1]), PneumaticPlant(plants[2])} {}

void SimulatedRig::open() {
  for (auto& p : plants_) p.reset(0.0);
  command_kPa_ = {};
  started_ = false;
}

BackendStatus SimulatedRig::do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept {
  // Advance the plants under the previous command up to now, then latch the new one (a
  // regulator holds its last command between writes).
  if (started_ && t_s > last_t_s_)
    for (std::size_t i = 0; i < plants_.size(); ++i) plants_[i].step(command_kPa_[i], t_s - last_t_s_);
  last_t_s_ = t_s;
  started_ = true;
  command_kPa_ = setpoint_kPa;
  return BackendStatus::ok;
}

BackendStatus SimulatedRig::do_read(ChannelPressures& monitor_kPa, double) noexcept {
  for (std::size_t i = 0; i < plants_.size(); ++i) monitor_kPa[i] = plants_[i].monitor_kPa();
  return BackendStatus::ok;
}

BackendStatus SimulatedRig::do_vent() noexcept {
  command_kPa_ = {};
  return BackendStatus::ok;
}

}  // namespace palprig
