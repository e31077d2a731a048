#include "gui/measures_chart.hpp"

#include <cmath>

namespace palprig::gui {

Chart measures_chart(const TrialSummary& summary) {
  Chart chart;
  chart.title = "Se, Sp, PPV and ACC per condition (Wilson 95 % intervals)";
  chart.y_label = "proportion";
  chart.x_categories = {"Se", "Sp", "PPV", "ACC"};
  chart.y_min = 0.0;  // proportions: the axis ends at 1, the legend sits beside the plot
  chart.y_max = 1.0;
  for (const SummaryRow& row : summary.rows) {
    ChartSeries bars;
    bars.label = row.key.empty() ? "all" : row.key[0];
    bars.style = ChartSeries::Style::bars;
    for (const Measure* m : {&row.measures.se, &row.measures.sp, &row.measures.ppv, &row.measures.acc}) {
      bars.x.push_back(double(bars.x.size()));
      bars.y.push_back(m->defined ? m->value : std::nan(""));
      bars.y_low.push_back(m->defined ? m->lower : std::nan(""));
      bars.y_high.push_back(m->defined ? m->upper : std::nan(""));
    }
    chart.series.push_back(std::move(bars));
  }
  return chart;
}

}  // namespace palprig::gui
