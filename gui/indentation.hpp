#pragma once
// How far the tissue gives under a finger, and paper 001's tiered grid deformation around the
// contact, for the scene view.
//
// Depth: the press over a contact stiffness that grows with the felt stiffness. Paper 002's
// reference press (2 N) sinks 7 mm into the soft silicone (E 14.7 kPa); a tumor (E 21.9 kPa) is
// stiffer by 21.9 / 14.7, so it gives 4.7 mm under the same press. Capped at 12 mm.
//
// Grid: a (2n+1) x (2n+1) sub-grid of vertices centred on the contact, in n+1 tiers (tier t =
// Chebyshev distance t cells from the centre). Tier t sinks depth * (n - t) / n: the full depth
// at the centre, falling tier by tier to 0 at the border, which joins the undeformed grid.
// Tissue dragging (paper 000's stick/slip, models/tissue_drag.hpp) carries the tissue under a
// finger laterally by an offset: the sub-grid is then centred on where that tissue was at rest
// (the contact minus the offset), and tier t is carried by offset * (n - t) / n, so the centre
// vertex sits under the finger and the border stays where it was: the skin stretched.
#include <vector>

namespace palprig::gui {

struct IndentationModel {
  double reference_force_N = 2.0;
  double soft_depth_mm = 7.0;                   // at the reference force, stiffness 0
  double hard_over_soft_modulus = 21.9 / 14.7;  // stiffness 1 (a tumor) against the silicone
  double max_depth_mm = 12.0;
  double depth_mm(double force_N, double stiffness) const noexcept;
};

struct GridVertex {
  double x_mm = 0, y_mm = 0;    // rest position on the skin
  double dx_mm = 0, dy_mm = 0;  // carried by tissue dragging: drawn at (x + dx, y + dy)
  double depth_mm = 0;          // how far it sank
  int tier = 0;                 // 0 at the contact, n at the border
};

// Vertices row by row ((2n+1)^2 of them), spaced cell_mm apart, for a contact at (x_mm, y_mm)
// whose tissue is carried by (drag_x_mm, drag_y_mm).
std::vector<GridVertex> tiered_grid(double x_mm, double y_mm, double depth_mm, int n, double cell_mm,
                                    double drag_x_mm = 0, double drag_y_mm = 0);

}  // namespace palprig::gui
