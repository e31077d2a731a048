#include "charts/psychometric_charts.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace palprig::charts {

Chart psychometric_chart(const std::string& group, const stats::PsychometricFit& f, const std::string& level_name) {
  Chart chart;
  chart.title = "Psychometric function: " + group + " (" + stats::to_string(f.sigmoid) + ")";
  chart.x_label = level_name;
  chart.y_label = "proportion yes / correct";
  chart.y_min = 0;
  chart.y_max = 1;
  int max_n = 1;
  for (const auto& c : f.levels) max_n = std::max(max_n, c.n);
  for (std::size_t i = 0; i < f.levels.size(); ++i) {
    const auto& c = f.levels[i];
    ChartSeries point;
    point.label = i == 0 ? "data (point area ~ n)" : "";
    point.style = ChartSeries::Style::points;
    point.x = {c.level};
    point.y = {static_cast<double>(c.k) / c.n};
    point.color_rgb = 0x1f77b4;
    point.width_px = 1.0 + 5.0 * std::sqrt(static_cast<double>(c.n) / max_n);
    chart.series.push_back(point);
  }
  const double lo = f.levels.front().level, hi = f.levels.back().level;
  ChartSeries curve;
  curve.label = "ML fit";
  curve.color_rgb = 0xd62728;
  for (int i = 0; i <= 200; ++i) {
    const double x = lo + (hi - lo) * i / 200.0;
    curve.x.push_back(x);
    curve.y.push_back(stats::psychometric_value(f.sigmoid, f.alpha, f.beta, f.guess, f.lapse, x));
  }
  chart.series.push_back(curve);
  ChartSeries threshold;
  threshold.label = "threshold";
  threshold.color_rgb = 0x2ca02c;
  threshold.x = {f.threshold, f.threshold};
  threshold.y = {0.0, f.threshold_proportion};
  chart.series.push_back(threshold);
  if (std::isfinite(f.threshold_ci.low)) {
    ChartSeries ci;
    ci.label = "95 % bootstrap interval";
    ci.color_rgb = 0x2ca02c;
    ci.width_px = 4;
    ci.x = {f.threshold_ci.low, f.threshold_ci.high};
    ci.y = {f.threshold_proportion, f.threshold_proportion};
    chart.series.push_back(ci);
  }
  return chart;
}

std::vector<SessionTrackChart> track_charts(const std::vector<ThresholdTrialRow>& rows) {
  std::vector<SessionTrackChart> out;
  std::map<std::int64_t, std::map<std::string, std::vector<const ThresholdTrialRow*>>> sessions;
  for (const auto& r : rows) sessions[r.session_id][r.trial.track_name].push_back(&r);
  for (const auto& [session, tracks] : sessions) {
    Chart chart;
    chart.title = "Adaptive tracks, session " + std::to_string(session);
    chart.x_label = "trial of the track";
    chart.y_label = "level (increment, kPa)";
    for (const auto& [name, trials] : tracks) {
      ChartSeries line, reversals;
      line.label = name;
      reversals.label = name + " reversals";
      reversals.style = ChartSeries::Style::points;
      reversals.width_px = 3;
      for (std::size_t i = 0; i < trials.size(); ++i) {
        line.x.push_back(static_cast<double>(i + 1));
        line.y.push_back(trials[i]->trial.level_kPa);
        if (trials[i]->trial.reversal) {
          reversals.x.push_back(static_cast<double>(i + 1));
          reversals.y.push_back(trials[i]->trial.level_kPa);
        }
      }
      chart.series.push_back(line);
      if (!reversals.x.empty()) chart.series.push_back(reversals);
    }
    out.push_back({session, std::move(chart)});
  }
  return out;
}

std::vector<std::string> write_track_charts(const std::vector<ThresholdTrialRow>& rows,
                                            const std::filesystem::path& dir) {
  std::vector<std::string> written;
  for (const SessionTrackChart& c : track_charts(rows)) {
    const auto path = dir / ("track_session" + std::to_string(c.session) + ".png");
    write_chart_png(c.chart, path);
    written.push_back(path.string());
  }
  return written;
}

}  // namespace palprig::charts
