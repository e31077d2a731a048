#include "charts/measures_chart.hpp"

#include <cmath>

namespace palprig::charts {

void add_measure_bar(ChartSeries& bars, const Measure& m) {
  bars.x.push_back(double(bars.x.size()));
  bars.y.push_back(m.defined ? m.value : std::nan(""));
  bars.y_low.push_back(m.defined ? m.lower : std::nan(""));
  bars.y_high.push_back(m.defined ? m.upper : std::nan(""));
  bars.bar_labels.push_back(m.defined ? "n=" + std::to_string(m.n) : "n/a");
}

Chart measures_chart(const TrialSummary& summary) {
  return measures_chart(summary, "Se, Sp, PPV and ACC per condition (Wilson 95 % intervals)", "");
}

Chart measures_chart(const TrialSummary& summary, const std::string& title, const std::string& series_prefix) {
  Chart chart;
  chart.title = title;
  chart.y_label = "proportion";
  chart.x_categories = {"Se", "Sp", "PPV", "ACC"};
  chart.y_min = 0.0;  // proportions: the axis ends at 1, the legend sits beside the plot
  chart.y_max = 1.0;
  for (const SummaryRow& row : summary.rows) {
    ChartSeries bars;
    bars.label = row.key.empty() ? "all" : series_prefix + row.key[0];
    bars.style = ChartSeries::Style::bars;
    for (const Measure* m : {&row.measures.se, &row.measures.sp, &row.measures.ppv, &row.measures.acc})
      add_measure_bar(bars, *m);
    chart.series.push_back(std::move(bars));
  }
  return chart;
}

Chart tumor_sensitivity_chart(const TrialSummary& by_tumor) {
  Chart chart;
  chart.title = "Sensitivity per tumor (Wilson 95 % intervals)";
  chart.y_label = "sensitivity";
  chart.y_min = 0.0;
  chart.y_max = 1.0;
  ChartSeries bars;
  bars.style = ChartSeries::Style::bars;
  for (const SummaryRow& row : by_tumor.rows) {
    chart.x_categories.push_back(row.key.empty() ? "all" : row.key[0]);
    add_measure_bar(bars, row.measures.se);
  }
  chart.series.push_back(std::move(bars));
  return chart;
}

}  // namespace palprig::charts
