#pragma once
// The step and chirp samples of one channel as the dynamics fits use them: runs of evenly spaced
// samples (the model restarts at each run's first sample), the commands passed through the
// channel's hysteresis model. Shared by dynamics_fit.cpp and exhaust_lag_fit.cpp; not a public
// interface.
#include <span>
#include <string>
#include <vector>

#include "calibration/sweep_csv.hpp"
#include "models/hysteresis.hpp"

namespace palprig::dynamics_runs {

// Evenly spaced runs of samples: the model restarts at each run's first sample.
struct Run {
  std::vector<double> x;  // the hysteresis model's output for the commands
  std::vector<double> m;  // monitor
  std::vector<SweepSegment> segment;
};

struct Prepared {
  double period_s = 0;
  std::vector<Run> runs;
  std::size_t residuals = 0;
};

// Throws InputError(file, what, ...) for data that cannot identify anything (fit_dynamics' refusals).
Prepared prepare_runs(std::span<const DynamicsSample> s, const PrandtlIshlinskii* hysteresis, const std::string& file,
                      const std::string& what);

}  // namespace palprig::dynamics_runs
