#pragma once
// A rigid transform (rotation and translation, mm) and the pose of a tracked tool, which is the
// same thing: the transform from the tool's own frame to the tracker's (OpenIGTLink TRANSFORM,
// PLUS "StylusToTracker"). Plain arrays, trivially copyable, so poses cross threads through
// runtime/latest_value.hpp as they are.
#include <array>

namespace palprig {

using Vec3_mm = std::array<double, 3>;
using Rotation3 = std::array<std::array<double, 3>, 3>;  // row-major: rotation[row][column]

inline constexpr Rotation3 kIdentityRotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

struct RigidTransform {
  Rotation3 rotation = kIdentityRotation;
  Vec3_mm translation_mm{};

  // rotation * p + translation
  Vec3_mm apply(const Vec3_mm& p) const noexcept;
  // rotation * v (a direction, no translation)
  Vec3_mm rotate(const Vec3_mm& v) const noexcept;
  // this after first: p -> this(first(p))
  RigidTransform after(const RigidTransform& first) const noexcept;
  RigidTransform inverse() const noexcept;
};

// Whether r is a proper rotation: every entry finite, R^T R within `tolerance` of the identity
// entry by entry, and det(R) > 0. A tracker that lost a tool sometimes sends zeros; a file with
// a reflection or a scale is a mistake.
bool is_rotation(const Rotation3& r, double tolerance = 1e-3) noexcept;

// The rotation of a unit quaternion (x, y, z, w), as OpenIGTLink's POSITION carries it. The
// quaternion is normalised first; a zero or non-finite one gives the identity and false.
bool rotation_from_quaternion(double qx, double qy, double qz, double qw, Rotation3& out) noexcept;

double distance_mm(const Vec3_mm& a, const Vec3_mm& b) noexcept;

}  // namespace palprig
