// Lag compensation on a regulator whose exhaust slows near 0 kPa (least pressure to push with):
// the stage leads a fall toward a light target with the lag the output meets there, so the fall
// lands on time without undershoot, where a compensator that knows one exhaust lag only (what a
// fit without the pressure dependence identifies) releases too early and leaves the output
// dragging above the target.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "controller/lag_compensation_stage.hpp"
#include "models/pneumatic_plant.hpp"
#include "tests/support/lag_stage_drive.hpp"

using namespace palprig;
using palprig::testing::drive_stage;
using palprig::testing::StageDrive;

namespace {

// The shipped asymmetric regulator's dynamics (data/rigs/simulated_asymmetric.json) without its
// play or noise: what the stage sees once the hysteresis inverse has done its work.
PlantParams exhaust_slowing_plant() {
  PlantParams p;
  p.hysteresis_kPa = 0;
  p.noise_sd_kPa = 0;
  p.time_constant_s = 0.040;
  p.exhaust_time_constant_s = 0.070;
  p.exhaust_lag_factor_at_0 = 2.5;
  p.exhaust_lag_scale_kPa = 5;
  return p;
}

double exhaust_rms(const StageDrive& d, std::size_t from, std::size_t to) {
  double s = 0;
  for (std::size_t k = from; k < to; ++k) s += std::pow(d.output[k] - d.target[k], 2);
  return std::sqrt(s / double(to - from));
}

}  // namespace

TEST(ExhaustLagCompensation, AFallTowardZeroIsLedWithTheLagItMeetsThere) {
  // 10 kPa, then at 0.3 s a fall to 0.7 kPa (a soft tissue's target after a tumor).
  auto fall = [](double t) { return t < 0.3 ? 10.0 : 0.7; };
  const RegulatorLag exact{0.004, 0.040, 2000, 0.070, 2.5, 5};
  // One exhaust lag: the plant's far from 0 kPa, and the one a fit without the pressure
  // dependence found on this plant's steps (86 ms).
  const RegulatorLag far{0.004, 0.040, 2000, 0.070}, averaged{0.004, 0.040, 2000, 0.086};
  const StageDrive d = drive_stage(fall, true, exact, 10, 1.0, exhaust_slowing_plant());
  const StageDrive f = drive_stage(fall, true, far, 10, 1.0, exhaust_slowing_plant());
  const StageDrive a = drive_stage(fall, true, averaged, 10, 1.0, exhaust_slowing_plant());
  // Within [0, p_max]; the fall is pushed with the command at 0 kPa, then released to the target.
  for (double u : d.command) ASSERT_TRUE(u >= 0 && u <= 60) << u;
  EXPECT_EQ(*std::min_element(d.command.begin() + 300, d.command.end()), 0.0);
  // No undershoot below the light target.
  double under = 0;
  for (std::size_t k = 300; k < d.output.size(); ++k) under = std::max(under, 0.7 - d.output[k]);
  EXPECT_LT(under, 0.05);
  // Landed as soon as the exhaust allows (a free exhaust from 10 to 0.7 kPa, after the dead time
  // and the tick the command takes), and held there.
  const auto landed = static_cast<std::size_t>(300 + 1000 * (exact.exhaust_time_s(10.0, 0.7) + 0.006)) + 5;
  EXPECT_NEAR(landed, 675u, 10u);
  for (std::size_t k = landed; k < d.output.size(); ++k) ASSERT_LT(std::abs(d.output[k] - 0.7), 0.02) << k;
  // The one-lag compensators released too early (about 0.2 s): the output drags above the target.
  EXPECT_GT(f.output[700] - 0.7, 0.3);
  EXPECT_GT(a.output[700] - 0.7, 0.25);
  EXPECT_EQ(f.command[520], 0.7);
  EXPECT_EQ(d.command[520], 0.0);
  // After the one-lag compensators released (0.5 s on): what the right lag saves.
  const double rms_exact = exhaust_rms(d, 500, 1000), rms_far = exhaust_rms(f, 500, 1000),
               rms_averaged = exhaust_rms(a, 500, 1000);
  EXPECT_LT(rms_exact, 0.85 * std::min(rms_far, rms_averaged)) << rms_exact << " " << rms_far << " " << rms_averaged;
}

