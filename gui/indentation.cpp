#include "gui/indentation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace palprig::gui {

double IndentationModel::depth_mm(double force_N, double stiffness) const noexcept {
  if (!(force_N > 0) || !std::isfinite(force_N) || !std::isfinite(stiffness)) return 0.0;
  const double s = std::clamp(stiffness, 0.0, 1.0);
  const double soft_per_N = soft_depth_mm / reference_force_N;
  const double d = force_N * soft_per_N / (1.0 + s * (hard_over_soft_modulus - 1.0));
  return std::min(d, max_depth_mm);
}

std::vector<GridVertex> tiered_grid(double x_mm, double y_mm, double depth_mm, int n, double cell_mm, double drag_x_mm,
                                    double drag_y_mm) {
  if (!std::isfinite(drag_x_mm) || !std::isfinite(drag_y_mm)) drag_x_mm = drag_y_mm = 0;
  std::vector<GridVertex> v;
  if (n < 1) return v;
  const std::size_t side = 2 * static_cast<std::size_t>(n) + 1;  // n >= 1 here
  v.reserve(side * side);
  for (int r = -n; r <= n; ++r)
    for (int c = -n; c <= n; ++c) {
      const int tier = std::max(std::abs(r), std::abs(c));
      const double carried = double(n - tier) / double(n);
      v.push_back({x_mm - drag_x_mm + c * cell_mm, y_mm - drag_y_mm + r * cell_mm, drag_x_mm * carried,
                   drag_y_mm * carried, depth_mm * carried, tier});
    }
  return v;
}

}  // namespace palprig::gui
