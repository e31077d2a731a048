// Paper 002 fig. 15's chart: a proportion axis from 0 to 1 (not 1.2, the old room for a legend
// that now sits beside the plot), and a gap where a measure has no denominator (localisation's
// Sp and ACC) instead of a bar at 0.
#include <gtest/gtest.h>

#include <cmath>

#include "charts/measures_chart.hpp"

namespace palprig {
namespace {

TEST(MeasuresChart, ProportionAxisIsZeroToOneAndUndefinedMeasuresAreGaps) {
  TrialSummary summary;
  summary.by = {SummaryKey::condition};
  SummaryRow discrimination;
  discrimination.key = {"three-finger"};
  discrimination.counts = ConfusionCounts{30, 2, 60, 3};
  discrimination.measures = diagnostic_measures(discrimination.counts);
  SummaryRow localisation;
  localisation.key = {"map"};
  localisation.counts = ConfusionCounts{9, 3, 0, 4};
  localisation.negatives_counted = false;
  localisation.measures = diagnostic_measures(localisation.counts);
  localisation.measures.sp = Measure{};
  localisation.measures.acc = Measure{};
  summary.rows = {discrimination, localisation};

  const charts::Chart chart = charts::measures_chart(summary);
  ASSERT_TRUE(chart.y_min && chart.y_max);
  EXPECT_EQ(*chart.y_min, 0.0);
  EXPECT_EQ(*chart.y_max, 1.0);
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_EQ(chart.series[0].label, "three-finger");
  for (double y : chart.series[0].y) EXPECT_TRUE(std::isfinite(y));
  const auto& loc = chart.series[1];
  EXPECT_NEAR(loc.y[0], 0.75, 1e-12);        // Se = 9/12
  EXPECT_TRUE(std::isnan(loc.y[1]));         // Sp: no true negatives exist
  EXPECT_NEAR(loc.y[2], 9.0 / 13.0, 1e-12);  // PPV
  EXPECT_TRUE(std::isnan(loc.y[3]));         // ACC
  EXPECT_TRUE(std::isnan(loc.y_low[1]) && std::isnan(loc.y_high[3]));
}

}  // namespace
}  // namespace palprig