TEST(ExhaustLagCompensation, TheFallIsAskedForEarlierByTheTimeTheSlowExhaustTakes) {
  // A fall edge known ahead: with the exhaust slowing near 0 kPa, half-way from 10 to 0.7 kPa
  // takes longer than one exhaust lag says, and the anticipation looks that much further ahead
  // (RegulatorLag::exhaust_time_s, the integral of the lag over the way down).
  const RegulatorLag exact{0.004, 0.040, 2000, 0.070, 2.5, 5}, flat{0.004, 0.040, 2000, 0.070};
  const double half_exact = exact.exhaust_time_s(10.0, 0.5 * (10.0 + 0.7));
  const double half_flat = flat.exhaust_time_s(10.0, 0.5 * (10.0 + 0.7));
  EXPECT_NEAR(half_flat, 0.070 * std::log(10.0 / 5.35), 1e-12);
  EXPECT_GT(half_exact, 1.3 * half_flat);
  struct Edge {
    double at_s;
  };
  const Edge edge{0.100};
  auto target = [](const void* context, double ahead_s) {
    return ahead_s >= static_cast<const Edge*>(context)->at_s ? 0.7 : 10.0;
  };
  // Where the anticipation switches to the fall: the lead plus the half-way time before the edge.
  auto switch_lead = [&](const RegulatorLag& m) {
    for (double lead = 0.0; lead < 0.1; lead += 0.0005)
      if (anticipated_target_kPa(m, lead, 10.0, 10, 60, 3, true, target, &edge) < 5) return lead;
    return 1.0;
  };
  EXPECT_NEAR(switch_lead(exact), edge.at_s - half_exact, 0.001);
  EXPECT_NEAR(switch_lead(flat), edge.at_s - half_flat, 0.001);
}

namespace {

// anticipated_target_kPa as it was before it was split into two halves (main 874db3b), kept here
// word for word as the oracle of the split.
double anticipated_before_split(const RegulatorLag& model, double lead_s, double y_kPa, double max_lead_kPa,
                                double p_max_kPa, int samples_ahead, bool anticipate, TargetAhead sample,
                                const void* context) {
  if (samples_ahead < 1) return sample(context, 0.0);
  const double at_lead = sample(context, lead_s);
  const double tau = model.time_constant_s, tau_fall = model.exhaust_tau_s();
  if (!anticipate || samples_ahead < 2 || !(tau > 0) || !(tau_fall > 0) || !std::isfinite(at_lead) ||
      !std::isfinite(y_kPa))
    return at_lead;
  constexpr double kEdge_kPa = 0.25;
  const double y = std::max(y_kPa, 0.0);
  const double window_s = look_ahead_window_s(model, y);
  const double later = sample(context, lead_s + window_s);
  if (!std::isfinite(later)) return at_lead;
  if (later < at_lead - kEdge_kPa && later < y) {
    const double b = std::max(later, 0.0);
    const double half_way_s = y > 0 ? std::clamp(model.exhaust_time_s(y, 0.5 * (y + b)), 0.0, window_s) : 0.0;
    const double there = samples_ahead >= 3 ? sample(context, lead_s + half_way_s) : later;
    return std::isfinite(there) ? std::min(at_lead, there) : at_lead;
  }
  if (later > at_lead + kEdge_kPa && later > y) {
    const double b = later;
    const double hi = std::min(p_max_kPa, b + std::min(max_lead_kPa, b));
    const double mid = 0.5 * (y + b);
    if (!(hi > mid)) return at_lead;
    const double half_way_s = std::clamp(tau * std::log((hi - y) / (hi - mid)), 0.0, window_s);
    const double there = samples_ahead >= 3 ? sample(context, lead_s + half_way_s) : at_lead;
    return std::isfinite(there) ? std::max(at_lead, there) : at_lead;
  }
  return at_lead;
}

}  // namespace

