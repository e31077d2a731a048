#include "mechanics/quad_mesh.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace palprig::mechanics {

namespace {

constexpr std::array<std::array<int, 3>, 4> kSideNodes = {{{0, 1, 2}, {2, 5, 8}, {6, 7, 8}, {0, 3, 6}}};

double cross(const MeshNode& o, const MeshNode& a, const MeshNode& b) {
  return (a.x_mm - o.x_mm) * (b.y_mm - o.y_mm) - (a.y_mm - o.y_mm) * (b.x_mm - o.x_mm);
}

}  // namespace

bool QuadMesh::has_boundary(const std::string& name) const {
  return std::any_of(boundaries.begin(), boundaries.end(), [&](const auto& b) { return b.first == name; });
}

const std::vector<MeshSide>& QuadMesh::boundary(const std::string& name) const {
  for (const auto& b : boundaries)
    if (b.first == name) return b.second;
  throw std::out_of_range("no boundary named " + name);
}

std::vector<MeshSide>& QuadMesh::boundary_for(const std::string& name) {
  for (auto& b : boundaries)
    if (b.first == name) return b.second;
  boundaries.emplace_back(name, std::vector<MeshSide>{});
  return boundaries.back().second;
}

std::uint32_t QuadMesh::add_element(std::array<std::uint32_t, 9> n, int material, int body) {
  const double area = cross(nodes[n[0]], nodes[n[2]], nodes[n[8]]) + cross(nodes[n[0]], nodes[n[8]], nodes[n[6]]);
  if (area < 0) {  // clockwise: mirror in u
    for (std::size_t row = 0; row < 3; ++row) std::swap(n[3 * row], n[3 * row + 2]);
  }
  elements.push_back({n, material, body});
  return std::uint32_t(elements.size() - 1);
}

void QuadMesh::add_side(const std::string& name, std::uint32_t element, std::uint32_t a, std::uint32_t b) {
  const auto& n = elements.at(element).nodes;
  for (int s = 0; s < 4; ++s) {
    const std::uint32_t p = n[std::size_t(kSideNodes[std::size_t(s)][0])];
    const std::uint32_t q = n[std::size_t(kSideNodes[std::size_t(s)][2])];
    if ((p == a && q == b) || (p == b && q == a)) {
      boundary_for(name).push_back({element, s});
      return;
    }
  }
  throw std::logic_error("add_side: the nodes are not the ends of one side of the element");
}

void QuadMesh::append(const QuadMesh& other, int body_offset, int material_offset) {
  const auto node_offset = std::uint32_t(nodes.size());
  const auto element_offset = std::uint32_t(elements.size());
  nodes.insert(nodes.end(), other.nodes.begin(), other.nodes.end());
  for (QuadElement e : other.elements) {
    for (auto& id : e.nodes) id += node_offset;
    e.body += body_offset;
    e.material += material_offset;
    elements.push_back(e);
  }
  for (const auto& [name, sides] : other.boundaries) {
    auto& mine = boundary_for(name);
    for (MeshSide s : sides) mine.push_back({s.element + element_offset, s.side});
  }
}

std::array<std::uint32_t, 3> QuadMesh::side_nodes(const MeshSide& s) const {
  const auto& n = elements.at(s.element).nodes;
  const auto& k = kSideNodes.at(std::size_t(s.side));
  return {n[std::size_t(k[0])], n[std::size_t(k[1])], n[std::size_t(k[2])]};
}

double QuadMesh::min_corner_area_mm2() const {
  double least = std::numeric_limits<double>::infinity();
  for (const auto& e : elements) {
    const auto& p = e.nodes;
    // Each corner's triangle with its two neighbouring corners (0 2 8 6 counter-clockwise).
    const std::array<std::uint32_t, 4> c = {p[0], p[2], p[8], p[6]};
    for (std::size_t i = 0; i < 4; ++i)
      least = std::min(least, cross(nodes[c[i]], nodes[c[(i + 1) % 4]], nodes[c[(i + 3) % 4]]) / 2);
  }
  return least;
}

std::size_t QuadMesh::count_elements(int body) const {
  return std::size_t(std::count_if(elements.begin(), elements.end(), [&](const auto& e) { return e.body == body; }));
}

}  // namespace palprig::mechanics
