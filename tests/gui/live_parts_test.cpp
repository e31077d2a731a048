// The window's parts that need no window: the strip chart's min/max-per-column reduction,
// the tiered indentation grid, the window pen's sample ages, and the telemetry feed.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "gui/indentation.hpp"
#include "gui/telemetry_feed.hpp"
#include "gui/trace_history.hpp"
#include "gui/window_pen_input.hpp"
#include "runtime/monotonic_clock.hpp"

using namespace palprig;
using namespace palprig::gui;

namespace {

TraceSample sample_at(double t, float setpoint_f1) {
  TraceSample s;
  s.t_s = t;
  s.kPa[int(TraceKind::setpoint)][0] = setpoint_f1;
  return s;
}

}  // namespace

TEST(TraceHistory, ColumnsKeepEveryPeakOfAWindow) {
  TraceHistory h(20000);
  // 10 s at 1 kHz: a flat 5 kPa with one 1 ms spike to 40 kPa at t = 7.3205 s and a dip to 0 at 2.5 s.
  for (int k = 0; k < 10000; ++k) {
    const double t = k * 1e-3;
    float v = 5.0f;
    if (k == 7320) v = 40.0f;
    if (k == 2500) v = 0.0f;
    h.push(sample_at(t, v));
  }
  std::vector<ColumnExtent> cols;
  h.columns_min_max(TraceKind::setpoint, 0, 0.0, 10.0, 400, cols);
  ASSERT_EQ(cols.size(), 400u);
  int spikes = 0, dips = 0;
  for (std::size_t c = 0; c < cols.size(); ++c) {
    ASSERT_FALSE(cols[c].empty) << c;  // 25 samples per column
    if (cols[c].max == 40.0f) {
      ++spikes;
      EXPECT_EQ(c, 292u);
    }  // 7.32 s / 25 ms
    if (cols[c].min == 0.0f) {
      ++dips;
      EXPECT_EQ(c, 100u);
    }
  }
  EXPECT_EQ(spikes, 1);
  EXPECT_EQ(dips, 1);
  // A window reaching past the data leaves its columns empty.
  h.columns_min_max(TraceKind::setpoint, 0, 8.0, 12.0, 4, cols);
  EXPECT_FALSE(cols[0].empty);
  EXPECT_FALSE(cols[1].empty);
  EXPECT_TRUE(cols[2].empty);
  EXPECT_TRUE(cols[3].empty);
}

TEST(TraceHistory, RingKeepsTheNewestAndClears) {
  TraceHistory h(100);
  for (int k = 0; k < 250; ++k) h.push(sample_at(k, float(k)));
  ASSERT_EQ(h.size(), 100u);
  EXPECT_EQ(h.at(0).t_s, 150.0);
  EXPECT_EQ(h.newest().t_s, 249.0);
  std::vector<ColumnExtent> cols;
  h.columns_min_max(TraceKind::setpoint, 0, 150.0, 250.0, 10, cols);
  EXPECT_EQ(cols[0].min, 150.0f);
  EXPECT_EQ(cols[9].max, 249.0f);
  h.clear();
  EXPECT_EQ(h.size(), 0u);
}

TEST(TraceHistory, NonFiniteMonitorIsAGapNotAValue) {
  TraceHistory h(10);
  TraceSample s = sample_at(0.0, 1.0f);
  s.kPa[int(TraceKind::monitor)][0] = std::nanf("");
  h.push(s);
  std::vector<ColumnExtent> cols;
  h.columns_min_max(TraceKind::monitor, 0, 0.0, 1.0, 2, cols);
  EXPECT_TRUE(cols[0].empty);
}

TEST(Indentation, DepthFromForceAndStiffness) {
  IndentationModel m;
  EXPECT_NEAR(m.depth_mm(2.0, 0.0), 7.0, 1e-12);                // paper 002: 2 N, 7 mm in soft silicone
  EXPECT_NEAR(m.depth_mm(2.0, 1.0), 7.0 * 14.7 / 21.9, 1e-12);  // a tumor gives less
  EXPECT_NEAR(m.depth_mm(1.0, 0.0), 3.5, 1e-12);
  EXPECT_EQ(m.depth_mm(0.0, 0.5), 0.0);
  EXPECT_EQ(m.depth_mm(std::nan(""), 0.5), 0.0);
  EXPECT_EQ(m.depth_mm(100.0, 0.0), m.max_depth_mm);
}

TEST(Indentation, TieredGridFallsTierByTierToZeroAtTheBorder) {
  const int n = 4;
  const std::size_t side = 2 * n + 1;
  const auto g = tiered_grid(50, 20, 6.0, n, 2.0);
  ASSERT_EQ(g.size(), side * side);
  const auto& centre = g[n * side + n];
  EXPECT_EQ(centre.tier, 0);
  EXPECT_EQ(centre.depth_mm, 6.0);
  EXPECT_EQ(centre.x_mm, 50.0);
  EXPECT_EQ(centre.y_mm, 20.0);
  for (const GridVertex& v : g) {
    EXPECT_EQ(v.tier, std::lround(std::max(std::abs(v.x_mm - 50), std::abs(v.y_mm - 20)) / 2.0));
    EXPECT_NEAR(v.depth_mm, 6.0 * (n - v.tier) / n, 1e-12);
    if (v.tier == n) {
      EXPECT_EQ(v.depth_mm, 0.0);  // joins the undeformed surface
    }
  }
}

