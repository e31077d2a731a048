#include "models/frep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/error.hpp"

namespace palprig {

namespace {

constexpr double kOutside = -1.0;  // value reported for points outside a node's box

void need_shape(bool ok, const char* what) {
  if (!ok) throw BadInput(std::string("FrepShape: ") + what);
}

bool finite(const Point3_mm& p) { return std::isfinite(p.x_mm) && std::isfinite(p.y_mm) && std::isfinite(p.z_mm); }

Box3_mm box_around(const Point3_mm& c, double ex, double ey, double ez) {
  return {{c.x_mm - ex, c.y_mm - ey, c.z_mm - ez}, {c.x_mm + ex, c.y_mm + ey, c.z_mm + ez}};
}

Box3_mm empty_box() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

Box3_mm merge(const Box3_mm& a, const Box3_mm& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {{std::min(a.lo.x_mm, b.lo.x_mm), std::min(a.lo.y_mm, b.lo.y_mm), std::min(a.lo.z_mm, b.lo.z_mm)},
          {std::max(a.hi.x_mm, b.hi.x_mm), std::max(a.hi.y_mm, b.hi.y_mm), std::max(a.hi.z_mm, b.hi.z_mm)}};
}

Box3_mm overlap(const Box3_mm& a, const Box3_mm& b) {
  return {{std::max(a.lo.x_mm, b.lo.x_mm), std::max(a.lo.y_mm, b.lo.y_mm), std::max(a.lo.z_mm, b.lo.z_mm)},
          {std::min(a.hi.x_mm, b.hi.x_mm), std::min(a.hi.y_mm, b.hi.y_mm), std::min(a.hi.z_mm, b.hi.z_mm)}};
}

}  // namespace

FrepShape::Node FrepShape::add(const NodeData& n) {
  nodes_.push_back(n);
  nodes_.back().cost = cost_of(n);  // its children are already in nodes_
  root_ = static_cast<Node>(nodes_.size() - 1);
  return root_;
}

FrepShape::Node FrepShape::sphere(const Point3_mm& centre, double radius_mm) {
  need_shape(finite(centre), "sphere centre must be finite");
  need_shape(std::isfinite(radius_mm) && radius_mm > 0, "sphere radius must be > 0");
  NodeData n{};
  n.kind = Kind::sphere;
  n.a = centre;
  n.p0 = radius_mm;
  n.box = box_around(centre, radius_mm, radius_mm, radius_mm);
  return add(n);
}

FrepShape::Node FrepShape::ellipsoid(const Point3_mm& centre, const std::array<double, 3>& r, double yaw_deg) {
  need_shape(finite(centre) && std::isfinite(yaw_deg), "ellipsoid centre and yaw must be finite");
  for (double v : r) need_shape(std::isfinite(v) && v > 0, "ellipsoid radii must be > 0");
  NodeData n{};
  n.kind = Kind::ellipsoid;
  n.a = centre;
  n.b = {r[0], r[1], r[2]};
  const double yaw = yaw_deg * std::numbers::pi / 180.0;
  n.p1 = std::cos(yaw);
  n.p2 = std::sin(yaw);
  // Extent of a turned ellipse along x and y.
  n.box = box_around(centre, std::hypot(r[0] * n.p1, r[1] * n.p2), std::hypot(r[0] * n.p2, r[1] * n.p1), r[2]);
  return add(n);
}

FrepShape::Node FrepShape::superellipsoid(const Point3_mm& centre, const std::array<double, 3>& r, double exponent,
                                          double yaw_deg) {
  need_shape(finite(centre) && std::isfinite(yaw_deg), "super-ellipsoid centre and yaw must be finite");
  for (double v : r) need_shape(std::isfinite(v) && v > 0, "super-ellipsoid radii must be > 0");
  need_shape(std::isfinite(exponent) && exponent >= 2, "super-ellipsoid exponent must be >= 2");
  NodeData n{};
  n.kind = Kind::superellipsoid;
  n.a = centre;
  n.b = {r[0], r[1], r[2]};
  n.p0 = exponent;
  const double yaw = yaw_deg * std::numbers::pi / 180.0;
  n.p1 = std::cos(yaw);
  n.p2 = std::sin(yaw);
  // A super-ellipse lies inside its turned bounding rectangle.
  const double c = std::abs(n.p1), s = std::abs(n.p2);
  n.box = box_around(centre, r[0] * c + r[1] * s, r[0] * s + r[1] * c, r[2]);
  return add(n);
}

FrepShape::Node FrepShape::tube(const Point3_mm& a, const Point3_mm& b, double radius_mm) {
  need_shape(finite(a) && finite(b), "tube ends must be finite");
  need_shape(std::isfinite(radius_mm) && radius_mm > 0, "tube radius must be > 0");
  NodeData n{};
  n.kind = Kind::tube;
  n.a = a;
  n.b = b;
  n.p0 = radius_mm;
  n.box = merge(box_around(a, radius_mm, radius_mm, radius_mm), box_around(b, radius_mm, radius_mm, radius_mm));
  return add(n);
}

FrepShape::Node FrepShape::blobs(const std::vector<Blob>& terms, double threshold) {
  need_shape(!terms.empty(), "a blobby object needs at least one blob");
  need_shape(std::isfinite(threshold) && threshold > 0, "blob threshold must be > 0");
  NodeData n{};
  n.kind = Kind::blobs;
  n.p0 = threshold;
  n.first = static_cast<std::int32_t>(terms_.size());
  n.count = static_cast<std::int32_t>(terms.size());
  // A point inside has sum >= c, so at least one of the N blobs gives >= c/N there:
  // k exp(-q) >= c/N  <=>  q <= ln(k N / c). Each blob's region of q <= q_max is an ellipsoid.
  Box3_mm box = empty_box();
  const double per_blob = threshold / static_cast<double>(terms.size());
  for (const Blob& t : terms) {
    need_shape(finite(t.centre), "blob centre must be finite");
    need_shape(std::isfinite(t.k) && t.k > 0, "blob weight k must be > 0");
    for (double s : t.inverse_scale_per_mm2) need_shape(std::isfinite(s) && s > 0, "blob inverse scales must be > 0");
    terms_.push_back(t);
    if (t.k <= per_blob) continue;  // this blob can never carry a point on its own share
    const double q_max = std::log(t.k / per_blob);
    const auto& s = t.inverse_scale_per_mm2;
    box = merge(box, box_around(t.centre, std::sqrt(q_max / s[0]), std::sqrt(q_max / s[1]), std::sqrt(q_max / s[2])));
  }
  n.box = box;
  return add(n);
}

FrepShape::Node FrepShape::unite(const std::vector<Node>& parts) {
  need_shape(!parts.empty(), "a union needs at least one part");
  NodeData n{};
  n.kind = Kind::unite;
  n.first = static_cast<std::int32_t>(children_.size());
  n.count = static_cast<std::int32_t>(parts.size());
  n.box = empty_box();
  for (Node c : parts) {
    need_shape(c >= 0 && c < static_cast<Node>(nodes_.size()), "union part is not a node of this shape");
    children_.push_back(c);
    n.box = merge(n.box, nodes_[c].box);
  }
  index_union(n);
  return add(n);
}

void FrepShape::index_union(NodeData& n) {
  constexpr std::int32_t kIndexFrom = 16;  // fewer parts: scanning their boxes is as fast
  if (n.count < kIndexFrom || n.box.empty()) return;
  PartGrid g;
  // About one part per cell for parts of similar size, at most 256 x 256 cells.
  const auto side = static_cast<std::int32_t>(std::clamp(std::ceil(std::sqrt(double(n.count))), 1.0, 256.0));
  g.nx = g.ny = side;
  g.x0 = n.box.lo.x_mm;
  g.y0 = n.box.lo.y_mm;
  const double w = n.box.hi.x_mm - n.box.lo.x_mm, h = n.box.hi.y_mm - n.box.lo.y_mm;
  g.inv_cell_x = w > 0 ? side / w : 0;
  g.inv_cell_y = h > 0 ? side / h : 0;
  auto cell = [](double v, double origin, double inv, std::int32_t cells) {
    const double c = std::floor((v - origin) * inv);
    return static_cast<std::int32_t>(std::clamp(c, 0.0, double(cells - 1)));
  };
  // Two passes (count, then fill) into one flat array, like a CSR matrix.
  std::vector<std::int32_t> count(static_cast<std::size_t>(side) * side + 1, 0);
  std::size_t entries = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::int32_t i = 0; i < n.count; ++i) {
      const Node c = children_[std::size_t(n.first) + std::size_t(i)];
      const Box3_mm& b = nodes_[static_cast<std::size_t>(c)].box;
      if (b.empty()) continue;  // contains nothing: never a candidate
      const std::int32_t x0 = cell(b.lo.x_mm, g.x0, g.inv_cell_x, side), x1 = cell(b.hi.x_mm, g.x0, g.inv_cell_x, side);
      const std::int32_t y0 = cell(b.lo.y_mm, g.y0, g.inv_cell_y, side), y1 = cell(b.hi.y_mm, g.y0, g.inv_cell_y, side);
      for (std::int32_t y = y0; y <= y1; ++y)
        for (std::int32_t x = x0; x <= x1; ++x) {
          const std::size_t k = static_cast<std::size_t>(y) * side + x;
          if (pass == 0) {
            ++count[k + 1];
            ++entries;
          } else {
            g.parts[std::size_t(g.cell_start[k]) + std::size_t(count[k]++)] = c;
          }
        }
    }
    if (pass == 0) {
      // Parts that each cover most of the grid make it no better than a scan: keep the scan.
      if (entries > 8 * static_cast<std::size_t>(n.count) + static_cast<std::size_t>(side) * side) return;
      for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
      g.cell_start = count;
      g.parts.resize(entries);
      std::fill(count.begin(), count.end(), 0);
    }
  }
  n.grid = static_cast<std::int32_t>(grids_.size());
  grids_.push_back(std::move(g));
}

