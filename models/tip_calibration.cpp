#include "models/tip_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "core/error.hpp"

namespace palprig {

Vec3_mm digitize_tip(const RigidTransform& sensor, const Vec3_mm& p) noexcept {
  Vec3_mm d{p[0] - sensor.translation_mm[0], p[1] - sensor.translation_mm[1], p[2] - sensor.translation_mm[2]};
  // R^-1 = R^T for a rotation.
  Vec3_mm out{};
  for (int r = 0; r < 3; ++r)
    out[r] = sensor.rotation[0][r] * d[0] + sensor.rotation[1][r] * d[1] + sensor.rotation[2][r] * d[2];
  return out;
}

namespace {

double angle_between_deg(const Rotation3& a, const Rotation3& b) {
  // trace(A^T B) = 1 + 2 cos(theta)
  double trace = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) trace += a[r][c] * b[r][c];
  return std::acos(std::clamp((trace - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

PivotCalibration pivot_calibrate(const std::vector<RigidTransform>& poses, double min_spread_deg) {
  if (poses.size() < 4) throw BadInput("at least 4 poses, got " + std::to_string(poses.size()));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!is_rotation(poses[i].rotation) || !std::isfinite(poses[i].translation_mm[0]) ||
        !std::isfinite(poses[i].translation_mm[1]) || !std::isfinite(poses[i].translation_mm[2]))
      throw BadInput("pose " + std::to_string(i + 1) + " is not a rigid transform");
  }
  PivotCalibration out;
  for (std::size_t i = 0; i < poses.size(); ++i)
    for (std::size_t j = i + 1; j < poses.size(); ++j)
      out.rotation_spread_deg =
          std::max(out.rotation_spread_deg, angle_between_deg(poses[i].rotation, poses[j].rotation));
  if (out.rotation_spread_deg < min_spread_deg)
    throw BadInput("poses that pivot at least " + std::to_string(int(min_spread_deg)) + " degrees apart, got " +
                   std::to_string(out.rotation_spread_deg) + " degrees");
  const auto n = static_cast<Eigen::Index>(poses.size());
  Eigen::MatrixXd a(3 * n, 6);
  Eigen::VectorXd b(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const RigidTransform& p = poses[static_cast<std::size_t>(i)];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) a(3 * i + r, c) = p.rotation[r][c];
      for (int c = 0; c < 3; ++c) a(3 * i + r, 3 + c) = r == c ? -1.0 : 0.0;
      b(3 * i + r) = -p.translation_mm[r];
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  // Turning about one axis only leaves the tip along that axis free: A loses rank.
  if (s(5) < 1e-3 * s(0))
    throw BadInput("poses that turn about more than one axis (pivot the tool in a cone, not in one plane)");
  const Eigen::VectorXd x = svd.solve(b);
  for (int r = 0; r < 3; ++r) {
    out.tip_mm[r] = x(r);
    out.pivot_mm[r] = x(3 + r);
  }
  double sum = 0;
  for (const RigidTransform& p : poses) {
    const double e = distance_mm(p.apply(out.tip_mm), out.pivot_mm);
    sum += e * e;
    out.max_mm = std::max(out.max_mm, e);
  }
  out.rms_mm = std::sqrt(sum / double(poses.size()));
  return out;
}

}  // namespace palprig