TEST(Indentation, ADraggedContactCarriesTheGridTierByTier) {
  // The tissue under the finger at (50, 20) was carried 3 mm along x and 1 mm along y (tissue
  // dragging): the grid rests around where that tissue was, its centre vertex is drawn under the
  // finger and its border, carried by nothing, stays where the skin was.
  const int n = 4;
  const std::size_t side = 2 * n + 1;
  const auto g = tiered_grid(50, 20, 6.0, n, 2.0, 3.0, 1.0);
  const auto& centre = g[n * side + n];
  EXPECT_EQ(centre.tier, 0);
  EXPECT_DOUBLE_EQ(centre.x_mm + centre.dx_mm, 50.0);
  EXPECT_DOUBLE_EQ(centre.y_mm + centre.dy_mm, 20.0);
  EXPECT_DOUBLE_EQ(centre.x_mm, 47.0);
  for (const GridVertex& v : g) {
    EXPECT_NEAR(v.dx_mm, 3.0 * (n - v.tier) / n, 1e-12);
    EXPECT_NEAR(v.dy_mm, 1.0 * (n - v.tier) / n, 1e-12);
    if (v.tier == n) {
      EXPECT_EQ(v.dx_mm, 0.0);
      EXPECT_EQ(v.dy_mm, 0.0);
    }
  }
  // Not dragged: as before (rest positions centred on the contact, nothing carried).
  for (const GridVertex& v : tiered_grid(50, 20, 6.0, n, 2.0)) EXPECT_EQ(v.dx_mm, 0.0);
}

TEST(WindowPenInput, PressedPenAgesWhenTheGuiStopsPublishing) {
  WindowPenInput pen;
  pen.publish(10, 20, 2.0, true);
  const TouchSample first = pen.latest(5.0);  // fixes the epoch: loop time 5 s is now
  EXPECT_EQ(first.x_mm, 10);
  EXPECT_TRUE(first.in_contact);
  EXPECT_NEAR(first.t_s, 5.0, 0.01);
  // No heartbeat for 120 ms: the sample is that old on the loop's clock.
  std::this_thread::sleep_for(std::chrono::milliseconds(120));
  const double now = 5.0 + 0.120;
  const TouchSample later = pen.latest(now);
  EXPECT_GE(now - later.t_s, 0.115);
  // A heartbeat makes it fresh again.
  pen.publish(10, 20, 2.0, true);
  EXPECT_LT(now + 0.001 - pen.latest(now + 0.001).t_s, 0.01);
}

TEST(WindowPenInput, LiftedPenIsNeverStaleButBadReadingsPassThrough) {
  WindowPenInput pen;
  pen.publish(10, 20, 0.0, false);
  pen.latest(0.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(pen.latest(0.05).t_s, 0.05);  // lifted: 0 kPa anyway, its age is not held against it
  pen.publish(10, 20, std::nan(""), false);
  const TouchSample bad = pen.latest(0.06);
  EXPECT_TRUE(std::isnan(bad.force_N));  // the tick's own check faults on it
  EXPECT_LT(bad.t_s, 0.06 + 1e-9);
}

TEST(TelemetryFeed, CarriesEveryRecordAndCountsOverruns) {
  TelemetryFeed feed;
  for (int k = 0; k < 3000; ++k) {
    TelemetryRecord r;
    r.tick = std::uint64_t(k);
    r.t_s = k * 1e-3;
    r.setpoint_kPa[1] = float(k % 7);
    r.wake_latency_us = k % 50 == 0 ? 500.0f : 10.0f;
    if (k % 1000 == 999) r.flags |= kOverrun;
    feed.on_tick(r);
  }
  std::vector<TraceSample> got;
  FeedStatus st;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (got.size() < 3000 && std::chrono::steady_clock::now() < end) {
    st = feed.take(got);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  st = feed.take(got);
  ASSERT_EQ(got.size(), 3000u);
  for (int k = 0; k < 3000; ++k) ASSERT_EQ(got[std::size_t(k)].kPa[int(TraceKind::setpoint)][1], float(k % 7));
  EXPECT_EQ(st.ticks, 3000u);
  EXPECT_EQ(st.overruns, 3u);
  EXPECT_EQ(st.latest.tick, 2999u);
  EXPECT_NEAR(st.loop_rate_hz, 1000.0, 1.0);
  EXPECT_EQ(st.wake_p50_us, 10.0);
  EXPECT_EQ(st.wake_p99_us, 500.0);  // 1 in 50 of the last 1000 took 500 us
  EXPECT_EQ(st.dropped, 0u);
  EXPECT_EQ(feed.last_t_s(), 2.999);
}
