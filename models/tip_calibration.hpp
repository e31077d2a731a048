#pragma once
// Where the fingertip is in a tracked sensor's own frame (the tip offset p_local), two ways:
//
//   static digitization (paper 003, eq. 2): a digitizer's tip touches the fingertip once;
//     p_local = R^-1 (p_digitized - o), with (R, o) the finger sensor's pose at that instant.
//   pivot calibration: the tip rests in a divot while the tool pivots about it; every pose
//     (R_i, t_i) then satisfies R_i p_local + t_i = p_pivot, solved for p_local and p_pivot by
//     linear least squares over all poses. The RMS of |R_i p_local + t_i - p_pivot| says how
//     well the tip stayed put (and how good the tracker is).
//
// The fingertip at time t is then p(t) = o(t) + R(t) p_local (paper 003, eq. 1).
#include <vector>

#include "models/rigid_transform.hpp"

namespace palprig {

Vec3_mm digitize_tip(const RigidTransform& sensor_pose, const Vec3_mm& digitized_mm) noexcept;

struct PivotCalibration {
  Vec3_mm tip_mm{};    // in the tool's frame
  Vec3_mm pivot_mm{};  // in the tracker's frame
  double rms_mm = 0, max_mm = 0;
  double rotation_spread_deg = 0;  // largest angle between two of the poses used
};

// Throws BadInput for fewer than 4 poses, non-finite or non-rotation poses, or
// poses that turn less than `min_spread_deg` apart or about one axis only (the tip along that
// axis is then undetermined).
PivotCalibration pivot_calibrate(const std::vector<RigidTransform>& poses, double min_spread_deg = 10.0);

}  // namespace palprig
