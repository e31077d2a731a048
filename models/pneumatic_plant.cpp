#include "models/pneumatic_plant.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.hpp"

namespace palprig {

double PlantParams::exhaust_time_constant_at(double p_kPa) const noexcept {
  const double tau = exhaust_time_constant();
  if (exhaust_lag_factor_at_0 == 1.0) return tau;
  const double p = std::max(p_kPa - min_kPa, 0.0);
  return tau * (1.0 + (exhaust_lag_factor_at_0 - 1.0) * exhaust_lag_scale_kPa / (p + exhaust_lag_scale_kPa));
}

double PlantParams::static_gain(double p_kPa) const noexcept {
  if (!(gain_saturation_kPa > 0)) return p_kPa;
  return min_kPa + gain_saturation_kPa * std::tanh((p_kPa - min_kPa) / gain_saturation_kPa);
}

namespace {
constexpr std::size_t kDelayCapacity = 8192;  // enough for 8 s of dead time at 1 kHz
}

PneumaticPlant::PneumaticPlant(const PlantParams& p) : params_(p), delay_(kDelayCapacity), rng_(p.seed) {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw BadInput(std::string("PneumaticPlant: ") + what);
  };
  need(std::isfinite(p.dead_time_s) && p.dead_time_s >= 0, "dead_time_s must be >= 0");
  need(std::isfinite(p.time_constant_s) && p.time_constant_s >= 0, "time_constant_s must be >= 0");
  need(p.slew_kPa_per_s > 0, "slew_kPa_per_s must be > 0");
  need(std::isfinite(p.min_kPa) && std::isfinite(p.max_kPa) && p.min_kPa < p.max_kPa, "min_kPa < max_kPa");
  need(p.hysteresis_kPa >= 0 && std::isfinite(p.hysteresis_kPa), "hysteresis_kPa must be >= 0");
  need(p.noise_sd_kPa >= 0 && std::isfinite(p.noise_sd_kPa), "noise_sd_kPa must be >= 0");
  need(p.rising_play_kPa() >= 0 && std::isfinite(p.rising_play_kPa()), "hysteresis_rising_kPa must be >= 0");
  need(p.falling_play_kPa() >= 0 && std::isfinite(p.falling_play_kPa()), "hysteresis_falling_kPa must be >= 0");
  need(std::isfinite(p.exhaust_time_constant()) && p.exhaust_time_constant() >= 0,
       "exhaust_time_constant_s must be >= 0");
  need(std::isfinite(p.exhaust_lag_factor_at_0) && p.exhaust_lag_factor_at_0 >= 1,
       "exhaust_lag_factor_at_0 must be >= 1");
  need(std::isfinite(p.exhaust_lag_scale_kPa) && p.exhaust_lag_scale_kPa > 0, "exhaust_lag_scale_kPa must be > 0");
  need(std::isfinite(p.gain_saturation_kPa) && p.gain_saturation_kPa >= 0, "gain_saturation_kPa must be >= 0");
  reset(p.min_kPa);
}

void PneumaticPlant::reset(double pressure_kPa) noexcept {
  output_kPa_ = play_kPa_ = initial_kPa_ = std::clamp(pressure_kPa, params_.min_kPa, params_.max_kPa);
  time_s_ = 0;
  head_ = 0;
  count_ = 0;
}

double PneumaticPlant::step(double command_kPa, double dt_s) noexcept {
  if (!std::isfinite(command_kPa)) command_kPa = 0.0;
  if (!(dt_s > 0) || !std::isfinite(dt_s)) return output_kPa_;
  const double x = std::clamp(command_kPa, params_.min_kPa, params_.max_kPa);
  // Play operator (backlash of +/- r). Near the bottom of the range the band above the
  // command narrows to the distance from the bottom: a regulator's exhaust valve opens fully at
  // a 0 kPa command, so venting empties the actuator instead of leaving it at +r (before
  // this, a vented plant read about 2 kPa, and a 0 kPa stimulus was felt at 2 kPa). Above 2 r the
  // band is the full +/- r, continuous in between.
  // Rising, the output stays rising_play below the command; falling, falling_play above it.
  const double r_above = std::min(params_.falling_play_kPa(), x - params_.min_kPa);
  play_kPa_ = std::max(x - params_.rising_play_kPa(), std::min(x + r_above, play_kPa_));

  // Dead time: push the play output, then read the newest value at least dead_time old.
  // The command is stamped with the time it was given (the start of this step) and is felt
  // dead_time later.
  const std::size_t cap = delay_.size();
  delay_[(head_ + count_) % cap] = {time_s_, params_.static_gain(play_kPa_)};
  time_s_ += dt_s;
  if (count_ < cap)
    ++count_;
  else
    head_ = (head_ + 1) % cap;
  const double due = time_s_ - params_.dead_time_s + 1e-12;
  while (count_ > 1 && delay_[(head_ + 1) % cap].t_s <= due) {
    head_ = (head_ + 1) % cap;
    --count_;
  }
  // Until the first command has aged past the dead time the regulator holds its reset value.
  const double delayed = delay_[head_].t_s <= due ? delay_[head_].value_kPa : initial_kPa_;

  // First-order lag (exact discretisation over the step, at the present pressure), then the
  // regulator's slew limit. Filling toward a higher pressure: time_constant_s; exhausting: the
  // exhaust's, at the present pressure.
  const double tau = delayed < output_kPa_ ? params_.exhaust_time_constant_at(output_kPa_) : params_.time_constant_s;
  const double alpha = tau > 0 ? 1.0 - std::exp(-dt_s / tau) : 1.0;
  double dy = (delayed - output_kPa_) * alpha;
  const double max_step = params_.slew_kPa_per_s * dt_s;
  dy = std::clamp(dy, -max_step, max_step);
  output_kPa_ = std::clamp(output_kPa_ + dy, params_.min_kPa, params_.max_kPa);
  return output_kPa_;
}

double PneumaticPlant::monitor_kPa() noexcept {
  const double v = output_kPa_ + params_.noise_sd_kPa * noise_(rng_);
  return std::clamp(v, params_.min_kPa, params_.max_kPa);
}

}  // namespace palprig
