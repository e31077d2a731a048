#pragma once
// The dynamics fit's stage 4: an exhaust lag that grows near 0 kPa. A regulator's exhaust has
// least pressure to push with near 0 kPa, so it empties the last kilopascals slower than it
// empties the first (the simulated plant's exhaust_lag_factor_at_0 and exhaust_lag_scale_kPa).
// From stage 3's fill and exhaust lags, Ceres frees two more parameters: the lag while
// exhausting at model output y is
//
//   tau_e(y) = tau_e (1 + (F - 1) s / (max(y, 0) + s))      (F at 0 kPa, tau_e far above s)
//
// (F = 1 is stage 3's model). The five parameters are fitted with automatic derivatives (Ceres
// Jets) propagated along the sequence, the dead time still a real number. The sweep's step
// segment falls to 0 kPa three times, so the exhaust below its lowest level is seen, not
// extrapolated (calibration/sweep_plan.cpp). Two more parameters can still fit noise: the
// model is kept only when it predicts samples it was not fitted on better, by cross-validation
// over blocks of the step and chirp rows (each block held out in turn, both models refitted
// without it and run over it), not by its own residual.
#include <vector>

#include "calibration/dynamics_runs.hpp"

namespace palprig {

struct ExhaustLagModel {
  double dead_time_s = 0, fill_time_constant_s = 0.05, exhaust_time_constant_s = 0.05;
  double factor_at_0 = 1.0;  // F: how many times slower the exhaust is at 0 kPa
  double scale_kPa = 10.0;   // s: the pressure below which it slows
};

struct ExhaustLagOptions {
  double max_dead_time_s = 0.3;
  double min_time_constant_s = 0.0005, max_time_constant_s = 2.0;
  double max_factor_at_0 = 10.0;
  double min_scale_kPa = 0.5, max_scale_kPa = 50.0;
  int max_iterations = 100;
  int folds = 4;                    // blocks are assigned to folds in turn
  double block_s = 0.3;             // the length of a held-out block
  double min_held_out_gain = 0.05;  // kept when the held-out RMS drops by this much
};

struct ExhaustLagFit {
  ExhaustLagModel model;  // fitted on every sample
  bool converged = false;
  int iterations = 0;
  double rms_residual_kPa = 0;
  // Held-out RMS (every block predicted by the model fitted without it): stage 3's model and this
  // one. kept: the latter is at least min_held_out_gain lower.
  double baseline_held_out_rms_kPa = 0, held_out_rms_kPa = 0;
  bool kept = false;
  std::string solver_report;
};

namespace dynamics_runs {

// Residuals (model - monitor) over every run, each run's first sample left out.
void exhaust_lag_residuals(const Prepared& p, const ExhaustLagModel& m, std::vector<double>& residuals);

// Stage 4 from stage 3's model (start: its dead time, fill and exhaust lags, F = 1).
ExhaustLagFit fit_exhaust_lag(const Prepared& p, const ExhaustLagModel& start, const ExhaustLagOptions& o);

}  // namespace dynamics_runs
}  // namespace palprig
