#include "calibration/dynamics_runs.hpp"

#include <algorithm>
#include <cmath>

#include "core/input_error.hpp"

namespace palprig::dynamics_runs {

Prepared prepare_runs(std::span<const DynamicsSample> s, const PrandtlIshlinskii* hysteresis, const std::string& file,
                      const std::string& what) {
  Prepared p;
  std::vector<double> gaps;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k].t_s > s[k - 1].t_s) gaps.push_back(s[k].t_s - s[k - 1].t_s);
  if (gaps.empty()) throw InputError(file, what, "step and chirp rows over time (at least 200 samples)");
  const auto middle = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2);
  std::nth_element(gaps.begin(), middle, gaps.end());
  p.period_s = *middle;
  PrandtlIshlinskii h = hysteresis ? *hysteresis : PrandtlIshlinskii{};
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (!std::isfinite(s[k].monitor_kPa) || !std::isfinite(s[k].command_kPa))
      throw InputError(file, "line " + std::to_string(s[k].line), "a monitor reading for the dynamics fit of " + what);
    const bool new_run = k == 0 || std::abs((s[k].t_s - s[k - 1].t_s) - p.period_s) > 0.25 * p.period_s;
    if (new_run) {
      if (!p.runs.empty() && p.runs.back().x.size() < 2) p.runs.pop_back();
      p.runs.emplace_back();
      h.reset(s[k].command_kPa);
    }
    Run& r = p.runs.back();
    // The pressure the regulator heads for: the command through the identified plays, which
    // narrow near 0 kPa as its exhaust does (as the tick runs them).
    r.x.push_back(h.is_identity() ? s[k].command_kPa : h.apply_exhausting(s[k].command_kPa));
    r.m.push_back(s[k].monitor_kPa);
    r.segment.push_back(s[k].segment);
  }
  if (!p.runs.empty() && p.runs.back().x.size() < 2) p.runs.pop_back();
  double cmin = 1e300, cmax = -1e300, mmin = 1e300, mmax = -1e300;
  for (const Run& r : p.runs) {
    p.residuals += r.x.size() - 1;
    for (std::size_t k = 0; k < r.x.size(); ++k) {
      cmin = std::min(cmin, r.x[k]), cmax = std::max(cmax, r.x[k]);
      mmin = std::min(mmin, r.m[k]), mmax = std::max(mmax, r.m[k]);
    }
  }
  if (p.residuals < 200)
    throw InputError(file, what,
                     "at least 200 evenly spaced step and chirp samples to identify the regulator's dynamics, got " +
                         std::to_string(p.residuals) + " (calibrate sweep --excitation ...,step,chirp)");
  if (!(cmax - cmin >= 1.0)) throw InputError(file, what, "step and chirp commands that move by at least 1 kPa");
  if (!(mmax - mmin >= 0.5))
    throw InputError(file, what, "a monitor that answers the step and chirp commands (it moved less than 0.5 kPa)");
  return p;
}

}  // namespace palprig::dynamics_runs
