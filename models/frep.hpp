#pragma once
// Function representation (FRep) of solids, paper 001: a solid is the set where a real function
// of position is >= 0. Primitives are spheres, ellipsoids, super-ellipsoids (the body shape of
// 001), tubes (ribs, bones, ligaments) and blobby objects
//     F(p) = sum_i k_i exp(-(s_x (x - x_i)^2 + s_y (y - y_i)^2 + s_z (z - z_i)^2)) - c,
// combined by union (max), intersection (min) and difference (min(a, -b)), and scaled about a
// point (enlarged organs are the normal organ scaled, 001).
//
// Coordinates: x, y on the skin plane as the touchpad's (mm, y grows down the pad), z the depth
// below the skin (mm, positive into the body).
//
// Membership is the sign of the value. The primitives are normalised differently (a sphere
// gives 1 - |p - c|^2 / r^2, a blob sum is in its own units), so a value is not a distance.
// Values are exact within each part's bounding box; outside it a part counts as -1, which
// keeps every sign (and so every union, intersection and difference) right.
//
// The shape is a tree stored in flat vectors, built once; value() walks it without allocating,
// and every node carries a conservative bounding box so distant points are rejected cheaply.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace palprig {

struct Point3_mm {
  double x_mm = 0, y_mm = 0, z_mm = 0;  // z_mm: depth below the skin
};

struct Box3_mm {
  Point3_mm lo, hi;
  bool contains(const Point3_mm& p) const noexcept {
    return p.x_mm >= lo.x_mm && p.x_mm <= hi.x_mm && p.y_mm >= lo.y_mm && p.y_mm <= hi.y_mm && p.z_mm >= lo.z_mm &&
           p.z_mm <= hi.z_mm;
  }
  bool empty() const noexcept { return lo.x_mm > hi.x_mm || lo.y_mm > hi.y_mm || lo.z_mm > hi.z_mm; }
};

// One term of a blobby object: k exp(-(s . (p - centre)^2)), s in 1/mm^2 (001's inverse scales).
struct Blob {
  Point3_mm centre;
  double k = 1.0;
  std::array<double, 3> inverse_scale_per_mm2{1, 1, 1};
};

class FrepShape {
 public:
  using Node = std::int32_t;

  // Builders return the new node; the last node built is the root unless set_root() says
  // otherwise. Sizes must be positive and finite (BadInput otherwise): the scene
  // loader refuses bad files with the field's name before it gets here.
  Node sphere(const Point3_mm& centre, double radius_mm);
  // Semi-axes along x, y, z, the x-y axes turned by yaw_deg about the depth axis.
  Node ellipsoid(const Point3_mm& centre, const std::array<double, 3>& radii_mm, double yaw_deg = 0);
  // 1 - |dx/a|^n - |dy/b|^n - |dz/c|^n (paper 001 uses n = 6 for the body).
  Node superellipsoid(const Point3_mm& centre, const std::array<double, 3>& radii_mm, double exponent,
                      double yaw_deg = 0);
  // The points within radius of the segment from a to b (a rib, a bone shaft, a ligament).
  Node tube(const Point3_mm& a, const Point3_mm& b, double radius_mm);
  // Blobby object: sum of blobs minus threshold c (c > 0).
  Node blobs(const std::vector<Blob>& terms, double threshold);
  Node unite(const std::vector<Node>& parts);
  Node intersect(const std::vector<Node>& parts);
  Node subtract(Node from, Node cut);
  // The child shape scaled by factor (per axis, > 0) about a fixed point.
  Node scaled(Node child, const Point3_mm& about, const std::array<double, 3>& factor);

  void set_root(Node n);
  Node root() const noexcept { return root_; }
  bool defined() const noexcept { return root_ >= 0; }

  // >= 0 inside. Never allocates or throws; an undefined shape is empty everywhere.
  double value(const Point3_mm& p) const noexcept;
  bool contains(const Point3_mm& p) const noexcept { return value(p) >= 0; }
  // A box holding every point where value() >= 0 (conservative).
  Box3_mm bounds() const noexcept;
  std::size_t node_count() const noexcept { return nodes_.size(); }
  // The most work one value() can do, in sphere-equivalent evaluations (a node visit is 1, a
  // super-ellipsoid 4 for its pow calls, a blob term 3 for its exp): every part whose box can
  // hold the point counted, a union's grid by its fullest cell. What the scene loader weighs
  // against the tick's period (formats/function_scene_file.cpp).
  double worst_case_cost() const noexcept { return root_ < 0 ? 0.0 : nodes_[static_cast<std::size_t>(root_)].cost; }

 private:
  enum class Kind : std::uint8_t { sphere, ellipsoid, superellipsoid, tube, blobs, unite, intersect, subtract, scaled };
  struct NodeData {
    Kind kind;
    Box3_mm box;
    // Geometry: centre / segment start (a), radii or segment end (b), extra numbers.
    Point3_mm a, b;
    double p0 = 0, p1 = 0, p2 = 0;      // meaning per kind (radius, cos yaw, sin yaw, exponent, threshold)
    std::int32_t first = 0, count = 0;  // children (into children_) or blob terms (into terms_)
    std::int32_t grid = -1;             // unions of many parts: their grid in grids_
    double cost = 0;                    // worst_case_cost() of this node, set when it is added
  };

  // A union of many parts (hundreds of spheres) finds the parts whose box can hold a point
  // through a uniform grid over the union's x-y box, so a value costs the few parts near the
  // point, not all of them: building a scene and sampling it stay linear in the part count.
  struct PartGrid {
    double x0 = 0, y0 = 0, inv_cell_x = 0, inv_cell_y = 0;
    std::int32_t nx = 0, ny = 0;
    std::vector<std::int32_t> cell_start;  // nx * ny + 1 offsets into parts
    std::vector<Node> parts;
  };
  void index_union(NodeData& n);

  Node add(const NodeData& n);
  double eval(Node n, const Point3_mm& p) const noexcept;
  double cost_of(const NodeData& n) const noexcept;  // from the children's costs

  std::vector<NodeData> nodes_;
  std::vector<Node> children_;
  std::vector<Blob> terms_;
  std::vector<PartGrid> grids_;
  Node root_ = -1;
};

}  // namespace palprig
