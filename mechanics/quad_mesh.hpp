#pragma once
// A 2D mesh of nine-node quadrilaterals (biquadratic, curved edges), built by the meshers of
// this folder and handed to the solver. GetFEM meshes only regular grids of simple shapes by
// itself (and its distmesh-style mesher gives triangles), so the fingertip (an O-grid between
// an elliptic bone and the outline), the block with circular nodules and the layered actuator
// are written by hand here, as structured quads whose shared nodes are one node by
// construction (never matched by distance: two bodies that touch stay two bodies).
//
// Node order inside an element is GetFEM's for GT_QK(2,2): tensor order, u fastest,
//   6 7 8
//   3 4 5      (u along 0-1-2, v along 0-3-6)
//   0 1 2
// Sides: 0 bottom (v = 0: nodes 0 1 2), 1 right (u = 1: 2 5 8), 2 top (v = 1: 6 7 8), 3 left
// (u = 0: 0 3 6). Elements are stored counter-clockwise (corner 0 -> 2 -> 8 -> 6).
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace palprig::mechanics {

struct MeshNode {
  double x_mm = 0, y_mm = 0;
};

struct QuadElement {
  std::array<std::uint32_t, 9> nodes{};
  int material = 0;  // index into the problem's material list
  int body = 0;      // index of the body it belongs to (0 the fingertip, 1 the block or actuator)
};

struct MeshSide {
  std::uint32_t element = 0;
  int side = 0;  // 0 bottom, 1 right, 2 top, 3 left (see above)
};

struct QuadMesh {
  std::vector<MeshNode> nodes;
  std::vector<QuadElement> elements;
  // Named boundaries ("fingertip_contact", "bone", "block_top", ...): element sides.
  std::vector<std::pair<std::string, std::vector<MeshSide>>> boundaries;

  bool has_boundary(const std::string& name) const;
  const std::vector<MeshSide>& boundary(const std::string& name) const;  // throws std::out_of_range
  std::vector<MeshSide>& boundary_for(const std::string& name);          // created when absent
  // Add an element from its nine node indices in tensor order; stored counter-clockwise (an
  // element given clockwise is mirrored in u). Returns its index.
  std::uint32_t add_element(std::array<std::uint32_t, 9> nodes, int material, int body);
  // Name the side of `element` whose end corners are nodes a and b (either order).
  void add_side(const std::string& name, std::uint32_t element, std::uint32_t a, std::uint32_t b);
  // Append another mesh: its nodes renumbered, its bodies shifted by body_offset, its materials
  // by material_offset, its boundaries merged by name.
  void append(const QuadMesh& other, int body_offset, int material_offset);
  // The three nodes of a side, in order along it.
  std::array<std::uint32_t, 3> side_nodes(const MeshSide& s) const;
  // Smallest signed area of the corner triangles of every element (negative: a tangled mesh).
  double min_corner_area_mm2() const;
  std::size_t count_elements(int body) const;
};

}  // namespace palprig::mechanics
