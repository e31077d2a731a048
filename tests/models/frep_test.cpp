// FRep shapes (paper 001): membership at known points, blobs, set operations, scaling, and
// conservative bounding boxes.
#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "models/frep.hpp"

using namespace palprig;

TEST(Frep, SphereInsideOutsideAndSurface) {
  FrepShape s;
  s.sphere({10, 20, 5}, 4);
  EXPECT_TRUE(s.contains({10, 20, 5}));
  EXPECT_TRUE(s.contains({13.9, 20, 5}));
  EXPECT_FALSE(s.contains({14.1, 20, 5}));
  EXPECT_NEAR(s.value({14, 20, 5}), 0.0, 1e-12);  // on the surface
  EXPECT_NEAR(s.value({10, 20, 5}), 1.0, 1e-12);
}

TEST(Frep, EllipsoidTurnedByYaw) {
  FrepShape s;
  s.ellipsoid({0, 0, 10}, {10, 2, 3}, 90);  // long axis now along y
  EXPECT_TRUE(s.contains({0, 9.5, 10}));
  EXPECT_FALSE(s.contains({9.5, 0, 10}));
  EXPECT_TRUE(s.contains({1.9, 0, 10}));
  EXPECT_FALSE(s.contains({0, 0, 13.5}));
}

TEST(Frep, SuperEllipsoidIsFlatWithBluntCorners) {
  FrepShape body;
  body.superellipsoid({0, 0, 0}, {10, 10, 10}, 6);
  // A sphere of the same radius misses the near-corner point; the exponent-6 body holds it.
  EXPECT_TRUE(body.contains({8, 8, 0}));
  FrepShape ball;
  ball.sphere({0, 0, 0}, 10);
  EXPECT_FALSE(ball.contains({8, 8, 0}));
  EXPECT_FALSE(body.contains({9.5, 9.5, 0}));  // the very corner is rounded off
}

TEST(Frep, TubeAroundASegment) {
  FrepShape s;
  s.tube({0, 0, 5}, {100, 0, 5}, 3);
  EXPECT_TRUE(s.contains({50, 2.9, 5}));
  EXPECT_FALSE(s.contains({50, 3.1, 5}));
  EXPECT_TRUE(s.contains({101, 0, 6}));  // the rounded end cap
  EXPECT_FALSE(s.contains({104, 0, 5}));
}

TEST(Frep, SingleBlobWithThresholdOneOverEIsABallOfItsRadius) {
  // k exp(-|p - c|^2 / sigma^2) >= exp(-1)  <=>  |p - c| <= sigma (k = 1).
  FrepShape s;
  const double sigma = 5;
  s.blobs({{{0, 0, 10}, 1.0, {1 / (sigma * sigma), 1 / (sigma * sigma), 1 / (sigma * sigma)}}}, std::exp(-1.0));
  EXPECT_TRUE(s.contains({4.99, 0, 10}));
  EXPECT_FALSE(s.contains({5.01, 0, 10}));
  EXPECT_NEAR(s.value({5, 0, 10}), 0.0, 1e-12);
}

TEST(Frep, BlobsBlendWhereNeitherAloneReaches) {
  // Two blobs 12 mm apart, each of radius 5 alone: the midpoint is outside both, but their sum
  // (2 exp(-36/25) = 0.47) passes the threshold 1/e: blobby objects merge (paper 001's organs).
  const double s2 = 1.0 / 25;
  FrepShape pair;
  pair.blobs({{{-6, 0, 0}, 1, {s2, s2, s2}}, {{6, 0, 0}, 1, {s2, s2, s2}}}, std::exp(-1.0));
  FrepShape one;
  one.blobs({{{-6, 0, 0}, 1, {s2, s2, s2}}}, std::exp(-1.0));
  EXPECT_TRUE(pair.contains({0, 0, 0}));
  EXPECT_FALSE(one.contains({0, 0, 0}));
  // F = sum k_i f_i - c at a known point: both blobs contribute exp(-1.44).
  EXPECT_NEAR(pair.value({0, 0, 0}), 2 * std::exp(-36.0 / 25) - std::exp(-1.0), 1e-12);
}