FrepShape::Node FrepShape::intersect(const std::vector<Node>& parts) {
  need_shape(!parts.empty(), "an intersection needs at least one part");
  NodeData n{};
  n.kind = Kind::intersect;
  n.first = static_cast<std::int32_t>(children_.size());
  n.count = static_cast<std::int32_t>(parts.size());
  bool first = true;
  for (Node c : parts) {
    need_shape(c >= 0 && c < static_cast<Node>(nodes_.size()), "intersection part is not a node of this shape");
    children_.push_back(c);
    n.box = first ? nodes_[c].box : overlap(n.box, nodes_[c].box);
    first = false;
  }
  return add(n);
}

FrepShape::Node FrepShape::subtract(Node from, Node cut) {
  const Node count = static_cast<Node>(nodes_.size());
  need_shape(from >= 0 && from < count && cut >= 0 && cut < count, "difference parts must be nodes of this shape");
  NodeData n{};
  n.kind = Kind::subtract;
  n.first = static_cast<std::int32_t>(children_.size());
  n.count = 2;
  children_.push_back(from);
  children_.push_back(cut);
  n.box = nodes_[from].box;
  return add(n);
}

FrepShape::Node FrepShape::scaled(Node child, const Point3_mm& about, const std::array<double, 3>& f) {
  need_shape(child >= 0 && child < static_cast<Node>(nodes_.size()), "scaled shape is not a node of this shape");
  need_shape(finite(about), "scaling centre must be finite");
  for (double v : f) need_shape(std::isfinite(v) && v > 0, "scale factors must be > 0");
  NodeData n{};
  n.kind = Kind::scaled;
  n.a = about;
  n.b = {f[0], f[1], f[2]};
  n.first = static_cast<std::int32_t>(children_.size());
  n.count = 1;
  children_.push_back(child);
  const Box3_mm& cb = nodes_[child].box;
  if (cb.empty()) {
    n.box = cb;
  } else {
    auto map = [&](double v, double c, double k) { return c + (v - c) * k; };
    n.box = {{map(cb.lo.x_mm, about.x_mm, f[0]), map(cb.lo.y_mm, about.y_mm, f[1]), map(cb.lo.z_mm, about.z_mm, f[2])},
             {map(cb.hi.x_mm, about.x_mm, f[0]), map(cb.hi.y_mm, about.y_mm, f[1]), map(cb.hi.z_mm, about.z_mm, f[2])}};
  }
  return add(n);
}

