#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "models/finger_layout.hpp"

using namespace palprig;

TEST(FingerLayout, RightAngleVertexFollowsThePen) {
  FingerLayout layout{16.0, 0.0};
  const auto f = layout.centres(50, 30);
  EXPECT_DOUBLE_EQ(f[0].x_mm, 50);
  EXPECT_DOUBLE_EQ(f[0].y_mm, 30);
  EXPECT_DOUBLE_EQ(f[1].x_mm, 66);
  EXPECT_DOUBLE_EQ(f[1].y_mm, 30);
  EXPECT_DOUBLE_EQ(f[2].x_mm, 50);
  EXPECT_DOUBLE_EQ(f[2].y_mm, 46);
}

TEST(FingerLayout, TriangleIsRightAngledWithEqualLegsAtAnyOrientation) {
  for (double deg : {0.0, 30.0, 90.0, -135.0, 271.0}) {
    FingerLayout layout{12.5, deg};
    const auto f = layout.centres(-3, 7);
    const double ax = f[1].x_mm - f[0].x_mm, ay = f[1].y_mm - f[0].y_mm;
    const double bx = f[2].x_mm - f[0].x_mm, by = f[2].y_mm - f[0].y_mm;
    EXPECT_NEAR(ax * bx + ay * by, 0.0, 1e-9) << deg;  // right angle at the pen
    EXPECT_NEAR(std::hypot(ax, ay), 12.5, 1e-9) << deg;
    EXPECT_NEAR(std::hypot(bx, by), 12.5, 1e-9) << deg;
    EXPECT_NEAR(std::atan2(ay, ax), std::remainder(deg, 360.0) * M_PI / 180.0, 1e-9) << deg;
  }
}

TEST(FingerLayout, NinetyDegreesRotatesCounterClockwise) {
  FingerLayout layout{10.0, 90.0};
  const auto f = layout.centres(0, 0);
  EXPECT_NEAR(f[1].x_mm, 0, 1e-9);
  EXPECT_NEAR(f[1].y_mm, 10, 1e-9);
  EXPECT_NEAR(f[2].x_mm, -10, 1e-9);
  EXPECT_NEAR(f[2].y_mm, 0, 1e-9);
}

// The layout's axis is kept per thread for the orientation it was computed for: layouts of
// different orientations used in turn, and on two threads, each get their own triangle.
TEST(FingerLayout, LayoutsOfDifferentOrientationsInTurnEachGetTheirOwnAxis) {
  const FingerLayout a{10.0, 0.0}, b{10.0, 90.0};
  auto check = [&] {
    for (int k = 0; k < 3; ++k) {
      EXPECT_DOUBLE_EQ(a.centres(0, 0)[1].x_mm, 10.0);
      EXPECT_NEAR(b.centres(0, 0)[1].x_mm, 0.0, 1e-12);
      EXPECT_NEAR(b.centres(0, 0)[1].y_mm, 10.0, 1e-12);
      EXPECT_DOUBLE_EQ(a.centres(0, 0)[2].y_mm, 10.0);
    }
  };
  check();
  std::thread other(check);
  check();
  other.join();
}
