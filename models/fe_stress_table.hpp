#pragma once
// The finite-element table: the peak fingertip contact stress computed by `palprig fe table`
// (mechanics/) over a grid of
//   indentation depth x nodule cover (depth of its top) x nodule diameter x stiffness contrast
//   (nodule / tissue, small-strain moduli) x lateral offset of the fingertip from the nodule,
// with the healthy block's peak per indentation depth, for the tick to interpolate instead of
// the felt-stiffness rule (function scenes with "fe_stress_table"; models/tissue_scene.hpp).
//
// Lookups are pure and allocation-free: a multilinear interpolation over the five axes (the
// contrast on a log scale), every query clamped to the grid, with two points the grid implies:
// contrast 1 and diameter 0 are the healthy block (no rise). Beyond the largest offset and
// cover the values are those at the edge (the builder's grid ends where the rise has died out).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace palprig {

inline constexpr std::size_t kFeTableAxes = 5;

struct FeTableAxes {
  std::vector<double> indentation_mm;   // increasing, > 0
  std::vector<double> cover_mm;         // depth of the nodule's top, increasing, >= 0
  std::vector<double> diameter_mm;      // increasing, > 0
  std::vector<double> contrast;         // nodule / tissue modulus, increasing, > 1
  std::vector<double> offset_mm;        // fingertip centre to nodule centre, increasing, >= 0
  std::size_t cells() const noexcept;   // combinations of the last four (solves needed)
  std::size_t values() const noexcept;  // every grid point
};

class FeStressTable {
 public:
  // peak_kPa in row-major order over (indentation, cover, diameter, contrast, offset), the
  // offset fastest; healthy_kPa per indentation. Throws std::invalid_argument for axes that are
  // empty, not increasing or out of their ranges, for sizes that do not match, or for values
  // that are not finite.
  FeStressTable(FeTableAxes axes, std::vector<double> peak_kPa, std::vector<double> healthy_kPa);

  // The fingertip's peak contact stress (kPa) pressed `indentation_mm` deep near one nodule.
  double peak_kPa(double indentation_mm, double cover_mm, double diameter_mm, double contrast,
                  double offset_mm) const noexcept;
  double healthy_kPa(double indentation_mm) const noexcept;
  // What the nodule adds to the healthy peak at the same indentation (never negative).
  double rise_kPa(double indentation_mm, double cover_mm, double diameter_mm, double contrast,
                  double offset_mm) const noexcept;

  const FeTableAxes& axes() const noexcept { return axes_; }
  const std::vector<double>& peaks_kPa() const noexcept { return peak_; }
  const std::vector<double>& healthy() const noexcept { return healthy_; }
  std::size_t index(std::size_t i, std::size_t c, std::size_t d, std::size_t k, std::size_t o) const noexcept;

 private:
  FeTableAxes axes_;
  std::vector<double> peak_, healthy_;
  std::array<std::size_t, kFeTableAxes> stride_{};
};

}  // namespace palprig
