#include "charts/measures_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace palprig::charts {

namespace {

std::string percent(double confidence) { return std::to_string(static_cast<int>(std::lround(confidence * 100))); }

std::string value_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

// The proportion axis: from a round step below the lowest interval end (0 when an interval
// reaches down there anyway) to 1, its ticks never beyond 1; the padding above 1 holds the labels.
void zoom_proportion_axis(Chart& chart) {
  double lowest = 1.0;
  for (const ChartSeries& s : chart.series)
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      const double lo = !s.y_low.empty() && std::isfinite(s.y_low[i]) ? s.y_low[i] : s.y[i];
      if (std::isfinite(lo)) lowest = std::min(lowest, lo);
    }
  const double step = lowest > 0.5 ? 0.05 : 0.1;
  chart.y_min = std::max(0.0, std::floor((lowest - 0.02) / step) * step);
}

}  // namespace

void add_measure_point(ChartSeries& points, const Measure& m) {
  points.x.push_back(double(points.x.size()));
  points.y.push_back(m.defined ? m.value : std::nan(""));
  points.y_low.push_back(m.defined ? m.lower : std::nan(""));
  points.y_high.push_back(m.defined ? m.upper : std::nan(""));
  points.point_labels.push_back(m.defined ? value_text(m.value) + "\nn=" + std::to_string(m.n) : "n/a");
}

Chart measures_chart(const TrialSummary& summary) {
  return measures_chart(summary, "Se, Sp, PPV and ACC per condition (Wilson 95 % intervals)", "");
}

Chart measures_chart(const TrialSummary& summary, const std::string& title, const std::string& series_prefix) {
  Chart chart;
  chart.title = title;
  chart.y_label = "proportion";
  chart.x_categories = {"sensitivity Se", "specificity Sp", "PPV", "accuracy ACC"};
  for (const SummaryRow& row : summary.rows) {
    ChartSeries points;
    points.label = row.key.empty() ? "all" : series_prefix + row.key[0];
    points.style = ChartSeries::Style::points;
    for (const Measure* m : {&row.measures.se, &row.measures.sp, &row.measures.ppv, &row.measures.acc})
      add_measure_point(points, *m);
    chart.series.push_back(std::move(points));
  }
  zoom_proportion_axis(chart);
  chart.y_max = 1.0;  // the axis' last tick; the labels above it have their room
  return chart;
}

Chart tumor_sensitivity_chart(const TrialSummary& by_tumor) {
  Chart chart;
  chart.title = "Sensitivity per tumor (Wilson 95 % intervals)";
  chart.x_label = "tumor";
  chart.y_label = "sensitivity";
  ChartSeries points;
  points.style = ChartSeries::Style::points;
  for (const SummaryRow& row : by_tumor.rows) {
    chart.x_categories.push_back(row.key.empty() ? "all" : row.key[0]);
    add_measure_point(points, row.measures.se);
  }
  chart.series.push_back(std::move(points));
  zoom_proportion_axis(chart);
  chart.y_max = 1.0;
  return chart;
}

Chart pulse_hit_rate_chart(const std::vector<PulseConditionSummary>& rows, double confidence) {
  Chart chart;
  chart.title = "Pulse localisation: hit rate (Wilson " + percent(confidence) + " % intervals)";
  chart.x_label = "condition";
  chart.y_label = "hit rate";
  ChartSeries points;
  points.style = ChartSeries::Style::points;
  for (const PulseConditionSummary& r : rows) {
    chart.x_categories.push_back(r.condition);
    add_measure_point(points, Measure{r.hits, r.trials, r.trials > 0, r.hit_rate, r.hit_low, r.hit_high});
  }
  chart.series.push_back(std::move(points));
  zoom_proportion_axis(chart);
  chart.y_max = 1.0;
  return chart;
}

Chart pulse_distance_chart(const std::vector<PulseConditionSummary>& rows) {
  Chart chart;
  chart.title = "Distance from the mark to the artery (median, quartiles)";
  chart.x_label = "condition";
  chart.y_label = "distance (mm)";
  chart.y_min = 0.0;
  ChartSeries points;
  points.style = ChartSeries::Style::points;
  for (const PulseConditionSummary& r : rows) {
    chart.x_categories.push_back(r.condition);
    points.x.push_back(double(points.x.size()));
    points.y.push_back(r.distance_median_mm);  // NaN (no answered trial): "n/a"
    points.y_low.push_back(r.distance_q1_mm);
    points.y_high.push_back(r.distance_q3_mm);
    char text[48];
    std::snprintf(text, sizeof text, "%.1f mm\nn=%d", r.distance_median_mm, r.answered);
    points.point_labels.push_back(r.answered > 0 ? std::string(text) : std::string("n/a"));
  }
  chart.series.push_back(std::move(points));
  return chart;
}

}  // namespace palprig::charts
