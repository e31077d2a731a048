#pragma once
// StiffnessMap: normalised tissue stiffness (0 soft .. 1 hardest) on a regular grid laid over a
// physical rectangle, as measured from paper 002's silicone phantom. Sampling is nearest-vertex
// (the paper's rule) or bilinear; outside the rectangle the map either clamps to its edge or
// returns a configured background stiffness.
#include <cstddef>
#include <initializer_list>
#include <iosfwd>
#include <string>
#include <vector>

#include "models/huge_page_allocator.hpp"

namespace palprig {

// A map's values, row-major: on 2 MiB pages when the map is large (models/huge_page_allocator.hpp).
using MapValues = std::vector<float, HugePageAllocator<float>>;

enum class MapSampling { nearest, bilinear };

struct OutsidePolicy {
  enum class Kind { clamp, background } kind = Kind::clamp;
  double background_stiffness = 0.0;  // used when kind == background, in 0..1
};

class StiffnessMap {
 public:
  StiffnessMap() = default;
  // values: rows*cols in row-major order, row 0 at y = 0 mm; each must be finite and in 0..1.
  StiffnessMap(std::size_t cols, std::size_t rows, double width_mm, double height_mm, MapValues values,
               OutsidePolicy outside = {});
  // The same from a plain vector (tests, generated maps): its values are copied.
  StiffnessMap(std::size_t cols, std::size_t rows, double width_mm, double height_mm, const std::vector<float>& values,
               OutsidePolicy outside = {})
      : StiffnessMap(cols, rows, width_mm, height_mm, MapValues(values.begin(), values.end()), outside) {}
  StiffnessMap(std::size_t cols, std::size_t rows, double width_mm, double height_mm,
               std::initializer_list<float> values, OutsidePolicy outside = {})
      : StiffnessMap(cols, rows, width_mm, height_mm, MapValues(values), outside) {}

  std::size_t cols() const noexcept { return cols_; }
  std::size_t rows() const noexcept { return rows_; }
  double width_mm() const noexcept { return width_mm_; }
  double height_mm() const noexcept { return height_mm_; }
  const OutsidePolicy& outside() const noexcept { return outside_; }
  void set_outside(OutsidePolicy p) noexcept { outside_ = p; }
  float at(std::size_t col, std::size_t row) const noexcept { return values_[row * cols_ + col]; }
  const MapValues& values() const noexcept { return values_; }

  // Vertex (col, row) sits at x = col * width/(cols-1), y = row * height/(rows-1).
  double sample_nearest(double x_mm, double y_mm) const noexcept;
  double sample_bilinear(double x_mm, double y_mm) const noexcept;
  double sample(double x_mm, double y_mm, MapSampling how) const noexcept {
    return how == MapSampling::nearest ? sample_nearest(x_mm, y_mm) : sample_bilinear(x_mm, y_mm);
  }
  // Start fetching the cells sample(x_mm, y_mm, how) will read, without waiting for them: on a
  // map much larger than the cache each sample is a cache and TLB miss, and the tick's samples of
  // one tick (every finger, now and ahead) are independent, so asking for all of them first lets
  // their misses overlap instead of queueing one behind the other.
  void prefetch(double x_mm, double y_mm, MapSampling how) const noexcept;

 private:
  // Grid coordinates of a point, or false when outside and the policy is background.
  bool to_grid(double x_mm, double y_mm, double& gx, double& gy) const noexcept;

  std::size_t cols_ = 0, rows_ = 0;
  double width_mm_ = 0, height_mm_ = 0;
  MapValues values_;
  OutsidePolicy outside_;
};

// Parsers take a stream and the name to report in errors (the file path); they throw
// InputError naming the line or field and what was expected.
//
// Largest map either reader accepts: 16384 vertices a side and 4096x4096 (16.8 M) in all,
// 64 MB of floats - finer than any rig's fingers can feel over a hand-sized phantom.
inline constexpr long kMaxMapSide = 16384;
inline constexpr long kMaxMapVertices = 4096L * 4096L;

// CSV: one grid row per line, comma separated, '#' comment lines allowed. Values must lie in
// 0..1 unless value_scale is given (e.g. 65535 for raw counts), then value/scale must.
StiffnessMap parse_stiffness_csv(std::istream& in, const std::string& source, double width_mm, double height_mm,
                                 double value_scale = 0.0);
// PGM: binary P5 with maxval up to 65535 (16-bit big-endian) or ASCII P2; value / maxval.
StiffnessMap parse_stiffness_pgm(std::istream& in, const std::string& source, double width_mm, double height_mm);
// Writers (used by scene rendering and tests).
void write_stiffness_csv(std::ostream& out, const StiffnessMap& map);
void write_stiffness_pgm16(std::ostream& out, const StiffnessMap& map);

}  // namespace palprig
