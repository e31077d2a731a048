#include "mechanics/body_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace palprig::mechanics {

namespace {

constexpr double kPi = std::numbers::pi;

double signed_power(double v, double p) { return std::copysign(std::pow(std::abs(v), p), v); }

// A structured block of (2nu+1) x (2nv+1) nodes (columns wrap when `wrap`): node(i, j) is the
// node index, point(i, j) its position. Elements take 3 x 3 nodes.
struct NodeGrid {
  int cols = 0, rows = 0;  // node columns and rows
  bool wrap = false;
  std::vector<std::uint32_t> ids;
  std::uint32_t at(int i, int j) const {
    if (wrap) i = ((i % cols) + cols) % cols;
    return ids[std::size_t(j) * std::size_t(cols) + std::size_t(i)];
  }
};

template <class Point>
NodeGrid add_grid(QuadMesh& mesh, int cols, int rows, bool wrap, Point point) {
  NodeGrid g{cols, rows, wrap, {}};
  g.ids.reserve(std::size_t(cols) * std::size_t(rows));
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      g.ids.push_back(std::uint32_t(mesh.nodes.size()));
      mesh.nodes.push_back(point(i, j));
    }
  return g;
}

std::array<std::uint32_t, 9> element_nodes(const NodeGrid& g, int ei, int ej) {
  std::array<std::uint32_t, 9> n{};
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 3; ++a)
      n[static_cast<std::size_t>(b) * 3 + static_cast<std::size_t>(a)] = g.at(2 * ei + a, 2 * ej + b);
  return n;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The fingertip: an O-grid. Node columns follow the outline (denser on the palmar side), node
