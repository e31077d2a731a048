// The maths of tracked fingers: rigid transforms and quaternions, point-based
// registration (Umeyama) with its FRE, pivot calibration and static digitization (paper 003
// eqs. 1 and 2), the rest detector, finger placement, the load cell and its simulation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/error.hpp"
#include "models/finger_placement.hpp"
#include "models/load_cell.hpp"
#include "models/point_registration.hpp"
#include "models/pose_hold.hpp"
#include "models/rigid_transform.hpp"
#include "models/tip_calibration.hpp"

using namespace palprig;

namespace {

Rotation3 rot(double axis_x, double axis_y, double axis_z, double deg) {
  const double n = std::sqrt(axis_x * axis_x + axis_y * axis_y + axis_z * axis_z);
  const double h = deg * std::numbers::pi / 360.0;
  Rotation3 r;
  EXPECT_TRUE(rotation_from_quaternion(std::sin(h) * axis_x / n, std::sin(h) * axis_y / n, std::sin(h) * axis_z / n,
                                       std::cos(h), r));
  return r;
}

RigidTransform pose(const Rotation3& r, Vec3_mm t) {
  RigidTransform p;
  p.rotation = r;
  p.translation_mm = t;
  return p;
}

}  // namespace

TEST(RigidTransform, ComposesInvertsAndChecksRotations) {
  const RigidTransform a = pose(rot(0, 0, 1, 90), {10, 0, 0});
  const Vec3_mm p = a.apply({1, 0, 0});
  EXPECT_NEAR(p[0], 10, 1e-12);
  EXPECT_NEAR(p[1], 1, 1e-12);
  const Vec3_mm back = a.inverse().apply(p);
  EXPECT_NEAR(back[0], 1, 1e-12);
  EXPECT_NEAR(back[1], 0, 1e-12);
  const RigidTransform b = pose(rot(1, 0, 0, 30), {0, 5, -2});
  const Vec3_mm q = b.after(a).apply({3, 4, 5}), r = b.apply(a.apply({3, 4, 5}));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(q[i], r[i], 1e-12);
  EXPECT_TRUE(is_rotation(a.rotation));
  EXPECT_FALSE(is_rotation(Rotation3{}));                                    // all zeros: a lost tool
  EXPECT_FALSE(is_rotation(Rotation3{{{1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}));  // a mirror
  EXPECT_FALSE(is_rotation(Rotation3{{{2, 0, 0}, {0, 1, 0}, {0, 0, 1}}}));   // a scale
  Rotation3 q0;
  EXPECT_FALSE(rotation_from_quaternion(0, 0, 0, 0, q0));
}

TEST(PointRegistration, RecoversAKnownTransformWithTheFiducialError) {
  const RigidTransform truth = pose(rot(0.2, -0.5, 1, 137), {-150, 40, -200});
  const std::vector<Vec3_mm> scene = {{10, 10, 0}, {150, 10, 0}, {150, 110, 0}, {10, 110, 5}, {80, 60, 20}};
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0, 0.2);
  std::vector<Vec3_mm> tracker;
  const RigidTransform to_tracker = truth.inverse();
  for (const auto& s : scene) {
    Vec3_mm t = to_tracker.apply(s);
    for (double& v : t) v += noise(rng);
    tracker.push_back(t);
  }
  const PointRegistration reg = register_points(tracker, scene);
  // FRE of a 0.2 mm per-axis noise (0.35 mm per point) over 5 points, 6 parameters fitted.
  EXPECT_GT(reg.fre_mm, 0.05);
  EXPECT_LT(reg.fre_mm, 0.5);
  ASSERT_EQ(reg.residual_mm.size(), scene.size());
  // Within a millimetre everywhere on the phantom.
  for (const Vec3_mm s : {Vec3_mm{0, 0, 0}, Vec3_mm{160, 120, 0}}) {
    const Vec3_mm a = reg.from_to.apply(to_tracker.apply(s));
    EXPECT_LT(distance_mm(a, s), 1.0);
  }
  // Exact data: exact transform.
  std::vector<Vec3_mm> exact;
  exact.reserve(scene.size());
  for (const auto& s : scene) exact.push_back(to_tracker.apply(s));
  EXPECT_LT(register_points(exact, scene).fre_mm, 1e-9);
}

TEST(PointRegistration, RefusesWhatCannotFixARotation) {
  EXPECT_THROW(register_points({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}), palprig::BadInput);
  EXPECT_THROW(register_points({{0, 0, 0}, {10, 0, 0}, {20, 0, 0}}, {{0, 0, 0}, {10, 0, 0}, {20, 0.1, 0}}),
               palprig::BadInput);
  EXPECT_THROW(register_points({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 0}, {1, 0, 0}}), palprig::BadInput);
  try {
    register_points({{0, 0, 0}, {10, 0, 0}, {20, 0, 0}}, {{0, 0, 0}, {10, 0, 0}, {20, 0, 0}});
    FAIL();
  } catch (const palprig::BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("one line"), std::string::npos) << e.what();
  }
}

