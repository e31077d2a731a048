// Tissue dragging with stick and slip (paper 000, section 3.2, eq. 3): a finger pressing above
// f_stick carries the tissue with it up to d_lat_max, then the skin slips and relaxes; pressing
// below f_stick releases it. And the pen predictor the lag compensation samples the scene with.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "models/pen_predictor.hpp"
#include "models/tissue_drag.hpp"
#include "models/tissue_scene.hpp"

using namespace palprig;

namespace {

const DragSetting kSkin{1.0, 6.0, 0.05};  // sticks from 1 N, slips past 6 mm, relaxes in 50 ms

}  // namespace

TEST(TissueDrag, StickingCarriesTheTissueWithTheFinger) {
  FingerDrag d;
  step_drag(d, kSkin, {20, 30}, 2.0, true, 0.0);
  EXPECT_EQ(d.phase, DragPhase::sticking);
  // The finger slides 4 mm in 0.1 s: the tissue it stuck to comes along, so it still feels the
  // point it first pressed.
  for (int k = 1; k <= 100; ++k) step_drag(d, kSkin, {20 + 0.04 * k, 30}, 2.0, true, 0.001);
  EXPECT_EQ(d.phase, DragPhase::sticking);
  EXPECT_NEAR(d.offset.x_mm, 4.0, 1e-9);
  EXPECT_NEAR(d.offset.y_mm, 0.0, 1e-12);
  const Point2_mm felt = d.felt_point({24, 30});
  EXPECT_NEAR(felt.x_mm, 20.0, 1e-9);
  EXPECT_NEAR(felt.y_mm, 30.0, 1e-9);
}

TEST(TissueDrag, SlipsAtDLatMaxAndRelaxesThenSticksAgain) {
  FingerDrag d;
  step_drag(d, kSkin, {0, 0}, 2.0, true, 0.0);
  int k = 0;
  double x = 0;
  // Along a diagonal: the stretch is Euclidean (eq. 2), so the slip comes at 6 mm of path.
  while (d.phase == DragPhase::sticking && k < 1000) {
    ++k;
    x = 0.01 * k;
    step_drag(d, kSkin, {x, x}, 2.0, true, 0.001);
  }
  ASSERT_EQ(d.phase, DragPhase::slipping);
  EXPECT_NEAR(std::hypot(x, x), kSkin.d_lat_max_mm, 0.02);
  // Released: the skin relaxes toward rest with its time constant (one step of 1 ms already).
  const double stretch = std::hypot(d.offset.x_mm, d.offset.y_mm);
  EXPECT_LT(stretch, kSkin.d_lat_max_mm);
  EXPECT_NEAR(stretch, std::hypot(x, x) * std::exp(-0.001 / kSkin.relax_s), 1e-6);
  // Still pressing: it slides until the skin has relaxed below a tenth of d_lat_max, then sticks.
  int slipping_ticks = 0;
  while (d.phase == DragPhase::slipping && slipping_ticks < 10000) {
    ++slipping_ticks;
    x += 0.01;
    step_drag(d, kSkin, {x, x}, 2.0, true, 0.001);
  }
  EXPECT_EQ(d.phase, DragPhase::sticking);
  EXPECT_NEAR(slipping_ticks * 0.001, kSkin.relax_s * std::log(1.0 / kDragRestickFraction), 0.003);
  // From there it carries the tissue again, from where it is.
  const Point2_mm before = d.offset;
  step_drag(d, kSkin, {x + 1, x}, 2.0, true, 0.001);
  EXPECT_NEAR(d.offset.x_mm - before.x_mm, 1.0, 1e-9);
}

TEST(TissueDrag, PressingBelowFStickReleases) {
  FingerDrag d;
  step_drag(d, kSkin, {0, 0}, 2.0, true, 0.0);
  for (int k = 1; k <= 30; ++k) step_drag(d, kSkin, {0.1 * k, 0}, 2.0, true, 0.001);
  ASSERT_EQ(d.phase, DragPhase::sticking);
  ASSERT_NEAR(d.offset.x_mm, 3.0, 1e-9);
  // The press drops below f_stick: eq. 3's first case, no lateral force; the skin relaxes.
  step_drag(d, kSkin, {3.1, 0}, 0.9, true, 0.001);
  EXPECT_EQ(d.phase, DragPhase::free);
  EXPECT_LT(d.offset.x_mm, 3.0);
  for (int k = 0; k < 1000; ++k) step_drag(d, kSkin, {3.1, 0}, 0.9, true, 0.001);
  EXPECT_EQ(d.offset.x_mm, 0.0);
  // A lifted finger, and a layer that does not drag, release too.
  FingerDrag lifted;
  step_drag(lifted, kSkin, {0, 0}, 2.0, true, 0.0);
  step_drag(lifted, kSkin, {1, 0}, 2.0, false, 0.001);
  EXPECT_EQ(lifted.phase, DragPhase::free);
  FingerDrag held;
  step_drag(held, DragSetting{1.0, 0.0, 0.05}, {0, 0}, 2.0, true, 0.0);
  step_drag(held, DragSetting{1.0, 0.0, 0.05}, {1, 0}, 2.0, true, 0.001);
  EXPECT_EQ(held.phase, DragPhase::free);
  EXPECT_EQ(held.offset.x_mm, 0.0);
}

