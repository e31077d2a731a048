#include "calibration/hysteresis_selection.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/input_error.hpp"

namespace palprig {

void held_out_errors(const PrandtlIshlinskii& fitted, std::span<const double> x, std::span<const double> y,
                     double& sum_squares, double& worst_kPa) {
  PrandtlIshlinskii m = fitted;
  m.reset(0.0);  // a run starts vented
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    const double e = m.apply_exhausting(x[k]) - y[k];
    sum_squares += e * e;
    worst_kPa = std::max(worst_kPa, std::abs(e));
  }
}

bool asymmetric_model_wins(double symmetric_rms_kPa, double asymmetric_rms_kPa, double min_gain,
                           double min_gain_kPa) noexcept {
  return asymmetric_rms_kPa < (1.0 - min_gain) * symmetric_rms_kPa &&
         symmetric_rms_kPa - asymmetric_rms_kPa >= min_gain_kPa;
}

HysteresisSelection select_hysteresis_model(std::span<const double> x, std::span<const double> y,
                                            std::span<const std::size_t> run_starts, const HysteresisFitOptions& o,
                                            double min_gain, double min_gain_kPa) {
  HysteresisSelection s;
  s.min_gain = min_gain;
  s.min_gain_kPa = min_gain_kPa;
  std::vector<std::size_t> starts(run_starts.begin(), run_starts.end());
  starts.erase(std::remove_if(starts.begin(), starts.end(), [&](std::size_t i) { return i >= x.size(); }),
               starts.end());
  if (starts.empty() || starts.front() != 0) starts.insert(starts.begin(), 0);
  if (starts.size() < 2) {
    s.reason = "one run only (no vent between repeats): nothing to hold out, symmetric model kept";
    return s;
  }
  double ss_sym = 0, ss_asym = 0, worst_sym = 0, worst_asym = 0;
  std::size_t held_out = 0;
  for (std::size_t f = 0; f < starts.size(); ++f) {
    const std::size_t lo = starts[f], hi = f + 1 < starts.size() ? starts[f + 1] : x.size();
    if (hi - lo < 3) continue;  // a closing vent alone: nothing of a loop to predict
    std::vector<double> x_train, y_train;
    x_train.reserve(x.size());
    y_train.reserve(x.size());
    for (std::size_t k = 0; k < x.size(); ++k)
      if (k < lo || k >= hi) {
        x_train.push_back(x[k]);
        y_train.push_back(y[k]);
      }
    HysteresisFitOptions sym = o, asym = o;
    sym.asymmetric = false;
    asym.asymmetric = true;
    // As many plays as the training runs support (4 samples per parameter: 1 + 2n, 1 + 3n).
    const std::size_t per4 = x_train.size() / 4;
    sym.operator_count = std::clamp<std::size_t>(per4 > 1 ? (per4 - 1) / 2 : 1, 1, o.operator_count);
    asym.operator_count = std::clamp<std::size_t>(per4 > 1 ? (per4 - 1) / 3 : 1, 1, o.operator_count);
    HysteresisFit fs, fa;
    try {
      fs = fit_hysteresis(x_train, y_train, sym, "held-out fit", "symmetric");
      fa = fit_hysteresis(x_train, y_train, asym, "held-out fit", "asymmetric");
    } catch (const InputError& e) {
      s.reason = std::string("not compared: a fit without run ") + std::to_string(f + 1) + " was refused (" + e.what() +
                 "); symmetric model kept";
      return s;
    }
    if (!fs.converged || !fa.converged) {
      s.reason = "not compared: Ceres did not converge on a fit without run " + std::to_string(f + 1) +
                 "; symmetric model kept";
      return s;
    }
    held_out_errors(fs.model, x.subspan(lo, hi - lo), y.subspan(lo, hi - lo), ss_sym, worst_sym);
    held_out_errors(fa.model, x.subspan(lo, hi - lo), y.subspan(lo, hi - lo), ss_asym, worst_asym);
    ++s.folds;
    held_out += hi - lo;
  }
  if (s.folds < 2) {
    s.reason = "fewer than 2 runs of 3 holds or more: nothing to hold out, symmetric model kept";
    return s;
  }
  s.compared = true;
  s.samples = held_out;
  s.symmetric = {std::sqrt(ss_sym / double(held_out)), worst_sym};
  s.asymmetric = {std::sqrt(ss_asym / double(held_out)), worst_asym};
  const bool relatively_better = s.asymmetric.rms_kPa < (1.0 - min_gain) * s.symmetric.rms_kPa;
  s.asymmetric_chosen = asymmetric_model_wins(s.symmetric.rms_kPa, s.asymmetric.rms_kPa, min_gain, min_gain_kPa);
  std::ostringstream why;
  why.setf(std::ios::fixed);
  why.precision(3);
  why << (s.asymmetric_chosen ? "asymmetric" : "symmetric") << " (held-out RMS over " << s.folds << " runs: symmetric "
      << s.symmetric.rms_kPa << " kPa, max " << s.symmetric.max_kPa << "; asymmetric " << s.asymmetric.rms_kPa
      << " kPa, max " << s.asymmetric.max_kPa << "; ";
  why.precision(2);
  if (s.asymmetric_chosen)
    why << s.symmetric.rms_kPa / s.asymmetric.rms_kPa << "x lower)";
  else if (!relatively_better)
    why << "the asymmetric model is not " << int(std::lround(100 * min_gain)) << " % better)";
  else
    why << "the asymmetric model is not " << min_gain_kPa << " kPa better)";
  s.reason = why.str();
  return s;
}

}  // namespace palprig
