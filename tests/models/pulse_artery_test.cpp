// Arteries: pulse sources along the path, 000's distance law, 003's activation hysteresis and
// force window, several fingers and several arteries, rate requests, the localisation score.
#include <cmath>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "models/artery.hpp"
#include "models/pulse_localisation.hpp"

using namespace palprig;

namespace {

ArterySpec straight(const char* name = "a", double depth = 5, double radius = 2) {
  ArterySpec s;
  s.name = name;
  s.path = {{0, 50}, {100, 50}};
  s.depth_mm = depth;
  s.radius_mm = radius;
  s.amplitude_kPa = 10;
  s.rate_bpm = 60;
  s.force_window = {1.0, 3.0, 1.0};
  return s;
}

// Felt pulse at the top of a beat (phase 0.1 of a rectangular D = 0.2 wave).
double peak(const PulseField& f, Point2_mm at, double force_N, PulseActivation& act,
            const PulseSettings& settings = {}) {
  PulseClocks clocks;
  f.update_clocks(clocks, 0, settings);
  return f.felt({at, force_N, true}, clocks, act, 0.1, {}, nullptr, settings).now_kPa;
}

}  // namespace

TEST(Artery, SourcesSpacedAtMostOneRangeApartAlongThePath) {
  ArterySpec s = straight();
  s.path = {{0, 0}, {30, 40}, {30, 100}};  // 50 + 60 mm
  s.range_mm = 12;
  const Artery a(s, 8);
  EXPECT_NEAR(a.length_mm(), 110, 1e-9);
  const auto& src = a.sources();
  ASSERT_EQ(src.size(), 11u);  // ceil(110 / 12) + 1
  EXPECT_NEAR(src.front().x_mm, 0, 1e-9);
  EXPECT_NEAR(src.back().y_mm, 100, 1e-9);
  for (std::size_t i = 1; i < src.size(); ++i) {
    const double gap = std::hypot(src[i].x_mm - src[i - 1].x_mm, src[i].y_mm - src[i - 1].y_mm);
    EXPECT_LE(gap, 12 + 1e-9);
    EXPECT_EQ(src[i].z_mm, 5);  // at the centreline's depth
  }
}

TEST(Artery, DistanceLawOfPaper000) {
  // A path shorter than the range: two sources, at x = 0 and x = 10. Over the first source at
  // lateral offset L the second is out of range when far enough, and the factor is
  // k (r - d) with d = sqrt(L^2 + depth^2) and k = 1 / (r - depth).
  ArterySpec s = straight();
  s.path = {{0, 50}, {10, 50}};
  s.range_mm = 9;
  const Artery a(s, 8);
  ASSERT_EQ(a.sources().size(), 3u);  // ceil(10/9) + 1: spacing 5
  // Straight over the middle source: the neighbours are 5 mm away along the path.
  const double d_mid = 5.0, d_side = std::hypot(5.0, 5.0);
  const double expected = std::min(((9 - d_mid) + 2 * (9 - d_side)) / (9 - 5.0), 1.0);
  EXPECT_NEAR(a.distance_factor({5, 50}), expected, 1e-12);
  // Far out: only the range limit counts.
  EXPECT_EQ(a.distance_factor({5, 60}), 0.0);
  // One source alone: a point beyond the path's end.
  const double L = 3;
  const double d = std::hypot(L, 5.0);
  const double d2 = std::hypot(L + 5.0, 5.0);  // the middle source, 5 mm further along
  EXPECT_NEAR(a.distance_factor({-L, 50}), (std::max(9 - d, 0.0) + std::max(9 - d2, 0.0)) / 4.0, 1e-12);
  // Nearer is stronger.
  EXPECT_GT(a.distance_factor({5, 55}), a.distance_factor({5, 56}));
  EXPECT_GT(a.distance_factor({5, 56}), 0.0);
}

