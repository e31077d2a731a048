#include "models/rigid_transform.hpp"

#include <cmath>

namespace palprig {

Vec3_mm RigidTransform::rotate(const Vec3_mm& v) const noexcept {
  Vec3_mm out{};
  for (int r = 0; r < 3; ++r) out[r] = rotation[r][0] * v[0] + rotation[r][1] * v[1] + rotation[r][2] * v[2];
  return out;
}

Vec3_mm RigidTransform::apply(const Vec3_mm& p) const noexcept {
  Vec3_mm out = rotate(p);
  for (int r = 0; r < 3; ++r) out[r] += translation_mm[r];
  return out;
}

RigidTransform RigidTransform::after(const RigidTransform& first) const noexcept {
  RigidTransform out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out.rotation[r][c] = rotation[r][0] * first.rotation[0][c] + rotation[r][1] * first.rotation[1][c] +
                           rotation[r][2] * first.rotation[2][c];
  out.translation_mm = apply(first.translation_mm);
  return out;
}

RigidTransform RigidTransform::inverse() const noexcept {
  RigidTransform out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out.rotation[r][c] = rotation[c][r];
  const Vec3_mm t = out.rotate(translation_mm);
  for (int r = 0; r < 3; ++r) out.translation_mm[r] = -t[r];
  return out;
}

bool is_rotation(const Rotation3& m, double tolerance) noexcept {
  for (const auto& row : m)
    for (double v : row)
      if (!std::isfinite(v)) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double dot = m[0][i] * m[0][j] + m[1][i] * m[1][j] + m[2][i] * m[2][j];
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > tolerance) return false;
    }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return det > 0;
}

bool rotation_from_quaternion(double x, double y, double z, double w, Rotation3& r) noexcept {
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  if (!std::isfinite(n) || n < 1e-9) {
    r = kIdentityRotation;
    return false;
  }
  x /= n, y /= n, z /= n, w /= n;
  r = {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
        {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
        {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
  return true;
}

double distance_mm(const Vec3_mm& a, const Vec3_mm& b) noexcept {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace palprig
