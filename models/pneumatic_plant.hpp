#pragma once
// PneumaticPlant: one simulated proportional regulator driving one actuator (paper 002 used
// SMC regulators, 0-100 kPa, about 50 ms response). The command passes through
//   range clamp -> play-operator hysteresis (backlash of +/- hysteresis_kPa; a 0 kPa command
//   exhausts to 0, the band narrowing below 2 x hysteresis_kPa)
//   -> dead time -> first-order lag (time_constant_s) -> slew limit -> range clamp
// and the monitor reading adds seeded Gaussian noise. Used by SimulatedRig, by the Modbus
// simulator and by calibration tests; the rig JSON file sets every parameter.
#include <cstdint>
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
