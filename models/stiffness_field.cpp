#include "models/stiffness_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.hpp"

namespace palprig {

namespace {

constexpr std::size_t kDepthSamples = 24;
constexpr double kReachInContactRadii = 4.0;

struct DepthKernel {
  std::array<double, kDepthSamples> u{};       // depth / contact radius
  std::array<double, kDepthSamples> weight{};  // normalised to sum 1
};

// Midpoint samples of the Boussinesq axis stress under a loaded disc, 0..4 contact radii.
const DepthKernel kDepth = [] {
  DepthKernel k;
  double sum = 0;
  for (std::size_t i = 0; i < kDepthSamples; ++i) {
    const double u = kReachInContactRadii * (static_cast<double>(i) + 0.5) / kDepthSamples;
    k.u[i] = u;
    k.weight[i] = 1.0 - u * u * u / std::pow(1.0 + u * u, 1.5);
    sum += k.weight[i];
  }
  for (double& w : k.weight) w /= sum;
  return k;
}();

// Centre for the inner disc (65 % of a Hertz load lies inside a / sqrt(2)), four points at
// 0.75 a for the annulus. A bone under a point bears on the finger with the Hertz contact
// pressure there relative to the centre's: sqrt(1 - 0.75^2) = 0.66 at the ring.
struct LateralPoint {
  double dx, dy, weight, bearing;
};
constexpr double kRingBearing = 0.6614378277661477;
constexpr std::array<LateralPoint, 5> kLateral{{
    {0.0, 0.0, 0.65, 1.0},
    {0.75, 0.0, 0.0875, kRingBearing},
    {-0.75, 0.0, 0.0875, kRingBearing},
    {0.0, 0.75, 0.0875, kRingBearing},
    {0.0, -0.75, 0.0875, kRingBearing},
}};

void need_field(bool ok, const std::string& what) {
  if (!ok) throw BadInput("StiffnessField: " + what);
}

bool positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

const char* to_string(InclusionKind k) noexcept {
  switch (k) {
    case InclusionKind::tumor: return "tumor";
    case InclusionKind::organ: return "organ";
    case InclusionKind::bone: return "bone";
    case InclusionKind::ligament: return "ligament";
    case InclusionKind::other: return "other";
  }
  return "other";
}

bool BodyOutline::contains(const Point2_mm& p) const noexcept {
  const double u = std::abs((p.x_mm - centre.x_mm) / half_width_mm);
  const double v = std::abs((p.y_mm - centre.y_mm) / half_height_mm);
  if (!(u <= 1.0 && v <= 1.0)) return false;  // also refuses NaN
  return std::pow(u, exponent) + std::pow(v, exponent) <= 1.0;
}

double PressModel::indentation_mm(double force_N) const noexcept {
  if (!(force_N > 0)) return 0.0;
  return reference_indentation_mm * std::cbrt((force_N / reference_force_N) * (force_N / reference_force_N));
}

double PressModel::contact_radius_mm(double force_N) const noexcept {
  return std::max(std::sqrt(finger_radius_mm * indentation_mm(force_N)), min_contact_radius_mm);
}

double PressModel::reach_mm(double force_N) const noexcept { return kReachInContactRadii * contact_radius_mm(force_N); }

StiffnessField::StiffnessField(TissueDefinition d) : def_(std::move(d)) {
  const BodyOutline& b = def_.body;
  need_field(std::isfinite(b.centre.x_mm) && std::isfinite(b.centre.y_mm), "body centre must be finite");
  need_field(positive(b.half_width_mm) && positive(b.half_height_mm), "body half sizes must be > 0");
  need_field(std::isfinite(b.exponent) && b.exponent >= 2, "body exponent must be >= 2");
  need_field(!def_.layers.empty(), "at least one tissue layer is needed");
  need_field(def_.layers.size() <= kMaxLayers, "at most " + std::to_string(kMaxLayers) + " layers");
  need_field(def_.inclusions.size() <= kMaxInclusions, "at most " + std::to_string(kMaxInclusions) + " inclusions");
  need_field(positive(def_.felt.soft_kPa) && positive(def_.felt.hard_kPa) && def_.felt.soft_kPa < def_.felt.hard_kPa,
             "felt range needs 0 < soft < hard");
  need_field(def_.support_kPa == 0 || positive(def_.support_kPa), "support modulus must be > 0 (or 0: none)");
  need_field(std::isfinite(def_.respiration.period_s) && def_.respiration.period_s >= 0,
             "breathing period must be >= 0");
  const PressModel& pm = def_.press;
  need_field(positive(pm.finger_radius_mm) && positive(pm.reference_force_N) && positive(pm.reference_indentation_mm) &&
                 positive(pm.min_contact_radius_mm),
             "press model values must be > 0");

  log_soft_ = std::log(def_.felt.soft_kPa);
  inv_log_span_ = 1.0 / (std::log(def_.felt.hard_kPa) - log_soft_);
  double depth = 0;
  for (std::size_t i = 0; i < def_.layers.size(); ++i) {
    const TissueLayer& l = def_.layers[i];
    need_field(positive(l.thickness_mm) && positive(l.stiffness_kPa),
               "layer '" + l.name + "' needs thickness and modulus > 0");
    need_field(std::isfinite(l.drag.f_stick_N) && l.drag.f_stick_N >= 0 && std::isfinite(l.drag.d_lat_max_mm) &&
                   l.drag.d_lat_max_mm >= 0 && std::isfinite(l.drag.relax_s) && l.drag.relax_s >= 0,
               "layer '" + l.name + "' needs a drag with f_stick_N, d_lat_max_mm and relax_s >= 0");
    depth += l.thickness_mm;
    layer_bottom_mm_[i] = depth;
    layer_level_[i] = normalised(l.stiffness_kPa);
  }
  support_level_ = def_.support_kPa > 0 ? normalised(def_.support_kPa) : layer_level_[def_.layers.size() - 1];
  for (std::size_t i = 0; i < def_.inclusions.size(); ++i) {
    const Inclusion& inc = def_.inclusions[i];
    need_field(inc.shape.defined(), "inclusion '" + inc.name + "' has no shape");
    need_field(positive(inc.stiffness_kPa), "inclusion '" + inc.name + "' needs a modulus > 0");
    const Point3_mm& e = inc.breathing_excursion_mm;
    need_field(std::isfinite(e.x_mm) && std::isfinite(e.y_mm) && std::isfinite(e.z_mm),
               "inclusion '" + inc.name + "' breathing excursion must be finite");
    inclusion_level_[i] = normalised(inc.stiffness_kPa);
    inclusion_rigid_[i] = inc.kind == InclusionKind::bone || inc.kind == InclusionKind::ligament;
    inclusion_box_[i] = inc.shape.bounds();
    if (def_.respiration.breathing() && (e.x_mm != 0 || e.y_mm != 0 || e.z_mm != 0)) any_breathing_ = true;
  }
}

double StiffnessField::normalised(double modulus_kPa) const noexcept {
  if (!(modulus_kPa > 0)) return 0.0;
  return std::clamp((std::log(modulus_kPa) - log_soft_) * inv_log_span_, 0.0, 1.0);
}

int StiffnessField::layer_at(double depth_mm) const noexcept {
  const std::size_t n = def_.layers.size();
  for (std::size_t i = 0; i < n; ++i)
    if (depth_mm < layer_bottom_mm_[i]) return static_cast<int>(i);
  return static_cast<int>(n - 1);
}

double StiffnessField::modulus_kPa(const Point3_mm& p, double t_s) const noexcept {
  if (!def_.body.contains({p.x_mm, p.y_mm}) || !(p.z_mm >= 0)) return 0.0;
  for (std::size_t i = def_.inclusions.size(); i-- > 0;) {
    const Inclusion& inc = def_.inclusions[i];
    const Point3_mm d = def_.respiration.displacement(inc.breathing_excursion_mm, t_s);
    if (inc.shape.contains({p.x_mm - d.x_mm, p.y_mm - d.y_mm, p.z_mm - d.z_mm})) return inc.stiffness_kPa;
  }
  const std::size_t n = def_.layers.size();
  for (std::size_t i = 0; i < n; ++i)
    if (p.z_mm < layer_bottom_mm_[i]) return def_.layers[i].stiffness_kPa;
  return def_.support_kPa > 0 ? def_.support_kPa : def_.layers[n - 1].stiffness_kPa;
}

StiffnessField::Level StiffnessField::level_at(const Point3_mm& p, const std::uint16_t* candidates, std::size_t count,
                                               const std::array<Point3_mm, kMaxInclusions>& shift) const noexcept {
  // Later inclusions win, so search from the end of the candidate list (kept in file order).
  for (std::size_t c = count; c-- > 0;) {
    const std::size_t i = candidates[c];
    const Point3_mm q{p.x_mm - shift[i].x_mm, p.y_mm - shift[i].y_mm, p.z_mm - shift[i].z_mm};
    if (def_.inclusions[i].shape.contains(q)) return {inclusion_level_[i], inclusion_rigid_[i]};
  }
  const std::size_t n = def_.layers.size();
  for (std::size_t i = 0; i < n; ++i)
    if (p.z_mm < layer_bottom_mm_[i]) return {layer_level_[i], false};
  return {support_level_, false};
}

TissueSample StiffnessField::sample(const Point2_mm& at, double force_N, double t_s) const noexcept {
  if (!std::isfinite(at.x_mm) || !std::isfinite(at.y_mm) || !def_.body.contains(at)) return {0.0, -1};
  const double a = def_.press.contact_radius_mm(force_N);
  const double reach = kReachInContactRadii * a;
  const double sunk = def_.press.indentation_mm(force_N);

  std::array<Point3_mm, kMaxInclusions> shift{};
  const std::size_t n_inc = def_.inclusions.size();
  if (any_breathing_)
    for (std::size_t i = 0; i < n_inc; ++i)
      shift[i] = def_.respiration.displacement(def_.inclusions[i].breathing_excursion_mm, t_s);

  double felt = 0, pressed_on = 0;
  for (const LateralPoint& lp : kLateral) {
    const Point2_mm q{at.x_mm + lp.dx * a, at.y_mm + lp.dy * a};
    if (!def_.body.contains(q)) continue;  // off the body: air, felt as 0
    // Broad phase: the inclusions whose (shifted) box meets this column of the loaded zone.
    std::array<std::uint16_t, kMaxInclusions> cand{};
    std::size_t n_cand = 0;
    for (std::size_t i = 0; i < n_inc; ++i) {
      const Box3_mm& b = inclusion_box_[i];
      const double x = q.x_mm - shift[i].x_mm, y = q.y_mm - shift[i].y_mm;
      if (x >= b.lo.x_mm && x <= b.hi.x_mm && y >= b.lo.y_mm && y <= b.hi.y_mm && b.hi.z_mm + shift[i].z_mm >= 0 &&
          b.lo.z_mm + shift[i].z_mm <= reach)
        cand[n_cand++] = static_cast<std::uint16_t>(i);
    }
    double column = 0;
    int first_rigid = -1;
    double rigid_level = 0;
    for (std::size_t k = 0; k < kDepthSamples; ++k) {
      const Level l = level_at({q.x_mm, q.y_mm, kDepth.u[k] * a}, cand.data(), n_cand, shift);
      column += kDepth.weight[k] * l.value;
      if (l.rigid && first_rigid < 0) {
        first_rigid = static_cast<int>(k);
        rigid_level = l.value;
      }
    }
    if (first_rigid >= 0) {
      // Where the bone starts, to a fraction of a millimetre: bisect between the last sample
      // above it and the first in it.
      double above = first_rigid > 0 ? kDepth.u[static_cast<std::size_t>(first_rigid) - 1] * a : 0.0;
      double in = kDepth.u[static_cast<std::size_t>(first_rigid)] * a;
      if (level_at({q.x_mm, q.y_mm, above}, cand.data(), n_cand, shift).rigid) in = above;
      for (int it = 0; it < 8 && in - above > 0.05; ++it) {
        const double mid = 0.5 * (above + in);
        if (level_at({q.x_mm, q.y_mm, mid}, cand.data(), n_cand, shift).rigid)
          in = mid;
        else
          above = mid;
      }
      const double u = std::max(in - sunk, 0.0) / a;
      pressed_on = std::max(pressed_on, lp.bearing * rigid_level * (1.0 - u * u * u / std::pow(1.0 + u * u, 1.5)));
    }
    felt += lp.weight * column;
  }
  // The finger is one rigid body: resting on bone anywhere under its contact stops it.
  return {std::clamp(std::max(felt, pressed_on), 0.0, 1.0), layer_at(sunk)};
}

double StiffnessField::worst_case_sample_cost() const noexcept {
  const std::size_t n = def_.inclusions.size();
  std::array<Box3_mm, kMaxInclusions> box{};
  std::array<double, kMaxInclusions> cost{};
  bool any_rigid = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Point3_mm& e = def_.inclusions[i].breathing_excursion_mm;
    const double ex = any_breathing_ ? std::abs(e.x_mm) : 0.0, ey = any_breathing_ ? std::abs(e.y_mm) : 0.0;
    box[i] = inclusion_box_[i];
    box[i].lo.x_mm -= ex;
    box[i].hi.x_mm += ex;
    box[i].lo.y_mm -= ey;
    box[i].hi.y_mm += ey;
    cost[i] = def_.inclusions[i].shape.worst_case_cost();
    any_rigid = any_rigid || inclusion_rigid_[i];
  }
  // The largest sum of costs over the boxes that hold one column is reached at a corner
  // (largest lo.x, largest lo.y) of some overlap, i.e. at (lo.x of one box, lo.y of another).
  double worst_point = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (box[a].empty()) continue;
    for (std::size_t b = 0; b < n; ++b) {
      if (box[b].empty()) continue;
      const double x = box[a].lo.x_mm, y = box[b].lo.y_mm;
      double sum = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (!box[i].empty() && x >= box[i].lo.x_mm && x <= box[i].hi.x_mm && y >= box[i].lo.y_mm && y <= box[i].hi.y_mm)
          sum += cost[i];
      worst_point = std::max(worst_point, sum);
    }
  }
  // Per lateral point: the depth samples, and with bone or ligament the probe above it and
  // the bisection (at most 8 steps).
  const double points_per_column = double(kDepthSamples) + (any_rigid ? 9.0 : 0.0);
  return double(kLateral.size()) * points_per_column * worst_point;
}

SceneBounds StiffnessField::bounds() const noexcept {
  const BodyOutline& b = def_.body;
  return {b.centre.x_mm - b.half_width_mm, b.centre.y_mm - b.half_height_mm, b.centre.x_mm + b.half_width_mm,
          b.centre.y_mm + b.half_height_mm};
}

}  // namespace palprig
