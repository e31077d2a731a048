#include "models/tissue_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace palprig {

FunctionScene::FunctionScene(TissueDefinition tissue, std::vector<ArterySpec> arteries)
    : field_(std::move(tissue)), arteries_(std::move(arteries), field_.definition().press.finger_radius_mm) {}

TissueSample FunctionScene::sample(const Point2_mm& at, double force_N, double t_s) const noexcept {
  TissueSample s = field_.sample(at, force_N, t_s);
  if (table_) {
    s.fe_stress = true;
    s.stress_rise_kPa = fe_stress_rise_kPa(at, force_N);
  }
  return s;
}

void FunctionScene::use_fe_table(std::shared_ptr<const FeStressTable> table) {
  table_ = std::move(table);
  nodule_count_ = 0;
  if (!table_) return;
  const auto& layers = field_.definition().layers;
  for (const InclusionOutline& o : outlines(InclusionKind::tumor)) {
    if (nodule_count_ == nodules_.size()) break;
    const double centre_depth = (o.top_depth_mm + o.bottom_depth_mm) / 2;
    const double around = layers[std::size_t(field_.layer_at(centre_depth))].stiffness_kPa;
    nodules_[nodule_count_++] = {o.x_mm, o.y_mm, o.top_depth_mm, 2 * o.radius_mm, o.stiffness_kPa / around};
  }
}

double FunctionScene::fe_stress_rise_kPa(const Point2_mm& at, double force_N) const noexcept {
  if (!table_ || !(force_N > 0)) return 0.0;
  const double indentation = field_.definition().press.indentation_mm(force_N);
  const double far = table_->axes().offset_mm.back();
  double rise = 0;
  for (std::size_t i = 0; i < nodule_count_; ++i) {
    const TableNodule& n = nodules_[i];
    const double offset = std::hypot(at.x_mm - n.x_mm, at.y_mm - n.y_mm);
    if (offset > far) continue;  // beyond the table (whose last offset is where the rise has died out)
    rise = std::max(rise, table_->rise_kPa(indentation, n.cover_mm, n.diameter_mm, n.contrast, offset));
  }
  return rise;
}

DragSetting FunctionScene::drag(int layer) const noexcept {
  const auto& layers = field_.definition().layers;
  if (layers.empty()) return {0, 0, 0};
  // The layer the fingertip has sunk into, or the nearest above it that says how it drags: a
  // firm press into the fat under the skin still carries the skin (and all under it) along.
  const std::size_t pressed = layer < 0 ? 0 : std::min(std::size_t(layer), layers.size() - 1);
  for (std::size_t i = pressed + 1; i-- > 0;)
    if (layers[i].drag_given) return layers[i].drag;
  return {0, 0, 0};
}

std::vector<InclusionOutline> FunctionScene::outlines(InclusionKind kind) const {
  // The bounding boxes of blobby shapes are loose, so the outline is measured: the shape is
  // sampled on a grid inside its box (0.5 mm across, 0.5 mm deep, at least 40 steps per axis)
  // and the outline is the circle around the inside points' centroid that holds them all. At
  // most 128 steps per axis: a shape larger than 64 mm is outlined more coarsely, rather than
  // a 10 m sphere costing 10^13 samples (a load that never ends).
  std::vector<InclusionOutline> out;
  for (const Inclusion& inc : field_.definition().inclusions) {
    if (inc.kind != kind) continue;
    const Box3_mm b = inc.shape.bounds();
    if (b.empty()) continue;
    auto steps = [](double lo, double hi) {
      return std::clamp(static_cast<int>(std::min(std::ceil((hi - lo) / 0.5), 1e6)), 40, 128);
    };
    const int nx = steps(b.lo.x_mm, b.hi.x_mm), ny = steps(b.lo.y_mm, b.hi.y_mm), nz = steps(b.lo.z_mm, b.hi.z_mm);
    auto at = [](double lo, double hi, int i, int n) { return lo + (hi - lo) * (i + 0.5) / n; };
    std::vector<Point2_mm> columns;  // (x, y) with any inside point
    double top = std::numeric_limits<double>::infinity(), bottom = -top;
    for (int ix = 0; ix < nx; ++ix)
      for (int iy = 0; iy < ny; ++iy) {
        const double x = at(b.lo.x_mm, b.hi.x_mm, ix, nx), y = at(b.lo.y_mm, b.hi.y_mm, iy, ny);
        bool any = false;
        for (int iz = 0; iz < nz; ++iz) {
          const double z = at(b.lo.z_mm, b.hi.z_mm, iz, nz);
          if (!inc.shape.contains({x, y, z})) continue;
          any = true;
          top = std::min(top, z);
          bottom = std::max(bottom, z);
        }
        if (any) columns.push_back({x, y});
      }
    if (columns.empty()) continue;  // too thin to sample: nothing a finger could find
    InclusionOutline o;
    o.name = inc.name;
    o.kind = inc.kind;
    for (const Point2_mm& c : columns) {
      o.x_mm += c.x_mm / static_cast<double>(columns.size());
      o.y_mm += c.y_mm / static_cast<double>(columns.size());
    }
    const double half_cell = 0.5 * std::hypot((b.hi.x_mm - b.lo.x_mm) / nx, (b.hi.y_mm - b.lo.y_mm) / ny);
    for (const Point2_mm& c : columns)
      o.radius_mm = std::max(o.radius_mm, std::hypot(c.x_mm - o.x_mm, c.y_mm - o.y_mm) + half_cell);
    o.top_depth_mm = std::max(top, 0.0);
    o.bottom_depth_mm = bottom;
    o.stiffness_kPa = inc.stiffness_kPa;
    out.push_back(o);
  }
  return out;
}

}  // namespace palprig
