#pragma once
// Identification of a regulator channel's dynamics from the sweep's step and chirp rows, with
// Ceres: a first-order lag with dead time (FOPDT) between the command, passed through the
// channel's fitted hysteresis model, and the monitor,
//
//   x_k = H[c]_k                      (the forward Prandtl-Ishlinskii model; identity without one)
//   tau y'(t) + y(t) = x(t - L)       (x held between samples: a zero-order hold)
//
// discretised exactly at the sample period T for a dead time L = d T + theta (0 <= theta < T):
//
//   y_{k+1} = a y_k + (1 - e) x_{k-d} + (e - a) x_{k-d-1},   a = exp(-T/tau), e = exp(-(T - theta)/tau)
//
// which is continuous in L across whole samples, so L is fitted as a real number. The samples
// are those the loop's tick and backend see (command written at tick k, monitor read back at
// tick k), so L includes the backend's transport (a fieldbus's cycle) and is what the tick's
// lag compensation must lead by, beyond the one tick every command takes to arrive.
//
// Stage 1: a grid over whole-sample dead times with the lag found by golden-section search for
// each. Stage 2: Ceres refines (L, tau) together from the best grid point, within bounds, with
// exact derivatives propagated along the sequence (one residual per sample). Reported: R^2 of
// the monitor, overall and per segment (step, chirp), and the residuals' RMS and maximum.
//
// Direction-dependent dynamics: a regulator fills through its supply valve and exhausts through
// its exhaust, at different rates. Stage 3 frees a second lag, tau_f while the input felt is
// above the output (filling), tau_e below it (exhausting), from stage 2's point; it is kept when
// its residual RMS is at least min_directional_gain (10 %) lower than the one-lag model's, so a
// symmetric regulator keeps its one lag (and the figures it always had).
#include <span>
#include <string>
#include <vector>

#include "calibration/sweep_csv.hpp"
#include "models/hysteresis.hpp"

namespace palprig {

struct DynamicsFitOptions {
  double max_dead_time_s = 0.3;
  double min_time_constant_s = 0.0005, max_time_constant_s = 2.0;
  int max_iterations = 100;
  bool directional = true;             // try separate fill and exhaust lags (stage 3)
  double min_directional_gain = 0.10;  // ... and keep them when the residual RMS drops by this much
};

struct DynamicsSegmentFit {
  SweepSegment segment = SweepSegment::step;
  std::size_t samples = 0;
  double r_squared = 0, rms_residual_kPa = 0, max_residual_kPa = 0;
};

struct DynamicsFit {
  double dead_time_s = 0, time_constant_s = 0;
  // Separate lags: time_constant_s while filling, this while exhausting (directional only).
  bool directional = false;
  double exhaust_time_constant_s = 0;
  double one_lag_rms_residual_kPa = 0;  // stage 2's, for the report: what the second lag gained
  double r_squared = 0, rms_residual_kPa = 0, max_residual_kPa = 0;
  std::size_t samples = 0;  // residuals (every sample but each run's first)
  double rate_hz = 0;
  std::vector<DynamicsSegmentFit> segments;
  double grid_rms_residual_kPa = 0;  // stage 1's best
  bool converged = false;            // Ceres reported CONVERGENCE
  int iterations = 0;
  double solve_seconds = 0;
  std::string solver_report;
};

// The model's monitor for the samples (runs of evenly spaced samples each start at their first
// monitor reading and the hysteresis model relaxed at their first command): for tests, charts.
// exhaust_time_constant_s > 0: the directional model (time_constant_s while filling).
std::vector<double> simulate_dynamics(std::span<const DynamicsSample> samples, const PrandtlIshlinskii* hysteresis,
                                      double dead_time_s, double time_constant_s, double exhaust_time_constant_s = 0);

// samples: one channel's step and chirp rows in time order. hysteresis: the channel's forward
// model fitted on the monitor (nullptr: identity). Throws InputError(file, what, ...) for data
// that cannot identify anything: fewer than 200 samples in runs of even spacing, a monitor
// reading missing, a command or monitor that never moves.
DynamicsFit fit_dynamics(std::span<const DynamicsSample> samples, const PrandtlIshlinskii* hysteresis,
                         const DynamicsFitOptions& options, const std::string& file, const std::string& what);

}  // namespace palprig
