#pragma once
// Paired-point registration from tracker space to scene space: fiducials on the phantom whose
// scene coordinates are known are touched with the tracked tip; the rigid transform that best
// maps the touched points onto the known ones (least squares, Umeyama's closed form through
// Eigen::umeyama, no scaling) and how well it fits: the fiducial registration error (FRE), the
// RMS distance between each known fiducial and its touched point carried across.
#include <string>
#include <vector>

#include "models/rigid_transform.hpp"

namespace palprig {

struct PointRegistration {
  RigidTransform from_to;           // maps `from` points onto `to` points
  double fre_mm = 0;                // RMS of residual_mm
  std::vector<double> residual_mm;  // per fiducial: |to - from_to(from)|
};

// Throws BadInput (with what is wrong) for fewer than 3 pairs, different counts,
// non-finite coordinates, or points that are (nearly) collinear in either set: the rotation
// about their line would be undetermined.
PointRegistration register_points(const std::vector<Vec3_mm>& from, const std::vector<Vec3_mm>& to);

}  // namespace palprig
