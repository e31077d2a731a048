#include "controller/tick_setup.hpp"

#include <cstdio>

namespace palprig {

namespace {

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

}  // namespace

std::string lag_compensation_refusal(const CalibrationModels& cal, std::size_t i) {
  const auto& d = cal.dynamics[i];
  if (!d) return "no identified dynamics (calibrate sweep --excitation ...,step,chirp, then calibrate fit)";
  if (!(d->r_squared >= cal.lag_compensation.min_r_squared))
    return "its identified dynamics fit with R^2 " + fixed(d->r_squared, 4) + ", below the bound " +
           fixed(cal.lag_compensation.min_r_squared, 4) +
           " (lag_compensation.min_r_squared): a poor model could push "
           "harder than the uncompensated rig";
  return {};
}

std::vector<std::string> describe_lag_compensation(const CalibrationModels& cal) {
  std::vector<std::string> out;
  if (!cal.lag_compensation.enabled) return out;
  std::string on;
  int channels_on = 0;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const std::string why = lag_compensation_refusal(cal, i);
    if (why.empty()) {
      const RegulatorDynamics& d = *cal.dynamics[i];
      on += (on.empty() ? "" : ", ") + std::to_string(i + 1) + " (dead time " + fixed(d.dead_time_s * 1000, 1) +
            " ms, lag " + fixed(d.time_constant_s * 1000, 1) +
            (d.exhaust_time_constant_s > 0
                 ? " ms filling, " + fixed(d.exhaust_time_constant_s * 1000, 1) + " ms exhausting)"
                 : " ms)");
      ++channels_on;
    } else {
      out.push_back("lag compensation stays off on channel " + std::to_string(i + 1) + ": " + why);
    }
  }
  if (channels_on > 0)
    out.insert(out.begin(), "lag compensation on for channel" + std::string(channels_on == 1 ? " " : "s ") + on +
                                ", lead at most " + fixed(cal.lag_compensation.max_lead_kPa, 1) + " kPa");
  return out;
}

TickConfig make_tick_config(const RigConfig& rig, const CalibrationModels& cal) {
  TickConfig cfg;
  cfg.layout = rig.layout;
  cfg.safety = rig.safety;
  cfg.contact_force_N = rig.contact_force_N;
  cfg.stress = cal.stress;
  cfg.actuators = cal.actuators;
  // A symmetric model goes through its analytic inverse and back, as the tick always took it (the
  // stored study figures were made so, to the last bit); an asymmetric one has no PI inverse and
  // is taken as fitted.
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const PrandtlIshlinskii& h = cal.hysteresis[i];
    cfg.hysteresis_model[i] = h.is_identity() ? PrandtlIshlinskii{}
                              : h.asymmetric  ? h
                                              : h.inverse().forward_of_inverse();
  }
  // The pulse stage pre-compensates each regulator's lag as the rig file's plant describes it,
  // or as calibration identified it where the fit is good.
  for (std::size_t i = 0; i < kFingerCount; ++i)
    cfg.pulse.lag[i] = {rig.plants[i].dead_time_s, rig.plants[i].time_constant_s, rig.plants[i].slew_kPa_per_s};
  // The identified dynamics (only channels whose fit passes the bound), and whether the whole
  // target is compensated with them.
  LagCompensationSetting& lag = cfg.lag_compensation;
  lag.whole_target = cal.lag_compensation.enabled;
  lag.max_lead_kPa = cal.lag_compensation.max_lead_kPa;
  lag.anticipate_edges = cal.lag_compensation.anticipate_edges;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    if (!lag_compensation_refusal(cal, i).empty()) continue;
    lag.identified[i] = true;
    lag.regulator[i] = {cal.dynamics[i]->dead_time_s, cal.dynamics[i]->time_constant_s, rig.plants[i].slew_kPa_per_s,
                        cal.dynamics[i]->exhaust_time_constant_s};
  }
  // Arteries whose scene gives no force window use the one measured on this rig (paper 003).
  if (cal.force_window) {
    cfg.pulse.has_measured_window = true;
    cfg.pulse.measured_window = {cal.force_window->f_min_N, cal.force_window->f_max_N, 1.0};
  }
  return cfg;
}

}  // namespace palprig