// rows run from the bone out to the skin's inner boundary and across the skin.
QuadMesh mesh_fingertip(const FingertipBody& f, const FingertipMeshSizes& sizes) {
  const double element_mm = sizes.element_mm;
  const double a = f.width_mm / 2, b = f.height_mm / 2, n = f.outline_exponent;
  auto outline = [&](double t) {
    return MeshNode{a * signed_power(std::cos(t), 2 / n), b + b * signed_power(std::sin(t), 2 / n)};
  };
  auto inward_normal = [&](double t) {
    const MeshNode p = outline(t);
    const double gx = signed_power(p.x_mm / a, n - 1) / a, gy = signed_power((p.y_mm - b) / b, n - 1) / b;
    const double len = std::hypot(gx, gy);
    return MeshNode{-gx / len, -gy / len};
  };
  auto bone = [&](double t) {
    return MeshNode{f.bone_width_mm / 2 * std::cos(t), f.bone_centre_height_mm + f.bone_height_mm / 2 * std::sin(t)};
  };
  // Element size along the outline: element_mm on the lower part, growing to the top's.
  const double fine_top = sizes.fine_height_mm > 0 ? sizes.fine_height_mm : 0.6 * f.height_mm;
  const double top_size = sizes.top_element_mm > 0 ? sizes.top_element_mm : 2.5 * element_mm;
  auto size_at = [&](double y) {
    if (y <= fine_top) return element_mm;
    return element_mm + (top_size - element_mm) * std::min(1.0, (y - fine_top) / (f.height_mm - fine_top));
  };
  // Cumulative element count along the outline from the bottom (t = -pi/2), counter-clockwise.
  constexpr int kSamples = 4096;
  std::vector<double> ts(kSamples + 1), cumulative(kSamples + 1, 0.0);
  for (int k = 0; k <= kSamples; ++k) ts[std::size_t(k)] = -kPi / 2 + 2 * kPi * k / kSamples;
  for (int k = 1; k <= kSamples; ++k) {
    const MeshNode p = outline(ts[std::size_t(k - 1)]), q = outline(ts[std::size_t(k)]);
    const double ds = std::hypot(q.x_mm - p.x_mm, q.y_mm - p.y_mm);
    cumulative[std::size_t(k)] = cumulative[std::size_t(k - 1)] + ds / size_at((p.y_mm + q.y_mm) / 2);
  }
  int around = std::max(16, static_cast<int>(std::lround(cumulative.back())));
  around += around % 2;  // even: the mesh is symmetric about the vertical axis
  const int cols = 2 * around;
  std::vector<double> col_t(static_cast<std::size_t>(cols));
  for (int i = 0; i < cols; ++i) {
    const double target = cumulative.back() * i / cols;
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    const std::size_t k = std::size_t(std::max<std::ptrdiff_t>(1, it - cumulative.begin()));
    const double w = (target - cumulative[k - 1]) / std::max(1e-300, cumulative[k] - cumulative[k - 1]);
    col_t[std::size_t(i)] = ts[k - 1] + w * (ts[k] - ts[k - 1]);
  }
  // Rows: tissue from the bone to the skin's inner boundary (finer towards the skin), then skin.
  const double palmar_tissue = f.bone_centre_height_mm - f.bone_height_mm / 2 - f.skin_thickness_mm;
  const int tissue_rows = sizes.tissue_rows > 0
                              ? sizes.tissue_rows
                              : std::max(2, static_cast<int>(std::ceil(palmar_tissue / (1.3 * element_mm))));
  const int skin_rows = std::max(1, static_cast<int>(std::lround(f.skin_thickness_mm / element_mm)));
  const int rows = 2 * (tissue_rows + skin_rows) + 1;

  QuadMesh mesh;
  const NodeGrid g = add_grid(mesh, cols, rows, true, [&](int i, int j) {
    const double t = col_t[std::size_t(i)];
    const MeshNode o = outline(t), nrm = inward_normal(t), bn = bone(t);
    const MeshNode s{o.x_mm + f.skin_thickness_mm * nrm.x_mm, o.y_mm + f.skin_thickness_mm * nrm.y_mm};
    if (j <= 2 * tissue_rows) {
      const double xi = std::pow(double(j) / (2 * tissue_rows), sizes.row_grading);  // finer near the skin
      return MeshNode{bn.x_mm + (s.x_mm - bn.x_mm) * xi, bn.y_mm + (s.y_mm - bn.y_mm) * xi};
    }
    const double xi = double(j - 2 * tissue_rows) / (2 * skin_rows);
    return MeshNode{s.x_mm + (o.x_mm - s.x_mm) * xi, s.y_mm + (o.y_mm - s.y_mm) * xi};
  });
  const double contact_top = 0.75 * f.height_mm;
  for (int ej = 0; ej < tissue_rows + skin_rows; ++ej)
    for (int ei = 0; ei < around; ++ei) {
      const bool in_skin = ej >= tissue_rows;
      const MeshNode outer = mesh.nodes[g.at(2 * ei + 1, rows - 1)];
      const bool nail = in_skin && f.nail_width_mm > 0 && outer.y_mm > b && std::abs(outer.x_mm) < f.nail_width_mm / 2;
      const int material = nail ? kNail : in_skin ? kSkin : kFingerTissue;
      const std::uint32_t e = mesh.add_element(element_nodes(g, ei, ej), material, 0);
      if (ej == 0) mesh.add_side("bone", e, g.at(2 * ei, 0), g.at(2 * ei + 2, 0));
      if (ej == tissue_rows + skin_rows - 1) {
        const std::uint32_t p = g.at(2 * ei, rows - 1), q = g.at(2 * ei + 2, rows - 1);
        mesh.add_side("fingertip_surface", e, p, q);
        if (outer.y_mm < contact_top) mesh.add_side("fingertip_contact", e, p, q);
      }
    }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// The block: a tensor grid graded from the contact, whose lines pass through each inclusion's
// circle box; inside each box the nodes are pulled onto concentric rounded squares so that the
// ring of nodes at the circle's radius lies on the circle (a "squircle" map: the box's edge stays
// straight, the circle is exact, in between the rings blend linearly).
QuadMesh mesh_block(const TissueBlock& block, const BlockMeshSizes& sizes) {
  const double h = sizes.element_mm;
  struct Box {
    double cx, cy, r, s;
  };
  std::vector<Box> boxes;
  for (const BlockInclusion& inc : block.inclusions) {
    const double r = inc.diameter_mm / 2, cy = -inc.centre_depth_mm;
    const double cover = inc.centre_depth_mm - r;
    const double side_room = block.width_mm / 2 - std::abs(inc.x_mm) - r;
    const double below = block.height_mm - inc.centre_depth_mm - r;
    double ring = std::min({0.5 * r, 0.6 * cover, 0.6 * side_room, 0.6 * below});
    for (const BlockInclusion& other : block.inclusions) {
      if (&other == &inc) continue;
      const double gap =
          std::max(std::abs(other.x_mm - inc.x_mm), std::abs(other.centre_depth_mm - inc.centre_depth_mm)) - r -
          other.diameter_mm / 2;
      ring = std::min(ring, 0.45 * gap);
    }
    if (!(ring > 0)) throw std::invalid_argument("inclusion " + inc.name + " touches the block's edge or another");
    boxes.push_back({inc.x_mm, cy, r, r + ring});
  }
  // Element size: h near the contact, growing by a fifth of the distance beyond the fine zone
  // (at most 5 h), and no more than a fifth of a nodule's radius inside its box.
  const double cap = sizes.max_element_mm > 0 ? sizes.max_element_mm : 5 * h;
  auto size_x = [&](double x) {
    const double beyond = std::max(0.0, std::abs(x) - sizes.fine_half_width_mm);
    double s = std::min(cap, h + 1.25 * sizes.growth * beyond);
    for (const Box& bx : boxes)
      if (std::abs(x - bx.cx) < bx.s + 1e-9) s = std::min(s, std::max(bx.r / 5, std::min(h, bx.r / 2.5)));
    return s;
  };
  auto size_y = [&](double y) {
    const double beyond = std::max(0.0, -y - sizes.fine_depth_mm);
    double s = std::min(cap, h + sizes.growth * beyond);
    for (const Box& bx : boxes)
      if (std::abs(y - bx.cy) < bx.s + 1e-9) s = std::min(s, std::max(bx.r / 5, std::min(h, bx.r / 2.5)));
    return s;
  };
  std::vector<double> xb{-sizes.fine_half_width_mm, sizes.fine_half_width_mm, 0.0}, yb{-sizes.fine_depth_mm};
  for (const Box& bx : boxes) {
    for (double d : {-bx.s, -bx.r, bx.r, bx.s}) {
      xb.push_back(bx.cx + d);
      yb.push_back(bx.cy + d);
    }
  }
  const std::vector<double> xs = graded_coordinates(-block.width_mm / 2, block.width_mm / 2, xb, size_x);
  const std::vector<double> ys = graded_coordinates(-block.height_mm, 0.0, yb, size_y);
  const int ex = int(xs.size()) - 1, ey = int(ys.size()) - 1;
  auto coordinate = [](const std::vector<double>& c, int i) {
    const auto k = static_cast<std::size_t>(i / 2);
    return i % 2 == 0 ? c[k] : (c[k] + c[k + 1]) / 2;
  };
  auto squircle = [&](MeshNode p) {
    for (const Box& bx : boxes) {
      const double dx = p.x_mm - bx.cx, dy = p.y_mm - bx.cy;
      const double rho = std::max(std::abs(dx), std::abs(dy));
      if (rho >= bx.s || rho <= 0) continue;
      const double w = rho <= bx.r ? rho / bx.r : (bx.s - rho) / (bx.s - bx.r);
      const double scale = rho / std::hypot(dx, dy);  // onto the circle of radius rho
      return MeshNode{bx.cx + dx * (1 + w * (scale - 1)), bx.cy + dy * (1 + w * (scale - 1))};
    }
    return p;
  };
  QuadMesh mesh;
  const NodeGrid g = add_grid(mesh, 2 * ex + 1, 2 * ey + 1, false, [&](int i, int j) {
    return squircle({coordinate(xs, i), coordinate(ys, j)});
  });
  for (int ej = 0; ej < ey; ++ej)
    for (int ei = 0; ei < ex; ++ei) {
      const double cx = (xs[std::size_t(ei)] + xs[std::size_t(ei) + 1]) / 2;
      const double cy = (ys[std::size_t(ej)] + ys[std::size_t(ej) + 1]) / 2;
      int material = 0;
      for (std::size_t k = 0; k < boxes.size(); ++k)
        if (std::max(std::abs(cx - boxes[k].cx), std::abs(cy - boxes[k].cy)) < boxes[k].r) material = int(k) + 1;
      const std::uint32_t e = mesh.add_element(element_nodes(g, ei, ej), material, 0);
      if (ej == ey - 1) mesh.add_side("block_top", e, g.at(2 * ei, 2 * ey), g.at(2 * ei + 2, 2 * ey));
      if (ej == 0) mesh.add_side("block_bottom", e, g.at(2 * ei, 0), g.at(2 * ei + 2, 0));
      if (ei == 0) mesh.add_side("block_left", e, g.at(0, 2 * ej), g.at(0, 2 * ej + 2));
      if (ei == ex - 1) mesh.add_side("block_right", e, g.at(2 * ex, 2 * ej), g.at(2 * ex, 2 * ej + 2));
    }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// The actuator: the membrane (one row of elements, or more when thick) under the silicone layer,
// columns through the chamber's edges, finer over the chamber and the contact.
QuadMesh mesh_actuator(const ActuatorBody& act, double element_mm) {
  const double h = element_mm, half = act.chamber_width_mm / 2;
  auto size_x = [&](double x) { return std::min(3 * h, h + 0.3 * std::max(0.0, std::abs(x) - 8.0)); };
  const std::vector<double> xs = graded_coordinates(-act.width_mm / 2, act.width_mm / 2, {-half, half, 0.0}, size_x);
  const int membrane_rows = std::max(1, static_cast<int>(std::lround(act.membrane_thickness_mm / (0.5 * h))));
  const int layer_rows = std::max(2, static_cast<int>(std::ceil(act.layer_thickness_mm / h)));
  std::vector<double> ys;  // bottom of the membrane to the top of the layer
  const double bottom = -act.layer_thickness_mm - act.membrane_thickness_mm;
  for (int k = 0; k <= membrane_rows; ++k) ys.push_back(bottom + act.membrane_thickness_mm * k / membrane_rows);
  for (int k = 1; k <= layer_rows; ++k) ys.push_back(-act.layer_thickness_mm * (1 - double(k) / layer_rows));
  const int ex = int(xs.size()) - 1, ey = int(ys.size()) - 1;
  auto coordinate = [](const std::vector<double>& c, int i) {
    const auto k = static_cast<std::size_t>(i / 2);
    return i % 2 == 0 ? c[k] : (c[k] + c[k + 1]) / 2;
  };
  QuadMesh mesh;
  const NodeGrid g = add_grid(mesh, 2 * ex + 1, 2 * ey + 1, false, [&](int i, int j) {
    return MeshNode{coordinate(xs, i), coordinate(ys, j)};
  });
  for (int ej = 0; ej < ey; ++ej)
    for (int ei = 0; ei < ex; ++ei) {
      const double cx = (xs[std::size_t(ei)] + xs[std::size_t(ei) + 1]) / 2;
      const std::uint32_t e = mesh.add_element(element_nodes(g, ei, ej), ej < membrane_rows ? 0 : 1, 0);
      if (ej == 0) mesh.add_side(std::abs(cx) < half ? "chamber" : "bonded", e, g.at(2 * ei, 0), g.at(2 * ei + 2, 0));
      if (ej == ey - 1) mesh.add_side("actuator_top", e, g.at(2 * ei, 2 * ey), g.at(2 * ei + 2, 2 * ey));
      if (ei == 0) mesh.add_side("actuator_left", e, g.at(0, 2 * ej), g.at(0, 2 * ej + 2));
      if (ei == ex - 1) mesh.add_side("actuator_right", e, g.at(2 * ex, 2 * ej), g.at(2 * ex, 2 * ej + 2));
    }
  return mesh;
}

}  // namespace palprig::mechanics