TEST(TissueDrag, ALayerWithoutItsOwnDragTakesTheOneAbove) {
  TissueDefinition t;
  TissueLayer skin{"skin", 2, 40};
  skin.drag = kSkin;
  skin.drag_given = true;
  TissueLayer fat{"fat", 3, 5};
  TissueLayer fascia{"fascia", 1, 60};
  fascia.drag = DragSetting{1.0, 0.0, 0.0};  // held: pressed into it, nothing slides
  fascia.drag_given = true;
  t.layers = {skin, fat, fascia, TissueLayer{"muscle", 30, 15}};
  t.felt = {5, 300};
  const FunctionScene scene(t, {});
  EXPECT_EQ(scene.drag(-1).d_lat_max_mm, kSkin.d_lat_max_mm);  // not yet pressed: the skin
  EXPECT_EQ(scene.drag(0).d_lat_max_mm, kSkin.d_lat_max_mm);
  EXPECT_EQ(scene.drag(1).d_lat_max_mm, kSkin.d_lat_max_mm);  // fat: the skin's
  EXPECT_FALSE(scene.drag(2).drags());                        // fascia: its own (held)
  EXPECT_FALSE(scene.drag(3).drags());                        // muscle: the fascia's
  EXPECT_FALSE(scene.drag(99).drags());
  // A map scene has no layers: nothing drags.
  const MapScene map(StiffnessMap(2, 2, 10, 10, std::vector<float>(4, 0.f)), MapSampling::nearest);
  EXPECT_FALSE(map.drag(0).drags());
}

TEST(PenPredictor, ExtrapolatesPositionAndForceFromPastSamplesOnly) {
  PenPredictor p;
  const PenPrediction how;
  // 40 mm/s along x, force rising 2 N/s; a 100 Hz tablet read by a 1 kHz loop (held readings).
  for (int k = 0; k <= 50; ++k) {
    const double t_sample = std::floor(k / 10.0) * 0.01;
    p.observe({t_sample, 10 + 40 * t_sample, 5, 1 + 2 * t_sample, true});
  }
  EXPECT_EQ(p.samples(), 6u);  // held readings are not new samples
  const TouchSample ahead = p.predict(0.05 + 0.02, how);
  EXPECT_NEAR(ahead.x_mm, 10 + 40 * 0.07, 1e-9);
  EXPECT_NEAR(ahead.y_mm, 5.0, 1e-9);
  EXPECT_NEAR(ahead.force_N, 1 + 2 * 0.07, 1e-9);
  EXPECT_TRUE(ahead.in_contact);
  // The horizon is capped, and so is the speed (a jump is not flung across the pad).
  EXPECT_NEAR(p.predict(10.0, how).x_mm, 10 + 40 * (0.05 + how.max_horizon_s), 1e-9);
  PenPredictor jump;
  jump.observe({0.000, 0, 0, 2, true});
  jump.observe({0.001, 100, 0, 2, true});
  EXPECT_NEAR(jump.predict(0.011, how).x_mm, 100 + how.max_speed_mm_per_s * 0.01, 1e-9);
  // A lift starts over; nothing observed: the pen as it is (lifted).
  p.observe({0.06, 12, 5, 0, false});
  EXPECT_EQ(p.samples(), 0u);
  EXPECT_FALSE(p.predict(0.07, how).in_contact);
}

