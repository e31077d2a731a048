#include "charts/trial_charts.hpp"

#include "charts/chart_png.hpp"
#include "charts/measures_chart.hpp"
#include "core/input_error.hpp"
#include "store/trial_summary.hpp"

namespace palprig::charts {

std::filesystem::path plot_measures_by_condition(TrialStore& store, const std::filesystem::path& dir,
                                                 bool include_practice) {
  SummaryOptions options;
  options.by = {SummaryKey::condition};
  options.include_practice = include_practice;
  const TrialSummary summary = summarise_trials(store, options);
  const Chart chart = measures_chart(summary);  // fig. 15, shared with the GUI
  if (chart.series.empty()) throw InputError(store.location(), "trials", "at least one scored trial to plot");
  std::filesystem::create_directories(dir);
  const auto path = dir / "measures_by_condition.png";
  write_chart_png(chart, path);
  return path;
}

}  // namespace palprig::charts