TEST(TipCalibration, StaticDigitizationInvertsPaper003Eq1) {
  const RigidTransform sensor = pose(rot(1, 2, 3, 40), {12, -7, 30});
  const Vec3_mm tip_local{0, 0, -12};
  // Eq. 1: p = o + R p_local; eq. 2 gives p_local back.
  const Vec3_mm p = sensor.apply(tip_local);
  const Vec3_mm back = digitize_tip(sensor, p);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], tip_local[i], 1e-12);
}

TEST(TipCalibration, PivotFindsTheTipAndItsResidual) {
  const Vec3_mm tip{1.5, -2, -12}, pivot{80, 60, -200};
  std::vector<RigidTransform> poses;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0, 0.1);
  for (int k = 0; k < 60; ++k) {
    const double yaw = 6.0 * k;
    // A cone about the vertical (the tool's axis circles it), as a hand pivots: turning about a
    // fixed axis only would leave the tip along that axis free.
    const Rotation3 r = RigidTransform{rot(0, 0, 1, yaw), {}}
                            .after(RigidTransform{rot(0, 1, 0, 25), {}})
                            .after(RigidTransform{rot(0, 0, 1, -yaw), {}})
                            .rotation;
    RigidTransform p{r, {}};
    const Vec3_mm off = p.rotate(tip);
    for (int i = 0; i < 3; ++i) p.translation_mm[i] = pivot[i] - off[i] + noise(rng);
    poses.push_back(p);
  }
  const PivotCalibration pc = pivot_calibrate(poses);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(pc.tip_mm[i], tip[i], 0.3);
    EXPECT_NEAR(pc.pivot_mm[i], pivot[i], 0.3);
  }
  EXPECT_GT(pc.rms_mm, 0.05);
  EXPECT_LT(pc.rms_mm, 0.3);
  EXPECT_NEAR(pc.rotation_spread_deg, 50, 1);
}

TEST(TipCalibration, PivotRefusesTooFewOrOneAxisOrStillPoses) {
  std::vector<RigidTransform> still(10, RigidTransform{});
  EXPECT_THROW(pivot_calibrate(still), palprig::BadInput);
  EXPECT_THROW(pivot_calibrate({RigidTransform{}, RigidTransform{}, RigidTransform{}}), palprig::BadInput);
  // Turning about z only: the tip along z is free.
  std::vector<RigidTransform> one_axis;
  one_axis.reserve(20);
  for (int k = 0; k < 20; ++k) one_axis.push_back(RigidTransform{rot(0, 0, 1, 5.0 * k), {0, 0, 0}});
  try {
    pivot_calibrate(one_axis);
    FAIL();
  } catch (const palprig::BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("more than one axis"), std::string::npos) << e.what();
  }
}

TEST(HoldTime, ARestDeliveredInOneBurstIsCountedInTheTrackersStamps) {
  HoldTime time;
  PointHold hold(1.0, 1.0);
  const double stamp0 = 1.7e9, arrived_s = 5.0;  // every pose arrives at once
  int k = 0;
  while (!hold.add(time.at(stamp0 + 0.025 * k, arrived_s), {1, 2, 3})) ASSERT_LT(++k, 100);
  EXPECT_NEAR(k, 40, 1);  // one second of the tracker's time (the stamps rounded at 1.7e9 s)
  EXPECT_TRUE(time.stamped());
}

