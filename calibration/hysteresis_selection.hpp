#pragma once
// Which hysteresis model a channel gets: the symmetric Prandtl-Ishlinskii model or the
// asymmetric (generalised, separate rising and falling thresholds) one of models/hysteresis.hpp,
// chosen by the error each makes on data it was not fitted on, not by its own residual (the
// asymmetric model has more parameters, so its residual is never worse on the data it saw).
//
// The sweep's runs are its folds: every run (a staircase repeat, the random levels, the sine)
// starts vented, so a model fitted on the other runs can be run on it from a known state. For
// each run, both classes are fitted on the others and simulated over it as the tick's copy
// runs (exhausting at 0 kPa, play states empty at the vent); the held-out RMS over all runs
// decides. The asymmetric model must beat the symmetric one by min_gain (10 %) of its held-out
// RMS and by min_gain_kPa (0.05 kPa) outright: within that the simpler model stays, so a
// symmetric regulator keeps the model it always had (fitted as the tick runs its plays, both
// classes can fit such a regulator's holds to about 0.02 kPa, where a 10 % difference is noise
// that no fingertip could feel). Fewer than 2 runs: nothing to hold out, the symmetric model stays and the reason says
// so.
#include <cstddef>
#include <limits>
#include <span>
#include <string>

#include "calibration/hysteresis_fit.hpp"

namespace palprig {

struct HysteresisHeldOut {
  double rms_kPa = std::numeric_limits<double>::quiet_NaN();
  double max_kPa = std::numeric_limits<double>::quiet_NaN();
};

struct HysteresisSelection {
  bool compared = false;  // enough runs to hold out and both classes fitted on every fold
  std::size_t folds = 0;  // runs held out
  std::size_t samples = 0;
  HysteresisHeldOut symmetric, asymmetric;
  bool asymmetric_chosen = false;
  double min_gain = 0.10;
  double min_gain_kPa = 0.05;
  std::string reason;  // one line: what won and by how much, or why nothing was compared
};

// The rule: the asymmetric model's held-out RMS at least min_gain (a fraction) and min_gain_kPa
// below the symmetric one's.
bool asymmetric_model_wins(double symmetric_rms_kPa, double asymmetric_rms_kPa, double min_gain,
                           double min_gain_kPa) noexcept;

// run_starts: the index in x/y where each run begins (ascending, the first 0). Fits use
// `options` (its `asymmetric` is set per class). Never throws for a fold that cannot be fitted
// (too few samples left, Ceres not converging): the comparison is then not made and the reason
// says why; the caller keeps the symmetric model.
HysteresisSelection select_hysteresis_model(std::span<const double> x_kPa, std::span<const double> y_kPa,
                                            std::span<const std::size_t> run_starts,
                                            const HysteresisFitOptions& options, double min_gain = 0.10,
                                            double min_gain_kPa = 0.05);

// The held-out error of a fitted model over one run, as the tick's copy would follow it.
void held_out_errors(const PrandtlIshlinskii& model, std::span<const double> x_kPa, std::span<const double> y_kPa,
                     double& sum_squares, double& worst_kPa);

}  // namespace palprig
