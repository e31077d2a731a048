#include "models/fe_stress_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace palprig {

namespace {

// Where a query falls on one axis: between grid index lo and hi (-1: the implicit point before
// the grid, whose rise is 0), hi's weight w.
struct Bracket {
  int lo = 0, hi = 0;
  double w = 0;
};

// `positions` of the grid (already on the interpolation scale); `implicit` the position of the
// point before the grid where the rise is 0, or NaN for none (the query is clamped instead).
Bracket bracket(const std::vector<double>& positions, double q, double implicit) noexcept {
  const int n = int(positions.size());
  if (!(q == q)) q = positions.front();  // NaN: the grid's first point (the tick checks inputs)
  if (q >= positions[std::size_t(n - 1)]) return {n - 1, n - 1, 0};
  if (q <= positions[0]) {
    if (std::isnan(implicit)) return {0, 0, 0};  // clamped to the grid's first point
    if (q <= implicit) return {-1, -1, 0};
    return {-1, 0, (q - implicit) / (positions[0] - implicit)};
  }
  int i = 0;
  while (i + 1 < n && positions[std::size_t(i) + 1] < q) ++i;
  return {i, i + 1, (q - positions[std::size_t(i)]) / (positions[std::size_t(i) + 1] - positions[std::size_t(i)])};
}

void check_axis(const std::vector<double>& axis, double lowest, bool strictly_above, const char* name) {
  if (axis.empty()) throw std::invalid_argument(std::string("the ") + name + " axis is empty");
  for (std::size_t i = 0; i < axis.size(); ++i) {
    const double v = axis[i];
    if (!std::isfinite(v) || v < lowest || (strictly_above && v <= lowest))
      throw std::invalid_argument(std::string("the ") + name + " axis has a value out of range");
    if (i > 0 && !(v > axis[i - 1]))
      throw std::invalid_argument(std::string("the ") + name + " axis is not increasing");
  }
}

}  // namespace

std::size_t FeTableAxes::cells() const noexcept {
  return cover_mm.size() * diameter_mm.size() * contrast.size() * offset_mm.size();
}

std::size_t FeTableAxes::values() const noexcept { return indentation_mm.size() * cells(); }

FeStressTable::FeStressTable(FeTableAxes axes, std::vector<double> peak_kPa, std::vector<double> healthy_kPa)
    : axes_(std::move(axes)), peak_(std::move(peak_kPa)), healthy_(std::move(healthy_kPa)) {
  check_axis(axes_.indentation_mm, 0, true, "indentation");
  check_axis(axes_.cover_mm, 0, false, "cover");
  check_axis(axes_.diameter_mm, 0, true, "diameter");
  check_axis(axes_.contrast, 1, true, "contrast");
  check_axis(axes_.offset_mm, 0, false, "offset");
  if (peak_.size() != axes_.values()) throw std::invalid_argument("the table's values do not fill its grid");
  if (healthy_.size() != axes_.indentation_mm.size())
    throw std::invalid_argument("the healthy peaks do not match the indentation axis");
  for (double v : peak_)
    if (!std::isfinite(v) || v < 0) throw std::invalid_argument("a table value is not a finite stress");
  for (double v : healthy_)
    if (!std::isfinite(v) || v < 0) throw std::invalid_argument("a healthy peak is not a finite stress");
  stride_[4] = 1;
  stride_[3] = axes_.offset_mm.size();
  stride_[2] = stride_[3] * axes_.contrast.size();
  stride_[1] = stride_[2] * axes_.diameter_mm.size();
  stride_[0] = stride_[1] * axes_.cover_mm.size();
  // The contrast is interpolated on a log scale: store the axis as it is, convert per query.
}

std::size_t FeStressTable::index(std::size_t i, std::size_t c, std::size_t d, std::size_t k,
                                 std::size_t o) const noexcept {
  return i * stride_[0] + c * stride_[1] + d * stride_[2] + k * stride_[3] + o * stride_[4];
}

double FeStressTable::healthy_kPa(double indentation_mm) const noexcept {
  const Bracket b = bracket(axes_.indentation_mm, indentation_mm, 0.0);
  auto at = [&](int i) { return i < 0 ? 0.0 : healthy_[std::size_t(i)]; };
  return (1 - b.w) * at(b.lo) + b.w * at(b.hi);
}

double FeStressTable::rise_kPa(double indentation_mm, double cover_mm, double diameter_mm, double contrast,
                               double offset_mm) const noexcept {
  // The contrast axis on a log scale; its implicit point (contrast 1) at 0. No allocation: the
  // log positions are computed for the two neighbours only.
  const auto& ks = axes_.contrast;
  Bracket bk;
  {
    const double q = std::log(std::max(contrast, 1e-9));
    const int n = int(ks.size());
    if (!(q == q) || q <= 0) {
      bk = {-1, -1, 0};
    } else if (q >= std::log(ks[std::size_t(n - 1)])) {
      bk = {n - 1, n - 1, 0};
    } else if (q <= std::log(ks[0])) {
      bk = {-1, 0, q / std::log(ks[0])};
    } else {
      int i = 0;
      while (i + 1 < n && std::log(ks[std::size_t(i) + 1]) < q) ++i;
      const double l0 = std::log(ks[std::size_t(i)]), l1 = std::log(ks[std::size_t(i) + 1]);
      bk = {i, i + 1, (q - l0) / (l1 - l0)};
    }
  }
  const std::array<Bracket, kFeTableAxes> b = {
      bracket(axes_.indentation_mm, indentation_mm, 0.0), bracket(axes_.cover_mm, cover_mm, std::nan("")),
      bracket(axes_.diameter_mm, diameter_mm, 0.0), bk, bracket(axes_.offset_mm, offset_mm, std::nan(""))};
  double sum = 0;
  for (unsigned corner = 0; corner < (1u << kFeTableAxes); ++corner) {
    double weight = 1;
    std::array<int, kFeTableAxes> at{};
    bool implicit = false;
    for (std::size_t a = 0; a < kFeTableAxes; ++a) {
      const bool high = (corner >> a) & 1u;
      weight *= high ? b[a].w : 1 - b[a].w;
      at[a] = high ? b[a].hi : b[a].lo;
      implicit = implicit || at[a] < 0;
    }
    if (weight == 0 || implicit) continue;  // the healthy block: no rise
    const std::size_t k =
        index(std::size_t(at[0]), std::size_t(at[1]), std::size_t(at[2]), std::size_t(at[3]), std::size_t(at[4]));
    sum += weight * (peak_[k] - healthy_[std::size_t(at[0])]);
  }
  return std::max(0.0, sum);
}

double FeStressTable::peak_kPa(double indentation_mm, double cover_mm, double diameter_mm, double contrast,
                               double offset_mm) const noexcept {
  return healthy_kPa(indentation_mm) + rise_kPa(indentation_mm, cover_mm, diameter_mm, contrast, offset_mm);
}

}  // namespace palprig
