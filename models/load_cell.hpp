#pragma once
// A load cell under the fingertip (paper 003: an FSR sewn into the fabric) read as a voltage on
// one of the rig's analog inputs, and its own calibration: force = (volts - tare) * gain. The
// tare is the reading with nothing pressing; the gain comes from one known load (a weight).
// Paper 003's two reference presses (a cuff at 60 and 120 mmHg over the sensor) then give the
// pulse's force window (calibration/force_window.hpp), read through this same calibration.
//
// The simulated rig's load cell: a fingertip pressing depth_mm into the phantom pushes with
// stiffness_N_per_mm * depth (the silicone as a linear spring), read through a sensor with its
// own true tare and gain and seeded Gaussian noise, so calibrating it is a real procedure.
#include <cstdint>
#include <random>

namespace palprig {

struct LoadCellCalibration {
  double tare_V = 0.0;   // reading with no load
  double N_per_V = 1.0;  // gain: newtons per volt above the tare
  double force_N(double volts) const noexcept { return (volts - tare_V) * N_per_V; }
};

struct SimulatedLoadCellParams {
  double stiffness_N_per_mm = 0.5;  // 4 mm deep gives 2 N, paper 002's reference press
  double tare_V = 0.1;              // the sensor's true offset
  double N_per_V = 2.0;             // its true gain
  double noise_sd_V = 0.002;
  double max_V = 10.0;  // the input's range: readings clip here
  std::uint64_t seed = 1;
};

class SimulatedLoadCell {
 public:
  explicit SimulatedLoadCell(const SimulatedLoadCellParams& p = {}) : p_(p), rng_(p.seed) {}
  // The force on the cell with the fingertip depth_mm below the surface (0 above it).
  double force_N(double depth_mm) const noexcept;
  // The voltage the input reads for that depth, noise and range included; `extra_load_N` is a
  // load placed on the cell by hand (a calibration weight).
  double volts(double depth_mm, double extra_load_N = 0.0) noexcept;
  const SimulatedLoadCellParams& params() const noexcept { return p_; }

 private:
  SimulatedLoadCellParams p_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> noise_{0.0, 1.0};
};

}  // namespace palprig