void FrepShape::set_root(Node n) {
  need_shape(n >= 0 && n < static_cast<Node>(nodes_.size()), "root is not a node of this shape");
  root_ = n;
}

double FrepShape::value(const Point3_mm& p) const noexcept { return root_ < 0 ? kOutside : eval(root_, p); }

Box3_mm FrepShape::bounds() const noexcept { return root_ < 0 ? empty_box() : nodes_[root_].box; }

double FrepShape::cost_of(const NodeData& n) const noexcept {
  constexpr double kVisit = 1.0, kPowCalls = 4.0, kExpCall = 3.0;
  auto cost = [&](Node c) { return nodes_[static_cast<std::size_t>(c)].cost; };
  auto child = [&](std::int32_t i) { return children_[std::size_t(n.first) + std::size_t(i)]; };
  switch (n.kind) {
    case Kind::sphere:
    case Kind::ellipsoid:
    case Kind::tube: return kVisit;
    case Kind::superellipsoid: return kPowCalls;
    case Kind::blobs: return kVisit + kExpCall * n.count;
    case Kind::unite:
      if (n.grid >= 0) {  // value() visits the parts of one cell: the fullest one bounds it
        const PartGrid& g = grids_[static_cast<std::size_t>(n.grid)];
        double worst = 0;
        for (std::size_t k = 0; k + 1 < g.cell_start.size(); ++k) {
          double sum = 0;
          for (std::int32_t i = g.cell_start[k]; i < g.cell_start[k + 1]; ++i)
            sum += cost(g.parts[static_cast<std::size_t>(i)]);
          worst = std::max(worst, sum);
        }
        return kVisit + worst;
      }
      [[fallthrough]];
    case Kind::intersect:
    case Kind::subtract:
    case Kind::scaled: {
      double sum = kVisit;
      for (std::int32_t i = 0; i < n.count; ++i) sum += cost(child(i));
      return sum;
    }
  }
  return kVisit;
}