TEST(HoldTime, StampsThatAreNotAClockFallBackToArrivalAndNeverEndAHoldEarly) {
  // None (0), unset and constant (what libopenigtlink 1.11 leaves), and one that jumps.
  for (const double garbage : {0.0, 3.2e9}) {
    HoldTime time;
    PointHold hold(1.0, 1.0);
    int k = 0;
    while (!hold.add(time.at(garbage, 0.025 * k), {1, 2, 3})) ASSERT_LT(++k, 100) << garbage;
    EXPECT_GE(k, 40) << garbage;  // at least a second of arrival time
    EXPECT_FALSE(time.stamped()) << garbage;
  }
  HoldTime time;
  PointHold hold(1.0, 1.0);
  EXPECT_FALSE(hold.add(time.at(1.7e9, 0.0), {1, 2, 3}));
  EXPECT_FALSE(hold.add(time.at(1.7e9 + 0.025, 0.025), {1, 2, 3}));
  EXPECT_FALSE(hold.add(time.at(1.7e9 + 100, 0.05), {1, 2, 3})) << "a stamp 100 s on is not a clock";
  EXPECT_FALSE(time.stamped());
  EXPECT_FALSE(hold.add(time.at(1.7e9 + 100.025, 0.075), {1, 2, 3}));
}

TEST(PointHold, TakesARestAndRestartsWhenTheTipMoves) {
  PointHold hold(1.0, 0.5);
  double t = 0;
  // Moving: never complete.
  for (int k = 0; k < 50; ++k, t += 0.025) EXPECT_FALSE(hold.add(t, {double(k), 0, 0}));
  // At rest with jitter: complete after 0.5 s, the mean of the rest.
  bool done = false;
  for (int k = 0; k < 40 && !done; ++k, t += 0.025) done = hold.add(t, {100.0 + (k % 2 ? 0.2 : -0.2), 5, 5});
  EXPECT_TRUE(done);
  EXPECT_NEAR(hold.mean()[0], 100.0, 0.05);
  EXPECT_GE(hold.held_s(), 0.5);
}

TEST(FingerPlacement, TriangleForThePenOwnPositionsAndVentsForTrackers) {
  FingerLayout layout;
  TouchSample pen{0, 50, 60, 2.0, true};
  const PlacedFingers a = place_fingers(layout, pen, 0.05);
  EXPECT_DOUBLE_EQ(a.centres[1].x_mm, 66);
  EXPECT_DOUBLE_EQ(a.centres[2].y_mm, 76);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(a.pressed[i]);
    EXPECT_DOUBLE_EQ(a.force_N[i], 2.0);
  }
  TouchSample tracked = pen;
  tracked.own_positions = tracked.per_finger_force = true;
  tracked.fingers[0] = {10, 20, -4, 2.0, FingerVent::none};
  tracked.fingers[1] = {30, 40, -4, 0.01, FingerVent::none};  // below the contact force
  tracked.fingers[2] = {50, 60, -4, 2.0, FingerVent::tool_stale};
  const PlacedFingers b = place_fingers(layout, tracked, 0.05);
  EXPECT_DOUBLE_EQ(b.centres[0].x_mm, 10);
  EXPECT_DOUBLE_EQ(b.centres[2].y_mm, 60);
  EXPECT_TRUE(b.pressed[0]);
  EXPECT_FALSE(b.pressed[1]);
  EXPECT_FALSE(b.pressed[2]);
  EXPECT_TRUE(finger_forces_valid(tracked));
  tracked.fingers[1].force_N = std::nan("");
  EXPECT_FALSE(finger_forces_valid(tracked));
  tracked.fingers[0].x_mm = std::nan("");
  EXPECT_FALSE(finger_positions_finite(tracked));
  tracked.fingers[0].vent = FingerVent::tool_stale;  // a vented finger's position is not used
  EXPECT_TRUE(finger_positions_finite(tracked));
}

TEST(LoadCell, CalibrationAndTheSimulatedSpring) {
  const LoadCellCalibration cal{0.1, 2.0};
  EXPECT_DOUBLE_EQ(cal.force_N(0.1), 0.0);
  EXPECT_DOUBLE_EQ(cal.force_N(1.1), 2.0);
  SimulatedLoadCellParams p;
  p.noise_sd_V = 0;
  SimulatedLoadCell cell(p);
  EXPECT_DOUBLE_EQ(cell.force_N(-3), 0.0);  // above the surface
  EXPECT_DOUBLE_EQ(cell.force_N(4), 2.0);   // 4 mm deep on 0.5 N/mm
  EXPECT_DOUBLE_EQ(cal.force_N(cell.volts(4)), 2.0);
  EXPECT_DOUBLE_EQ(cal.force_N(cell.volts(0, 5.0)), 5.0);  // a 5 N weight
  p.max_V = 1.0;
  SimulatedLoadCell clipped(p);
  EXPECT_DOUBLE_EQ(clipped.volts(100), 1.0);  // the input's range
}