// The two halves the tick calls (begin for every channel, its last samples asked for at once,
// then finish) give what anticipated_target_kPa gives, and say which sample they still need: on
// a fall, the target the exhaust's half-way time ahead of the lead (the closed form of the plant
// above); on a rise, the filling lag's half-way time towards the bound hi; none without an edge.
TEST(ExhaustLagCompensation, TheAnticipationsTwoHalvesAskForTheEdgesSampleAndEqualTheWhole) {
  const RegulatorLag m{0.004, 0.040, 2000, 0.070, 2.5, 5};
  struct Step {
    double at_s, before_kPa, after_kPa;
  };
  auto target = [](const void* context, double ahead_s) {
    const auto& s = *static_cast<const Step*>(context);
    return ahead_s >= s.at_s ? s.after_kPa : s.before_kPa;
  };
  const double lead = 0.005;
  // A fall from 10 to 0.7 kPa 60 ms ahead, with the output at 10 kPa.
  const Step fall{0.060, 10.0, 0.7};
  const EdgeAnticipation f = begin_anticipation(m, lead, 10.0, 10, 60, 3, true, target, &fall);
  ASSERT_TRUE(f.needs_sample());
  EXPECT_EQ(f.edge, EdgeAnticipation::Edge::fall);
  EXPECT_DOUBLE_EQ(f.at_lead_kPa, 10.0);
  EXPECT_NEAR(f.there_ahead_s, lead + m.exhaust_time_s(10.0, 0.5 * (10.0 + 0.7)), 1e-12);
  EXPECT_DOUBLE_EQ(finish_anticipation(f, 0.7), 0.7);    // the fall is asked for
  EXPECT_DOUBLE_EQ(finish_anticipation(f, 12.0), 10.0);  // never more than at the lead
  EXPECT_DOUBLE_EQ(finish_anticipation(f, NAN), 10.0);
  // A rise from 2 to 20 kPa 60 ms ahead, with the output at 2 kPa: pushed at hi = 30 kPa.
  const Step rise{0.060, 2.0, 20.0};
  const EdgeAnticipation r = begin_anticipation(m, lead, 2.0, 10, 60, 3, true, target, &rise);
  ASSERT_TRUE(r.needs_sample());
  EXPECT_EQ(r.edge, EdgeAnticipation::Edge::rise);
  const double window_s = look_ahead_window_s(m, 2.0);
  EXPECT_NEAR(r.there_ahead_s, lead + std::min(0.040 * std::log((30.0 - 2.0) / (30.0 - 11.0)), window_s), 1e-12);
  EXPECT_DOUBLE_EQ(finish_anticipation(r, 20.0), 20.0);
  EXPECT_DOUBLE_EQ(finish_anticipation(r, 1.0), 2.0);
  // No edge in the window: nothing more to sample; two samples only: the edge is judged from
  // the window's sample, which is the fall's value.
  const Step flat{0.060, 5.0, 5.1};
  EXPECT_FALSE(begin_anticipation(m, lead, 5.0, 10, 60, 3, true, target, &flat).needs_sample());
  const EdgeAnticipation two = begin_anticipation(m, lead, 10.0, 10, 60, 2, true, target, &fall);
  EXPECT_FALSE(two.needs_sample());
  EXPECT_DOUBLE_EQ(finish_anticipation(two, two.there_kPa), 0.7);
  // And the halves in a row give what the function gave before the split, along a sweep of
  // leads across both edges (negative and NaN leads too), levels, sample counts and regulators
  // (one lag, two lags, an exhaust slowing near 0 kPa), a target that is NaN past its edge.
  const RegulatorLag one_lag{0.004, 0.050, 2000}, two_lags{0.004, 0.040, 2000, 0.086};
  const Step nan_after{0.060, 5.0, NAN}, negative{0.060, 5.0, -3.0};
  int compared = 0;
  for (const RegulatorLag* model : {&m, &one_lag, &two_lags})
    for (double l = -0.01; l < 0.08; l += 0.0005)
      for (const Step* s : {&fall, &rise, &flat, &nan_after, &negative})
        for (double y : {-1.0, 0.0, 2.0, 10.0, 40.0, double(NAN)})
          for (int samples : {0, 1, 2, 3})
            for (double l_s : {l, double(NAN)}) {
              const EdgeAnticipation a = begin_anticipation(*model, l_s, y, 10, 60, samples, true, target, s);
              const double halves = finish_anticipation(a, a.needs_sample() ? target(s, a.there_ahead_s) : a.there_kPa);
              const double before = anticipated_before_split(*model, l_s, y, 10, 60, samples, true, target, s);
              ASSERT_TRUE(halves == before || (std::isnan(halves) && std::isnan(before)))
                  << "lead " << l_s << " y " << y << " samples " << samples << ": " << halves << " vs " << before;
              const double whole = anticipated_target_kPa(*model, l_s, y, 10, 60, samples, true, target, s);
              EXPECT_TRUE(whole == halves || (std::isnan(whole) && std::isnan(halves)));
              ++compared;
            }
  EXPECT_GT(compared, 10000);
}