TEST(Artery, ActivationHysteresisOfPaper003) {
  // R = 2, h = 3 (depth 5), delta 0.5, epsilon 0.57: on at d <= 5.5, off at d >= 6.07, with d the
  // distance from the finger on the skin to the centreline: lateral 2.29 and 3.44 mm.
  ArterySpec s = straight("a", 5, 2);
  s.activation_margin_mm = 0.5;
  s.release_margin_mm = 0.57;
  s.range_mm = 8;
  const PulseField f({s}, 8);
  const double on_lateral = std::sqrt(5.5 * 5.5 - 25), off_lateral = std::sqrt(6.07 * 6.07 - 25);
  PulseActivation act;
  EXPECT_EQ(peak(f, {50, 50 + 3.0}, 2, act), 0.0);  // approaching from outside: not yet
  EXPECT_EQ(peak(f, {50, 50 + on_lateral + 0.01}, 2, act), 0.0);
  EXPECT_GT(peak(f, {50, 50 + on_lateral - 0.01}, 2, act), 0.0);  // on
  EXPECT_GT(peak(f, {50, 50 + 3.0}, 2, act), 0.0);                // still on between the thresholds
  EXPECT_GT(peak(f, {50, 50 + off_lateral - 0.01}, 2, act), 0.0);
  EXPECT_EQ(peak(f, {50, 50 + off_lateral + 0.01}, 2, act), 0.0);  // off
  EXPECT_EQ(peak(f, {50, 50 + 3.0}, 2, act), 0.0);                 // and stays off until d <= 5.5
  EXPECT_FALSE(act.on[0]);
  EXPECT_GT(peak(f, {50, 50}, 2, act), 0.0);
  PulseClocks clocks;
  f.update_clocks(clocks, 0);
  f.felt({{50, 50}, 2, false}, clocks, act, 0.1, {});  // pen lifted: released
  EXPECT_FALSE(act.on[0]);
}

TEST(Artery, DefaultActivationSwitchesOnWhenThePadIsOverTheArtery) {
  const Artery a(straight("a", 6, 2), 8);  // fingertip pad radius 8 mm
  EXPECT_NEAR(std::sqrt(a.on_distance_mm() * a.on_distance_mm() - 36), 8.0, 1e-9);
  EXPECT_NEAR(a.off_distance_mm() - a.on_distance_mm(), 0.57, 1e-12);
  EXPECT_NEAR(a.range_mm(), a.off_distance_mm(), 1e-12);  // felt wherever it is on
}

TEST(Artery, ForceWindowOfPaper003) {
  ArterySpec s = straight();
  s.force_window = {1.0, 3.0, 0.8};
  const PulseField f({s}, 8);
  PulseActivation act;
  const Point2_mm over{50, 50};
  EXPECT_EQ(peak(f, over, 0.9, act), 0.0);  // too light
  EXPECT_EQ(peak(f, over, 3.1, act), 0.0);  // occluded
  const double full = 10 * f.artery(0).distance_factor(over);
  for (double F : {1.0, 1.5, 2.0, 2.5, 3.0})
    EXPECT_NEAR(peak(f, over, F, act), full * (F - 1.0) / 2.0 * 0.8, 1e-12) << F;
  EXPECT_DOUBLE_EQ(s.force_window.factor(2.0), 0.4);
}

TEST(Artery, EveryFingerOverAnArteryFeelsItAndAmplitudesDifferPerArtery) {
  ArterySpec radial = straight("radial");
  ArterySpec femoral = straight("femoral", 12, 4);
  femoral.path = {{0, 100}, {100, 100}};
  femoral.amplitude_kPa = 4;
  const PulseField f({radial, femoral}, 8);
  std::array<PulseActivation, 3> act{};
  // Fingers at x = 20 and 36 on the radial artery, one 16 mm across it.
  const double a0 = peak(f, {20, 50}, 2, act[0]), a1 = peak(f, {36, 50}, 2, act[1]), a2 = peak(f, {20, 66}, 2, act[2]);
  EXPECT_GT(a0, 0);
  EXPECT_NEAR(a0, a1, 1e-9);
  EXPECT_EQ(a2, 0);
  std::array<PulseActivation, 2> act2{};
  const double r = peak(f, {50, 50}, 2, act2[0]), fem = peak(f, {50, 100}, 2, act2[1]);
  // Each its own amplitude, scaled by how near the finger is to that artery's sources.
  EXPECT_NEAR(f.artery(0).distance_factor({50, 50}), 1.0, 1e-12);
  EXPECT_NEAR(r / fem, 10.0 / (4.0 * f.artery(1).distance_factor({50, 100})), 1e-9);
  EXPECT_GT(fem, 0);
  EXPECT_EQ(f.find("femoral"), 1);
  EXPECT_EQ(f.find("carotid"), -1);
}

TEST(Artery, AnOperatorsRateAppliesFromTheTickItArrivesWithThePhaseKept) {
  const PulseField f({straight()}, 8);
  PulseClocks clocks;
  f.update_clocks(clocks, 0.0);
  EXPECT_EQ(clocks.clock[0].bpm, 60);
  PulseSettings settings;
  settings.rate_bpm[0] = 120;
  const double before = clocks.clock[0].phase(5.3);
  f.update_clocks(clocks, 5.3, settings);
  EXPECT_EQ(clocks.clock[0].bpm, 120);
  EXPECT_NEAR(clocks.clock[0].phase(5.3), before, 1e-12);
  EXPECT_NEAR(clocks.clock[0].phase(6.3), before + 2, 1e-12);
  EXPECT_EQ(f.rate_bpm(0, settings), 120);
  EXPECT_EQ(f.rate_bpm(0, {}), 60) << "NaN: the scene's own rate";
  EXPECT_FALSE(PulseField::valid_rate_bpm(19));
  EXPECT_FALSE(PulseField::valid_rate_bpm(251));
  EXPECT_FALSE(PulseField::valid_rate_bpm(std::nan("")));
  settings.rate_bpm[0] = 251;  // out of range: the scene's rate stands
  EXPECT_EQ(f.rate_bpm(0, settings), 60);
}

