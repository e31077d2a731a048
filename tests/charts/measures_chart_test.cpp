// The charts of paper 002's measures and of a psychometric fit, as data: fig. 15's proportion
// axis zoomed where the proportions are (0-1 hid the differences between 0.9 and 1.0) with its
// ticks ending at 1, every point labelled with its value and n, a gap labelled "n/a" where a
// measure has no denominator (localisation's Sp and ACC) instead of a 0; the psychometric chart
// with an axis in words and units, points at 0 and 1 inside the frame, and a threshold told
// apart from its interval and printed on the chart.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <set>
#include <tuple>

#include "charts/measures_chart.hpp"
#include "charts/psychometric_charts.hpp"

namespace palprig {
namespace {

TEST(MeasuresChart, TheAxisZoomsToTheProportionsAndUndefinedMeasuresAreLabelledGaps) {
  TrialSummary summary;
  summary.by = {SummaryKey::condition};
  SummaryRow discrimination;
  discrimination.key = {"three-finger"};
  discrimination.counts = ConfusionCounts{30, 0, 60, 1};
  discrimination.measures = diagnostic_measures(discrimination.counts);
  SummaryRow localisation;
  localisation.key = {"map"};
  localisation.counts = ConfusionCounts{29, 1, 0, 1};
  localisation.negatives_counted = false;
  localisation.measures = diagnostic_measures(localisation.counts);
  localisation.measures.sp = Measure{};
  localisation.measures.acc = Measure{};
  summary.rows = {discrimination, localisation};

  const charts::Chart chart = charts::measures_chart(summary);
  ASSERT_TRUE(chart.y_min && chart.y_max);
  EXPECT_EQ(*chart.y_max, 1.0);
  // The lowest Wilson bound here is about 0.83: the axis starts at a round 0.8, not at 0.
  EXPECT_GT(*chart.y_min, 0.7);
  EXPECT_LT(*chart.y_min, 0.83);
  EXPECT_NE(chart.title.find("Wilson 95 % intervals"), std::string::npos);
  EXPECT_EQ(chart.y_label, "proportion");
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_EQ(chart.series[0].label, "three-finger");
  EXPECT_EQ(chart.series[0].style, charts::ChartSeries::Style::points);
  EXPECT_EQ(chart.series[0].point_labels[0], "1.000\nn=30");
  const auto& loc = chart.series[1];
  EXPECT_NEAR(loc.y[0], 29.0 / 30.0, 1e-12);  // Se
  EXPECT_TRUE(std::isnan(loc.y[1]));          // Sp: no true negatives exist
  EXPECT_EQ(loc.point_labels[1], "n/a");
  EXPECT_TRUE(std::isnan(loc.y_low[1]) && std::isnan(loc.y_high[3]));
}

TEST(PsychometricChart, AxesInWordsPointsInsideTheFrameAndTheThresholdOnTheChart) {
  stats::PsychometricFit f;
  f.sigmoid = stats::Sigmoid::cumulative_gaussian;
  f.alpha = 0.5;
  f.beta = 0.2;
  f.guess = 0.5;
  f.threshold = 0.5;
  f.threshold_proportion = 0.75;
  f.threshold_ci = {0.43, 0.58};
  f.levels = {{0.1, 10, 5}, {0.5, 20, 15}, {1.0, 30, 30}};
  const charts::Chart c = charts::psychometric_chart("three-finger", f, "level_kPa");
  EXPECT_EQ(c.x_label, "pressure increment over the reference (kPa)");
  EXPECT_EQ(c.y_label, "proportion correct");
  ASSERT_TRUE(c.y_min && c.y_max);
  EXPECT_LT(*c.y_min, 0.0) << "a proportion of 0 sits inside the frame";
  // Every legend entry distinguishable: no two share colour, marker and dash.
  std::set<std::tuple<unsigned, int, int, int>> styles;
  int entries = 0;
  for (const auto& s : c.series) {
    if (s.label.empty()) continue;
    ++entries;
    styles.insert({s.color_rgb, int(s.style), int(s.marker), int(s.dash)});
  }
  EXPECT_EQ(entries, 3);
  EXPECT_EQ(styles.size(), 3u);
  const auto threshold = std::find_if(c.series.begin(), c.series.end(),
                                      [](const charts::ChartSeries& s) { return s.marker == charts::Marker::diamond; });
  ASSERT_NE(threshold, c.series.end());
  EXPECT_EQ(threshold->x_low, std::vector<double>{0.43});  // the interval is the threshold's whisker
  EXPECT_NE(threshold->label.find("0.5 kPa, 95 % bootstrap interval 0.43 to 0.58"), std::string::npos)
      << threshold->label;
  ASSERT_EQ(c.annotations.size(), 1u);
  EXPECT_EQ(c.annotations[0].text, "0.5 kPa\nat 75.0 %");
}

TEST(TrackChart, EachTrackHasItsThresholdLine) {
  std::vector<ThresholdTrialRow> rows;
  for (int i = 0; i < 6; ++i) {
    ThresholdTrialRow r;
    r.session_id = 1;
    r.trial.track_name = "one-finger";
    r.trial.level_kPa = 2.0 - 0.2 * i;
    r.trial.reversal = i == 3;
    rows.push_back(r);
  }
  ThresholdTrackSummary estimate;
  estimate.session = 1;
  estimate.track = "one-finger";
  estimate.estimate.threshold_kPa = 1.25;
  estimate.estimate.target_probability = 0.794;
  const auto charts = charts::track_charts(rows, {estimate});
  ASSERT_EQ(charts.size(), 1u);
  bool line = false;
  for (const auto& s : charts[0].chart.series)
    if (s.dash == charts::Dash::dashed && s.y == std::vector<double>{1.25, 1.25}) {
      line = true;
      EXPECT_EQ(s.label, "one-finger threshold 1.250 kPa (79.4 %)");
    }
  EXPECT_TRUE(line);
}

}  // namespace
}  // namespace palprig
