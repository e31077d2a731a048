#include "models/load_cell.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

double SimulatedLoadCell::force_N(double depth_mm) const noexcept {
  return std::isfinite(depth_mm) && depth_mm > 0 ? p_.stiffness_N_per_mm * depth_mm : 0.0;
}

double SimulatedLoadCell::volts(double depth_mm, double extra_load_N) noexcept {
  const double load_N = force_N(depth_mm) + (std::isfinite(extra_load_N) ? std::max(extra_load_N, 0.0) : 0.0);
  const double v = p_.tare_V + load_N / p_.N_per_V + p_.noise_sd_V * noise_(rng_);
  return std::clamp(v, 0.0, p_.max_V);
}

}  // namespace palprig
