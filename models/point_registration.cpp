#include "models/point_registration.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "core/error.hpp"

namespace palprig {

namespace {

Eigen::Matrix3Xd columns(const std::vector<Vec3_mm>& points) {
  Eigen::Matrix3Xd m(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int r = 0; r < 3; ++r) {
      if (!std::isfinite(points[i][r]))
        throw BadInput("fiducial " + std::to_string(i + 1) + " has a non-finite coordinate");
      m(r, static_cast<Eigen::Index>(i)) = points[i][r];
    }
  return m;
}

// The spread of a point set across its second direction: 0 for collinear points.
double second_spread_mm(const Eigen::Matrix3Xd& m) {
  const Eigen::Matrix3Xd centred = m.colwise() - m.rowwise().mean();
  const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(centred);
  return svd.singularValues()(1) / std::sqrt(double(m.cols()));
}

}  // namespace

PointRegistration register_points(const std::vector<Vec3_mm>& from, const std::vector<Vec3_mm>& to) {
  if (from.size() != to.size())
    throw BadInput("as many touched points as fiducials (got " + std::to_string(from.size()) + " and " +
                   std::to_string(to.size()) + ")");
  if (from.size() < 3) throw BadInput("at least 3 fiducials, got " + std::to_string(from.size()));
  const Eigen::Matrix3Xd a = columns(from), b = columns(to);
  // 1 mm of spread off the line: below that, the rotation about the line is noise.
  constexpr double kMinSpread_mm = 1.0;
  if (second_spread_mm(b) < kMinSpread_mm)
    throw BadInput("fiducials that are not all on one line (their spread off the line is under 1 mm)");
  if (second_spread_mm(a) < kMinSpread_mm)
    throw BadInput("touched points that are not all on one line (their spread off the line is under 1 mm)");
  const Eigen::Matrix4d t = Eigen::umeyama(a, b, false);
  PointRegistration out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.from_to.rotation[r][c] = t(r, c);
    out.from_to.translation_mm[r] = t(r, 3);
  }
  double sum = 0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const double e = distance_mm(out.from_to.apply(from[i]), to[i]);
    out.residual_mm.push_back(e);
    sum += e * e;
  }
  out.fre_mm = std::sqrt(sum / double(from.size()));
  return out;
}

}  // namespace palprig
