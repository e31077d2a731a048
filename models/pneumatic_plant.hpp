#pragma once
// PneumaticPlant: one simulated proportional regulator driving one actuator (paper 002 used
// SMC regulators, 0-100 kPa, about 50 ms response). The command passes through
//   range clamp -> play-operator hysteresis (the output lags a rising command by
//     rising_play_kPa() and stays above a falling one by falling_play_kPa(); both
//     hysteresis_kPa unless set apart; a 0 kPa command exhausts to 0, the band above the
//     command narrowing near the bottom of the range)
//   -> static gain (linear, or saturating: S tanh(p / S) above min_kPa)
//   -> dead time -> first-order lag (time_constant_s while filling, exhaust_time_constant()
//     while exhausting, that one growing near 0 kPa when exhaust_lag_factor_at_0 > 1)
//   -> slew limit -> range clamp
// and the monitor reading adds seeded Gaussian noise. Used by SimulatedRig, by the Modbus
// simulator and by calibration tests; the rig JSON file sets every parameter.
//
// A real regulator is not symmetric: it fills through its supply valve and empties through its
// exhaust, so its dead band, its speed and its gain differ with the direction and the pressure.
// Every such parameter defaults to the symmetric regulator, whose arithmetic is then exactly
// what it was (the stored study figures stay byte for byte the same).
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

namespace palprig {

struct PlantParams {
  double dead_time_s = 0.005;
  double time_constant_s = 0.050;
  double slew_kPa_per_s = 2000.0;
  double min_kPa = 0.0;
  double max_kPa = 100.0;
  double hysteresis_kPa = 2.0;  // half-width of the play operator (inflation vs deflation gap / 2)
  double noise_sd_kPa = 0.1;    // monitor noise, standard deviation
  std::uint64_t seed = 1;
  // Asymmetric play: how far the output stays below a rising command and above a falling one
  // (unset: hysteresis_kPa each).
  std::optional<double> hysteresis_rising_kPa, hysteresis_falling_kPa;
  // The lag while exhausting (unset: time_constant_s). Near 0 kPa the exhaust has least pressure
  // to push with: the exhaust time constant at pressure p is
  //   tau_e (1 + (F - 1) s / (p + s)),   F = exhaust_lag_factor_at_0, s = exhaust_lag_scale_kPa,
  // F times tau_e at 0 kPa, tau_e far above s. F = 1: no pressure dependence.
  std::optional<double> exhaust_time_constant_s;
  double exhaust_lag_factor_at_0 = 1.0;
  double exhaust_lag_scale_kPa = 10.0;
  // A static gain that saturates: the regulator delivers S tanh(p / S) for p asked (above
  // min_kPa); 0: linear.
  double gain_saturation_kPa = 0.0;

  double rising_play_kPa() const noexcept { return hysteresis_rising_kPa.value_or(hysteresis_kPa); }
  double falling_play_kPa() const noexcept { return hysteresis_falling_kPa.value_or(hysteresis_kPa); }
  double exhaust_time_constant() const noexcept { return exhaust_time_constant_s.value_or(time_constant_s); }
  // The exhaust time constant at output pressure p_kPa (above min_kPa).
  double exhaust_time_constant_at(double p_kPa) const noexcept;
  // The static gain: the pressure delivered for p_kPa out of the play.
  double static_gain(double p_kPa) const noexcept;
};

class PneumaticPlant {
 public:
  explicit PneumaticPlant(const PlantParams& params = {});

  // Advance by dt_s under a commanded pressure; returns the new output pressure. Never throws,
  // never allocates; a non-finite command is treated as 0 kPa (venting).
  double step(double command_kPa, double dt_s) noexcept;
  double output_kPa() const noexcept { return output_kPa_; }
  double monitor_kPa() noexcept;  // output plus measurement noise, clamped to the range
  void reset(double pressure_kPa = 0.0) noexcept;
  const PlantParams& params() const noexcept { return params_; }

 private:
  PlantParams params_;
  double play_kPa_ = 0.0;    // play-operator state
  double output_kPa_ = 0.0;  // actuator pressure
  double initial_kPa_ = 0.0;
  double time_s_ = 0.0;
  // Dead-time delay line: (time, value) pairs in a fixed ring, allocated once.
  struct Stamped {
    double t_s, value_kPa;
  };
  std::vector<Stamped> delay_;
  std::size_t head_ = 0, count_ = 0;
  std::mt19937_64 rng_;
  std::normal_distribution<double> noise_{0.0, 1.0};
};

}  // namespace palprig
