#pragma once
// Identification of a Prandtl-Ishlinskii hysteresis model (models/hysteresis.hpp) from a
// quasi-static input/output sequence, with Ceres:
//
//   y_k = w0 * x_k + sum_i w_i * play_{r_i}[x]_k          (play states start relaxed at x_0)
//
// Parameters and their bounds keep the model invertible (Kuhnen): w0 >= min_linear_weight,
// w_i >= 0, and thresholds written as increments r_i = d_1 + ... + d_i with d_i >=
// min_threshold_step_kPa so they stay positive and strictly increasing.
// Stage 1 fixes the thresholds on a grid; the problem is then linear in the weights and is
// solved exactly as non-negative least squares (reweighted for a robust loss), and operators
// the data does not use are dropped. Stage 2 (Ceres) frees the thresholds too, with exact
// derivatives of the play operators propagated along the sequence. The play states depend on the whole history, so
// they are computed once per evaluation point in a ceres::EvaluationCallback and every sample
// is its own residual block, which keeps a robust loss per sample possible.
//
// With `asymmetric` the model is the generalised PI model of models/hysteresis.hpp, each play
// with a rising threshold r+_i and a falling one r-_i: stage 1 puts the pairs on a grid (every
// rising threshold with every falling one, NNLS keeps the few the data uses), stage 2 frees both
// thresholds of each kept play, bounded to [min_threshold_step_kPa, the input's range] (no order
// is needed: the model is inverted numerically at the actuator's state, not analytically).
#include <span>
#include <string>

#include "models/hysteresis.hpp"

namespace palprig {

enum class RobustLoss { none, huber, cauchy };

struct HysteresisFitOptions {
  std::size_t operator_count = 8;
  // Largest initial threshold; 0 picks it from the data (2.5x the half-width of the residual
  // band around a straight line, between 2 % and 50 % of the input range).
  double max_threshold_kPa = 0;
  bool refine_thresholds = true;
  bool asymmetric = false;  // separate rising and falling thresholds (generalised PI)
  // The plays as the rig runs them: near 0 kPa a play's band above the input narrows to the
  // input (a regulator commanded towards 0 kPa opens its exhaust and empties the actuator:
  // PrandtlIshlinskii::apply_exhausting), the model the tick inverts and the held-out comparison
  // scores. A sweep returns to 0 kPa between its runs; plain plays predict their upper edge there
  // (1-2 kPa) where the regulator reads 0, and those residuals pull the whole fit. false: the
  // plain plays.
  bool exhausting = true;
  double min_linear_weight = 0.01;  // keeps the inverse's gain at most 1/0.01
  double min_threshold_step_kPa = 0.05;
  RobustLoss loss = RobustLoss::none;
  double loss_scale_kPa = 1.0;  // residual size where the robust loss starts to bend
  int max_iterations = 200;
  int threads = 1;
};

struct HysteresisFit {
  PrandtlIshlinskii model;  // forward model, play states reset to 0
  std::size_t samples = 0;
  double rms_error_kPa = 0;
  double max_abs_error_kPa = 0;
  double r_squared = 0;             // of the model's output against the measured output
  double stage1_rms_error_kPa = 0;  // the grid fit, before Ceres moved the thresholds
  bool converged = false;           // stage 1 finished and Ceres reported CONVERGENCE in stage 2
  bool thresholds_refined = false;  // stage 2's result was kept (else the grid fit is returned)
  int iterations = 0;               // over both stages
  double solve_seconds = 0;
  std::string solver_report;  // Ceres' brief report of the last stage
};

// Forward simulation of a model over an input sequence, starting relaxed at input[0]; exhausting
// as HysteresisFitOptions::exhausting says.
void simulate_hysteresis(PrandtlIshlinskii model, std::span<const double> input_kPa, std::span<double> output_kPa,
                         bool exhausting = true);

// Throws InputError(file, what, ...) for unusable data: fewer samples than 4x the parameters,
// non-finite values, an input that never moves or never reverses (no hysteresis to see).
// When Ceres does not converge in stage 2 the result is stage 1's grid fit, with
// converged == false and the solver's report, so the caller can say so.
HysteresisFit fit_hysteresis(std::span<const double> input_kPa, std::span<const double> output_kPa,
                             const HysteresisFitOptions& options, const std::string& file, const std::string& what);

}  // namespace palprig
