// The finite-element table's lookups: exact at its grid points, linear between them (the
// contrast on a log scale), the healthy block at contrast 1, diameter 0 and indentation 0,
// clamped beyond its ends, and refused when its grid is not one.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "models/fe_stress_table.hpp"

namespace palprig {
namespace {

// peak = healthy(i) + cover-, diameter-, contrast- and offset-dependent rise, made up so each
// axis' effect is known.
FeStressTable made_up_table() {
  FeTableAxes ax;
  ax.indentation_mm = {2, 4};
  ax.cover_mm = {1, 5};
  ax.diameter_mm = {5, 10};
  ax.contrast = {2, 8};
  ax.offset_mm = {0, 10};
  const std::vector<double> healthy = {1.0, 3.0};
  std::vector<double> peak;
  for (std::size_t i = 0; i < 2; ++i)
    for (double c : ax.cover_mm)
      for (double d : ax.diameter_mm)
        for (double k : ax.contrast)
          for (double o : ax.offset_mm)
            peak.push_back(healthy[i] + (o == 0 ? 1.0 : 0.0) * (c == 1 ? 2.0 : 1.0) * d / 5 * std::log2(k) * (i + 1));
  return FeStressTable(ax, peak, healthy);
}

TEST(FeStressTable, ExactAtGridPoints) {
  const FeStressTable t = made_up_table();
  EXPECT_DOUBLE_EQ(t.peak_kPa(4, 1, 10, 8, 0), 3.0 + 2 * 2 * 3 * 2);
  EXPECT_DOUBLE_EQ(t.peak_kPa(2, 5, 5, 2, 0), 1.0 + 1);
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 5, 5, 2, 10), 0.0);
  EXPECT_DOUBLE_EQ(t.healthy_kPa(4), 3.0);
}

TEST(FeStressTable, LinearBetweenPointsAndLogInContrast) {
  const FeStressTable t = made_up_table();
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 3, 5, 2, 0), 1.5);    // halfway in cover
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 1, 5, 2, 5), 1.0);    // halfway in offset
  EXPECT_NEAR(t.rise_kPa(2, 5, 5, 4, 0), 2.0, 1e-12);  // log2(4) halfway between log2(2) and log2(8)
  EXPECT_DOUBLE_EQ(t.healthy_kPa(3), 2.0);
}

TEST(FeStressTable, HealthyAtContrastOneDiameterZeroAndNoPress) {
  const FeStressTable t = made_up_table();
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 5, 5, 1.0, 0), 0.0);
  EXPECT_NEAR(t.rise_kPa(2, 5, 5, std::sqrt(2.0), 0), 0.5, 1e-12);  // halfway to contrast 2 on a log scale
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 5, 2.5, 2, 0), 0.5);               // halfway to diameter 5
  EXPECT_DOUBLE_EQ(t.healthy_kPa(0), 0.0);
  EXPECT_DOUBLE_EQ(t.healthy_kPa(1), 0.5);
  EXPECT_DOUBLE_EQ(t.rise_kPa(0, 5, 5, 2, 0), 0.0);
}

TEST(FeStressTable, ClampedBeyondTheGrid) {
  const FeStressTable t = made_up_table();
  EXPECT_DOUBLE_EQ(t.rise_kPa(9, 1, 10, 8, 0), t.rise_kPa(4, 1, 10, 8, 0));
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 0, 5, 2, 0), t.rise_kPa(2, 1, 5, 2, 0));
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 30, 5, 2, 0), t.rise_kPa(2, 5, 5, 2, 0));
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 1, 50, 80, 40), 0.0);
  EXPECT_DOUBLE_EQ(t.rise_kPa(2, 1, 50, 80, 0), t.rise_kPa(2, 1, 10, 8, 0));
  EXPECT_TRUE(std::isfinite(t.peak_kPa(std::nan(""), std::nan(""), std::nan(""), std::nan(""), std::nan(""))));
}

TEST(FeStressTable, RefusesWhatIsNotAGrid) {
  FeTableAxes ax;
  ax.indentation_mm = {2, 1};
  ax.cover_mm = {1};
  ax.diameter_mm = {5};
  ax.contrast = {2};
  ax.offset_mm = {0};
  EXPECT_THROW(FeStressTable(ax, {1, 1}, {1, 1}), std::invalid_argument);  // not increasing
  ax.indentation_mm = {1, 2};
  ax.contrast = {0.5};
  EXPECT_THROW(FeStressTable(ax, {1, 1}, {1, 1}), std::invalid_argument);  // contrast <= 1
  ax.contrast = {2};
  EXPECT_THROW(FeStressTable(ax, {1}, {1, 1}), std::invalid_argument);  // too few values
  EXPECT_THROW(FeStressTable(ax, {1, std::nan("")}, {1, 1}), std::invalid_argument);
  EXPECT_NO_THROW(FeStressTable(ax, {1, 2}, {1, 1}));
}

}  // namespace
}  // namespace palprig