TEST(Artery, BroadPhaseRegionHoldsEveryPlaceThePulseIsFelt) {
  const Artery a(straight(), 8);
  for (double y = 20; y <= 80; y += 0.5)
    if (a.distance_factor({50, y}) > 0) {
      EXPECT_TRUE(a.in_region({50, y})) << y;
    }
  EXPECT_FALSE(a.in_region({50, 0}));
  EXPECT_FALSE(a.in_region({150, 50}));
}

TEST(Artery, ImpossibleArteriesAreRefused) {
  ArterySpec s = straight();
  s.depth_mm = 1;  // shallower than its radius
  EXPECT_THROW(Artery(s, 8), palprig::BadInput);
  s = straight();
  s.range_mm = 4;  // never reaches the skin from 5 mm down
  EXPECT_THROW(Artery(s, 8), palprig::BadInput);
  s = straight();
  s.rate_bpm = 300;
  EXPECT_THROW(Artery(s, 8), palprig::BadInput);
  s = straight();
  s.path = {{0, 0}};
  EXPECT_THROW(Artery(s, 8), palprig::BadInput);
  s = straight();
  s.force_window = {3, 1, 1};
  EXPECT_THROW(Artery(s, 8), palprig::BadInput);
  EXPECT_THROW(PulseField({straight("x"), straight("x")}, 8), palprig::BadInput);
  std::vector<ArterySpec> many(kMaxArteries + 1, straight());
  for (std::size_t i = 0; i < many.size(); ++i) many[i].name = "a" + std::to_string(i);
  EXPECT_THROW(PulseField(many, 8), palprig::BadInput);
}

TEST(PulseLocalisation, MarkScoredByDistanceToTheCentreline) {
  ArterySpec bend = straight("brachial");
  bend.path = {{0, 50}, {50, 50}, {50, 100}};
  ArterySpec other = straight("radial");
  other.path = {{100, 0}, {100, 100}};
  const PulseField f({bend, other}, 8);
  PulseMarkScore s = score_pulse_mark(f, {25, 53}, 4.0);
  EXPECT_EQ(s.artery, 0);
  EXPECT_NEAR(s.distance_mm, 3.0, 1e-12);
  EXPECT_TRUE(s.hit);
  s = score_pulse_mark(f, {56, 75}, 4.0);  // beside the second leg
  EXPECT_NEAR(s.distance_mm, 6.0, 1e-12);
  EXPECT_FALSE(s.hit);
  s = score_pulse_mark(f, {90, 75}, 4.0);  // nearest is the radial
  EXPECT_EQ(s.artery, 1);
  EXPECT_NEAR(s.distance_mm, 10.0, 1e-12);
  s = score_pulse_mark(f, {90, 75}, 4.0, "brachial");  // scored against the artery asked for
  EXPECT_EQ(s.artery, 0);
  EXPECT_NEAR(s.distance_mm, 40.0, 1e-12);
  EXPECT_EQ(score_pulse_mark(f, {0, 0}, 4.0, "carotid").artery, -1);
  EXPECT_FALSE(score_pulse_mark(f, {std::nan(""), 0}, 4.0).hit);
  const PulseField none;
  EXPECT_FALSE(score_pulse_mark(none, {0, 0}, 4.0).hit);
}

TEST(Artery, AnOperatorsAmplitudeScalesThePulse) {
  const PulseField f({straight()}, 8);
  PulseActivation act{};
  const double full = peak(f, {50, 50}, 2, act);
  EXPECT_GT(full, 0);
  EXPECT_EQ(f.amplitude_kPa(0, {}), 10);
  PulseSettings settings;
  settings.amplitude_kPa[0] = 2.5;
  PulseActivation act2{};
  EXPECT_NEAR(peak(f, {50, 50}, 2, act2, settings), full * 0.25, 1e-12);
  EXPECT_FALSE(PulseField::valid_amplitude_kPa(-1));
  EXPECT_FALSE(PulseField::valid_amplitude_kPa(51));
  EXPECT_FALSE(PulseField::valid_amplitude_kPa(std::nan("")));
  EXPECT_EQ(f.amplitude_kPa(1, settings), 0) << "no such artery";
}