double FrepShape::eval(Node index, const Point3_mm& p) const noexcept {
  const NodeData& n = nodes_[static_cast<std::size_t>(index)];
  if (!n.box.contains(p)) return kOutside;
  const double dx = p.x_mm - n.a.x_mm, dy = p.y_mm - n.a.y_mm, dz = p.z_mm - n.a.z_mm;
  switch (n.kind) {
    case Kind::sphere: return 1.0 - (dx * dx + dy * dy + dz * dz) / (n.p0 * n.p0);
    case Kind::ellipsoid: {
      const double u = (n.p1 * dx + n.p2 * dy) / n.b.x_mm, v = (-n.p2 * dx + n.p1 * dy) / n.b.y_mm, w = dz / n.b.z_mm;
      return 1.0 - (u * u + v * v + w * w);
    }
    case Kind::superellipsoid: {
      const double u = std::abs((n.p1 * dx + n.p2 * dy) / n.b.x_mm), v = std::abs((-n.p2 * dx + n.p1 * dy) / n.b.y_mm),
                   w = std::abs(dz / n.b.z_mm);
      return 1.0 - (std::pow(u, n.p0) + std::pow(v, n.p0) + std::pow(w, n.p0));
    }
    case Kind::tube: {
      const double ex = n.b.x_mm - n.a.x_mm, ey = n.b.y_mm - n.a.y_mm, ez = n.b.z_mm - n.a.z_mm;
      const double len2 = ex * ex + ey * ey + ez * ez;
      const double t = len2 > 0 ? std::clamp((dx * ex + dy * ey + dz * ez) / len2, 0.0, 1.0) : 0.0;
      const double qx = dx - t * ex, qy = dy - t * ey, qz = dz - t * ez;
      return 1.0 - (qx * qx + qy * qy + qz * qz) / (n.p0 * n.p0);
    }
    case Kind::blobs: {
      double sum = 0;
      for (std::int32_t i = 0; i < n.count; ++i) {
        const Blob& b = terms_[std::size_t(n.first) + std::size_t(i)];
        const double bx = p.x_mm - b.centre.x_mm, by = p.y_mm - b.centre.y_mm, bz = p.z_mm - b.centre.z_mm;
        const auto& s = b.inverse_scale_per_mm2;
        sum += b.k * std::exp(-(s[0] * bx * bx + s[1] * by * by + s[2] * bz * bz));
      }
      return sum - n.p0;
    }
    case Kind::unite: {
      double v = kOutside;
      if (n.grid >= 0) {  // only the parts whose box meets p's cell can hold p
        const PartGrid& g = grids_[static_cast<std::size_t>(n.grid)];
        auto cell = [](double coordinate_mm, double origin, double inv, std::int32_t cells) {
          const double c = std::floor((coordinate_mm - origin) * inv);
          return static_cast<std::int32_t>(std::clamp(c, 0.0, double(cells - 1)));
        };
        const std::size_t k = static_cast<std::size_t>(cell(p.y_mm, g.y0, g.inv_cell_y, g.ny)) * g.nx +
                              cell(p.x_mm, g.x0, g.inv_cell_x, g.nx);
        for (std::int32_t i = g.cell_start[k]; i < g.cell_start[k + 1]; ++i)
          v = std::max(v, eval(g.parts[static_cast<std::size_t>(i)], p));
        return v;
      }
      for (std::int32_t i = 0; i < n.count; ++i) {
        v = std::max(v, eval(children_[std::size_t(n.first) + std::size_t(i)], p));
      }
      return v;
    }
    case Kind::intersect: {
      double v = std::numeric_limits<double>::infinity();
      for (std::int32_t i = 0; i < n.count; ++i) {
        v = std::min(v, eval(children_[std::size_t(n.first) + std::size_t(i)], p));
      }
      return v;
    }
    case Kind::subtract: {
      const double a = eval(children_[static_cast<std::size_t>(n.first)], p);
      return std::min(a, -eval(children_[std::size_t(n.first) + 1], p));
    }
    case Kind::scaled: {
      const Point3_mm q{n.a.x_mm + dx / n.b.x_mm, n.a.y_mm + dy / n.b.y_mm, n.a.z_mm + dz / n.b.z_mm};
      return eval(children_[static_cast<std::size_t>(n.first)], q);
    }
  }
  return kOutside;
}

}  // namespace palprig
