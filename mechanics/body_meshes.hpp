#pragma once
// The meshers of the three bodies (written by hand: see quad_mesh.hpp for why). Each returns a
// QuadMesh of one body, numbered from body 0 and from its own material 0; the problem builders
// (contact_problems.hpp) append them and shift both.
//
// Sizes: `element_mm` is the edge length where the stress is read (the fingertip's palmar
// surface, the block's and the actuator's top around the contact); elsewhere elements grow to
// about three times that. Nine-node elements, so a 1 mm element has nodes every 0.5 mm (paper
// 002 used 1 mm four-node elements: the same node spacing at twice the element size).
#include "mechanics/quad_mesh.hpp"
#include "models/fe_bodies.hpp"

namespace palprig::mechanics {

// Fingertip materials, in this order.
enum FingertipMaterial { kSkin = 0, kFingerTissue = 1, kNail = 2 };
// Boundaries: "bone" (the phalanx's outline, where the press is applied), "fingertip_contact"
// (the outline below 3/4 of the height: what may touch), "fingertip_surface" (all the outline).
struct FingertipMeshSizes {
  double element_mm = 1.0;     // along the outline below fine_height_mm
  double fine_height_mm = -1;  // default: 0.6 of the height
  double top_element_mm = -1;  // at the top, growing linearly above fine_height_mm (default 2.5 x)
  int tissue_rows = 0;         // element rows from the bone to the skin (default: from the palmar thickness)
  double row_grading = 0.8;    // rows at (i/n)^grading of the way: < 1 finer towards the skin
};
QuadMesh mesh_fingertip(const FingertipBody& body, const FingertipMeshSizes& sizes);
inline QuadMesh mesh_fingertip(const FingertipBody& body, double element_mm) {
  FingertipMeshSizes s;
  s.element_mm = element_mm;
  return mesh_fingertip(body, s);
}

// Block materials: 0 the tissue, 1 + i inclusion i. Boundaries "block_top", "block_bottom",
// "block_left", "block_right". The block's top is y = 0; finer elements within `fine_half_width_mm`
// of its middle and `fine_depth_mm` of its top; each inclusion is meshed around its circle (its
// outline a ring of nodes).
struct BlockMeshSizes {
  double element_mm = 1.0;
  double fine_half_width_mm = 10.0;
  double fine_depth_mm = 12.0;
  double growth = 0.2;         // element size added per mm beyond the fine zone
  double max_element_mm = -1;  // default: 5 x element_mm
};
QuadMesh mesh_block(const TissueBlock& block, const BlockMeshSizes& sizes);

// Actuator materials: 0 membrane, 1 silicone layer. Boundaries "actuator_top", "chamber" (the
// membrane's underside over the cavity, where the air pushes), "bonded" (its underside on the
// substrate: held both ways, or only vertically when ActuatorBody::membrane_slides),
// "actuator_left", "actuator_right".
QuadMesh mesh_actuator(const ActuatorBody& body, double element_mm);

// Graded grid coordinates from lo to hi (lo < hi) through every breakpoint, with cells about
// size(x) long where they start. Exposed for tests.
template <class SizeAt>
std::vector<double> graded_coordinates(double lo, double hi, std::vector<double> breakpoints, SizeAt size);

}  // namespace palprig::mechanics

#include <algorithm>
#include <cmath>
#include <numeric>

template <class SizeAt>
std::vector<double> palprig::mechanics::graded_coordinates(double lo, double hi, std::vector<double> breakpoints,
                                                           SizeAt size) {
  breakpoints.push_back(lo);
  breakpoints.push_back(hi);
  std::sort(breakpoints.begin(), breakpoints.end());
  std::vector<double> cuts;
  for (double b : breakpoints)
    if (b >= lo && b <= hi && (cuts.empty() || b - cuts.back() > 1e-9)) cuts.push_back(b);
  // Within each interval, march from its start with the local size and stretch the steps so
  // that the last lands on the interval's end.
  std::vector<double> out{cuts.front()};
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    std::vector<double> steps;
    for (double x = a; x < b - 1e-9 && steps.size() < 100000;) {
      const double h = std::max(size(x), 1e-6);
      steps.push_back(h);
      x += h;
    }
    if (steps.size() > 1 && steps.back() > 0 &&
        (b - a) - (std::accumulate(steps.begin(), steps.end() - 1, 0.0)) < 0.5 * steps.back())
      steps.pop_back();  // a sliver at the end: fold it into the others
    double total = 0;
    for (double h : steps) total += h;
    double x = a;
    for (std::size_t k = 0; k < steps.size(); ++k) {
      x += steps[k] * (b - a) / total;
      out.push_back(k + 1 == steps.size() ? b : x);
    }
  }
  return out;
}
