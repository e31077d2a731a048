#include "controller/tick_setup.hpp"

namespace palprig {

TickConfig make_tick_config(const RigConfig& rig, const CalibrationModels& cal) {
  TickConfig cfg;
  cfg.layout = rig.layout;
  cfg.safety = rig.safety;
  cfg.contact_force_N = rig.contact_force_N;
  cfg.stress = cal.stress;
  cfg.actuators = cal.actuators;
  for (std::size_t i = 0; i < kFingerCount; ++i)
    cfg.hysteresis_inverse[i] = cal.hysteresis[i].is_identity() ? PrandtlIshlinskii{} : cal.hysteresis[i].inverse();
  // The pulse stage pre-compensates each regulator's lag as the rig file's plant describes it.
  for (std::size_t i = 0; i < kFingerCount; ++i)
    cfg.pulse.lag[i] = {rig.plants[i].dead_time_s, rig.plants[i].time_constant_s, rig.plants[i].slew_kPa_per_s};
  // Arteries whose scene gives no force window use the one measured on this rig (paper 003).
  if (cal.force_window) {
    cfg.pulse.has_measured_window = true;
    cfg.pulse.measured_window = {cal.force_window->f_min_N, cal.force_window->f_max_N, 1.0};
  }
  return cfg;
}

}  // namespace palprig