TEST(PenPredictor, ATrackedPoseIsExtrapolatedFromWhenItWasTakenNotWhenItArrived) {
  // Finger 1 at 40 mm/s along x, tracked at 40 Hz; each pose arrives 0 to 20 ms late (a loaded
  // rig PC, a network hiccup), two of them together in one burst, and the reader wakes every
  // 10 ms between poses (samples that carry the same pose again). Each sample says when its pose
  // was taken (FingerTouch::pose_t_s), so every prediction lands on the path, however late.
  PenPredictor p;
  const PenPrediction how;
  const double lateness_s[] = {0.0, 0.012, 0.020, 0.003, 0.017, 0.008, 0.020, 0.001, 0.015, 0.010};
  auto x_at = [](double t) { return 10 + 40 * t; };
  double newest_pose_t = -1, worst_mm = 0;
  int checked = 0;
  for (int ms = 0; ms <= 260; ++ms) {
    const double t = ms * 0.001;
    // The newest pose that has arrived by t (pose 5 waits for pose 6: one burst).
    int newest = -1;
    for (int k = 0; k * 0.025 <= t; ++k) {
      const double arrives = k == 5 ? 6 * 0.025 + lateness_s[6] : k * 0.025 + lateness_s[k % 10];
      if (arrives <= t + 1e-12) newest = std::max(newest, k);
    }
    if (newest < 0) continue;
    const bool new_pose = newest * 0.025 != newest_pose_t;
    if (!new_pose && ms % 10 != 0) continue;  // the reader wakes on a pose or every 10 ms
    newest_pose_t = newest * 0.025;
    TouchSample s{t, 0, 0, 2, true};
    s.own_positions = s.per_finger_force = true;
    s.fingers[0] = {x_at(newest_pose_t), 5, -1, 2.0, FingerVent::none, newest_pose_t};
    s.fingers[1] = {50, 50, -1, 1.5, FingerVent::none, newest_pose_t};
    s.fingers[2] = {0, 0, 0, 0, FingerVent::no_tool};
    p.observe(s, how);
    if (newest < 1) continue;
    // Where the finger will be one regulator lag (50 ms) and one tick from now.
    const double ahead_s = t + 0.051;
    const PredictedFinger f = p.predict_finger(ahead_s, how, 0);
    worst_mm = std::max(worst_mm, std::abs(f.x_mm - x_at(ahead_s)));
    EXPECT_NEAR(p.predict_finger(ahead_s, how, 1).x_mm, 50, 1e-9);
    EXPECT_NEAR(p.predict(ahead_s, how).fingers[0].x_mm, f.x_mm, 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 20);
  EXPECT_LT(worst_mm, 1e-9);
  // Timed by arrival instead, the same stream puts the finger up to millimetres off.
  PenPredictor by_arrival;
  double arrival_worst_mm = 0;
  for (int k = 0; k < 10; ++k) {
    const double arrived = k * 0.025 + lateness_s[k];
    TouchSample s{arrived, 0, 0, 2, true};
    s.own_positions = s.per_finger_force = true;
    s.fingers[0] = {x_at(k * 0.025), 5, -1, 2.0, FingerVent::none};
    by_arrival.observe(s, how);
    if (k >= 1)
      arrival_worst_mm = std::max(
          arrival_worst_mm, std::abs(by_arrival.predict_finger(arrived + 0.051, how, 0).x_mm - x_at(arrived + 0.051)));
  }
  EXPECT_GT(arrival_worst_mm, 0.5);
}

TEST(PenPredictor, ExtrapolatesEachTrackedFingerFromItsOwnPosesSinceItWasLastSeen) {
  PenPredictor p;
  const PenPrediction how;
  // Three tracked fingertips at 100 Hz: finger 1 moves at 40 mm/s along x with its load cell
  // rising 2 N/s, finger 2 holds still, finger 3's tool is out of view until 0.03 s and comes
  // back 30 mm away (not a jump to extrapolate), then moves at -20 mm/s along y.
  for (int k = 0; k <= 6; ++k) {
    const double t = k * 0.01;
    TouchSample s{t, 0, 0, 2, true};
    s.own_positions = s.per_finger_force = true;
    s.fingers[0] = {10 + 40 * t, 5, -1, 1 + 2 * t, FingerVent::none};
    s.fingers[1] = {50, 50, -1, 1.5, FingerVent::none};
    s.fingers[2] = k < 3 ? FingerTouch{0, 0, 0, 0, FingerVent::tool_stale}
                         : FingerTouch{30, 30 - 20 * (t - 0.03), -1, 1.0, FingerVent::none};
    p.observe(s, how);
  }
  const TouchSample ahead = p.predict(0.07, how);
  EXPECT_NEAR(ahead.fingers[0].x_mm, 10 + 40 * 0.07, 1e-9);
  EXPECT_NEAR(ahead.fingers[0].y_mm, 5, 1e-9);
  EXPECT_NEAR(ahead.fingers[0].force_N, 1 + 2 * 0.07, 1e-9);
  EXPECT_NEAR(ahead.fingers[1].x_mm, 50, 1e-9);
  EXPECT_NEAR(ahead.fingers[1].force_N, 1.5, 1e-9);
  EXPECT_NEAR(ahead.fingers[2].x_mm, 30, 1e-9);
  EXPECT_NEAR(ahead.fingers[2].y_mm, 30 - 20 * 0.04, 1e-9);
  EXPECT_EQ(ahead.fingers[2].vent, FingerVent::none);
  EXPECT_TRUE(ahead.own_positions);
  // What the tick's look ahead reads, one finger at a time, is the same prediction.
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const PredictedFinger f = p.predict_finger(0.07, how, i);
    EXPECT_EQ(f.x_mm, ahead.fingers[i].x_mm);
    EXPECT_EQ(f.y_mm, ahead.fingers[i].y_mm);
    EXPECT_EQ(f.force_N, ahead.fingers[i].force_N);
    EXPECT_EQ(f.pen_x_mm, ahead.x_mm);
    EXPECT_EQ(f.pen_force_N, ahead.force_N);
    EXPECT_TRUE(f.own_position && f.own_force && f.in_contact);
  }
}