TEST(Frep, UnionIsMaxIntersectionIsMinDifferenceCuts) {
  FrepShape u;
  const auto a = u.sphere({0, 0, 0}, 5), b = u.sphere({8, 0, 0}, 5);
  u.unite({a, b});
  EXPECT_TRUE(u.contains({-4, 0, 0}));
  EXPECT_TRUE(u.contains({12, 0, 0}));
  EXPECT_TRUE(u.contains({4, 0, 0}));
  EXPECT_NEAR(u.value({4, 0, 0}), std::max(1 - 16.0 / 25, 1 - 16.0 / 25), 1e-12);

  FrepShape i;
  const auto c = i.sphere({0, 0, 0}, 5), d = i.sphere({8, 0, 0}, 5);
  i.intersect({c, d});
  EXPECT_FALSE(i.contains({-4, 0, 0}));
  EXPECT_FALSE(i.contains({12, 0, 0}));
  EXPECT_TRUE(i.contains({4, 0, 0}));
  EXPECT_NEAR(i.value({3, 0, 0}), std::min(1 - 9.0 / 25, 1 - 25.0 / 25), 1e-12);

  FrepShape diff;
  const auto e = diff.sphere({0, 0, 0}, 5), f = diff.sphere({5, 0, 0}, 3);
  diff.subtract(e, f);
  EXPECT_TRUE(diff.contains({-4, 0, 0}));
  EXPECT_FALSE(diff.contains({4, 0, 0}));  // carved away
  EXPECT_FALSE(diff.contains({7, 0, 0}));  // in the cut only
}

TEST(Frep, ScaledShapeIsTheEnlargedOrgan) {
  FrepShape s;
  const auto liver = s.sphere({10, 0, 0}, 5);
  s.scaled(liver, {0, 0, 0}, {1.5, 1.5, 1.5});  // enlarged about the origin: centre 15, radius 7.5
  EXPECT_TRUE(s.contains({22, 0, 0}));
  EXPECT_FALSE(s.contains({23, 0, 0}));
  EXPECT_TRUE(s.contains({8, 0, 0}));
  EXPECT_FALSE(s.contains({7, 0, 0}));
  const Box3_mm b = s.bounds();
  EXPECT_NEAR(b.lo.x_mm, 7.5, 1e-9);
  EXPECT_NEAR(b.hi.x_mm, 22.5, 1e-9);
}

TEST(Frep, BoundingBoxesHoldEveryInsidePoint) {
  // Random points over a wide box: every point inside the shape lies in its bounds.
  FrepShape s;
  const double s2 = 1.0 / 16;
  const auto blob = s.blobs(
      {{{0, 0, 10}, 1, {s2, s2, s2}}, {{7, 3, 12}, 0.8, {s2, 2 * s2, s2}}, {{-5, 6, 9}, 1.2, {s2, s2, 3 * s2}}}, 0.3);
  const auto ell = s.ellipsoid({20, -5, 15}, {8, 3, 4}, 35);
  const auto sup = s.superellipsoid({-15, 10, 12}, {6, 4, 3}, 6, 60);
  const auto tube = s.tube({-20, -20, 5}, {0, -10, 20}, 2.5);
  const auto scaled = s.scaled(ell, {10, 0, 10}, {1.3, 0.8, 1.1});
  s.unite({blob, scaled, sup, tube});
  const Box3_mm box = s.bounds();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-40, 40);
  int inside = 0;
  for (int k = 0; k < 200000; ++k) {
    const Point3_mm p{u(rng), u(rng), u(rng) * 0.5 + 12};
    if (!s.contains(p)) continue;
    ++inside;
    ASSERT_TRUE(box.contains(p)) << p.x_mm << " " << p.y_mm << " " << p.z_mm;
  }
  EXPECT_GT(inside, 1000);  // the test did look at inside points
}

TEST(Frep, UndefinedShapeIsEmptyAndBadSizesAreRefused) {
  FrepShape empty;
  EXPECT_FALSE(empty.contains({0, 0, 0}));
  EXPECT_TRUE(empty.bounds().empty());
  FrepShape s;
  EXPECT_THROW(s.sphere({0, 0, 0}, -1), palprig::BadInput);
  EXPECT_THROW(s.sphere({0, 0, 0}, 0), palprig::BadInput);
  EXPECT_THROW(s.ellipsoid({0, 0, 0}, {1, -2, 1}), palprig::BadInput);
  EXPECT_THROW(s.blobs({}, 1), palprig::BadInput);
  EXPECT_THROW(s.blobs({{{0, 0, 0}, 1, {1, 1, 1}}}, 0), palprig::BadInput);
  EXPECT_THROW(s.superellipsoid({0, 0, 0}, {1, 1, 1}, 1.5), palprig::BadInput);
  EXPECT_THROW(s.unite({3}), palprig::BadInput);
  EXPECT_THROW(s.tube({0, 0, 0}, {1, 0, 0}, std::nan("")), palprig::BadInput);
}
