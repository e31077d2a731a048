#include "gui/trial_charts.hpp"

#include <cmath>

#include "gui/chart_png.hpp"
#include "models/parse_error.hpp"
#include "store/trial_summary.hpp"

namespace palprig::gui {

std::filesystem::path plot_measures_by_condition(TrialStore& store, const std::filesystem::path& dir,
                                                 bool include_practice) {
  SummaryOptions options;
  options.by = {SummaryKey::condition};
  options.include_practice = include_practice;
  const TrialSummary summary = summarise_trials(store, options);
  Chart chart;
  chart.title = "Se, Sp, PPV and ACC per condition (Wilson 95 % intervals)";
  chart.y_label = "proportion";
  chart.x_categories = {"Se", "Sp", "PPV", "ACC"};
  chart.y_min = 0.0;
  chart.y_max = 1.25;  // room above the bars for the legend
  for (const SummaryRow& row : summary.rows) {
    ChartSeries bars;
    bars.label = row.key.empty() ? "all" : row.key[0];
    bars.style = ChartSeries::Style::bars;
    for (const Measure* m : {&row.measures.se, &row.measures.sp, &row.measures.ppv, &row.measures.acc}) {
      bars.x.push_back(double(bars.x.size()));
      // An undefined measure (no cases) is left out of the chart rather than drawn as 0.
      bars.y.push_back(m->defined ? m->value : std::nan(""));
      bars.y_low.push_back(m->defined ? m->lower : std::nan(""));
      bars.y_high.push_back(m->defined ? m->upper : std::nan(""));
    }
    chart.series.push_back(std::move(bars));
  }
  if (chart.series.empty()) throw InputError(store.location(), "trials", "at least one scored trial to plot");
  std::filesystem::create_directories(dir);
  const auto path = dir / "measures_by_condition.png";
  write_chart_png(chart, path);
  return path;
}

}  // namespace palprig::gui
