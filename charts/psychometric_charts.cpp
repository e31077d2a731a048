#include "charts/psychometric_charts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace palprig::charts {

namespace {

std::string axis_name(const std::string& level_name) {
  if (level_name == "level_kPa") return "pressure increment over the reference (kPa)";
  if (level_name == "reference_kPa") return "reference pressure (kPa)";
  return level_name;
}

std::string number(double v, const char* format = "%.3g") {
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace

Chart psychometric_chart(const std::string& group, const stats::PsychometricFit& f, const std::string& level_name,
                         const std::string& response_name) {
  Chart chart;
  chart.title = "Psychometric function: " + group;
  chart.x_label = axis_name(level_name);
  chart.y_label = response_name == "correct" ? "proportion correct" : "proportion '" + response_name + "'";
  // Proportions of 0 and 1 sit inside the frame; ticks run 0..1.
  chart.y_min = -0.06;
  chart.y_max = 1.06;
  int max_n = 1;
  for (const auto& c : f.levels) max_n = std::max(max_n, c.n);
  ChartSeries data;
  data.label = "answers per level (area ~ trials, at most " + std::to_string(max_n) + ")";
  data.style = ChartSeries::Style::points;
  data.marker = Marker::circle;
  data.color_rgb = 0x0072B2;
  data.marker_px = 9;
  for (const auto& c : f.levels) {
    data.x.push_back(c.level);
    data.y.push_back(static_cast<double>(c.k) / c.n);
    data.marker_sizes_px.push_back(4.0 + 12.0 * std::sqrt(static_cast<double>(c.n) / max_n));
  }
  chart.series.push_back(data);
  const double lo = f.levels.front().level, hi = f.levels.back().level;
  ChartSeries curve;
  curve.label = "fit: " + std::string(stats::to_string(f.sigmoid)) + ", maximum likelihood";
  curve.color_rgb = 0xD55E00;
  for (int i = 0; i <= 300; ++i) {
    const double x = lo + (hi - lo) * i / 300.0;
    curve.x.push_back(x);
    curve.y.push_back(stats::psychometric_value(f.sigmoid, f.alpha, f.beta, f.guess, f.lapse, x));
  }
  chart.series.push_back(curve);
  // The threshold: a dashed drop line to the axis, a diamond on the curve, its interval as a
  // horizontal whisker; one legend entry each, in other shapes and dashes than the data and fit.
  ChartSeries drop;
  drop.color_rgb = 0x009E73;
  drop.dash = Dash::dashed;
  drop.width_px = 1.5;
  drop.x = {f.threshold, f.threshold};
  drop.y = {0.0, f.threshold_proportion};
  chart.series.push_back(drop);
  const bool interval = std::isfinite(f.threshold_ci.low) && std::isfinite(f.threshold_ci.high);
  ChartSeries threshold;
  threshold.style = ChartSeries::Style::points;
  threshold.marker = Marker::diamond;
  threshold.marker_px = 13;
  threshold.color_rgb = 0x009E73;
  threshold.x = {f.threshold};
  threshold.y = {f.threshold_proportion};
  const std::string unit = level_name == "level_kPa" ? " kPa" : "";
  threshold.label =
      "threshold " + number(f.threshold) + unit +
      (interval ? ", 95 % bootstrap interval " + number(f.threshold_ci.low) + " to " + number(f.threshold_ci.high)
                : std::string(" (no bootstrap interval)"));
  if (interval) {
    threshold.x_low = {f.threshold_ci.low};
    threshold.x_high = {f.threshold_ci.high};
  }
  chart.series.push_back(threshold);
  // Its value beside it, right of the interval's end so the whisker stays clear.
  ChartText at;
  at.x = interval ? f.threshold_ci.high : f.threshold;
  at.y = f.threshold_proportion;
  at.text = number(f.threshold) + unit + "\nat " + number(100 * f.threshold_proportion, "%.1f") + " %";
  at.align = ChartText::Align::right;
  at.offset_px = 12;
  at.color_rgb = 0x00684A;
  chart.annotations.push_back(at);
  return chart;
}

std::vector<SessionTrackChart> track_charts(const std::vector<ThresholdTrialRow>& rows,
                                            const std::vector<ThresholdTrackSummary>& estimates) {
  std::vector<SessionTrackChart> out;
  std::map<std::int64_t, std::map<std::string, std::vector<const ThresholdTrialRow*>>> sessions;
  for (const auto& r : rows) sessions[r.session_id][r.trial.track_name].push_back(&r);
  constexpr unsigned kColours[] = {0x0072B2, 0xD55E00, 0x009E73, 0xCC79A7, 0xE69F00, 0x56B4E9};
  for (const auto& [session, tracks] : sessions) {
    Chart chart;
    chart.title = "Adaptive tracks, session " + std::to_string(session);
    chart.x_label = "trial of the track";
    chart.y_label = "level: increment over the reference (kPa)";
    std::size_t index = 0;
    for (const auto& [name, trials] : tracks) {
      const unsigned rgb = kColours[index % std::size(kColours)];
      ChartSeries line, reversals;
      line.label = name;
      line.color_rgb = rgb;
      line.width_px = 1.5;
      line.marker = Marker::circle;
      line.marker_px = 4;
      reversals.label = name + " reversals";
      reversals.style = ChartSeries::Style::points;
      reversals.color_rgb = rgb;
      reversals.marker = index % 2 == 0 ? Marker::square : Marker::triangle;
      reversals.marker_px = 9;
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
      // Named captures: a lambda may not capture a structured binding in clang 14 (C++20 allows
      // it; GCC does), and the style gate parses this file with clang.
      const auto estimate = std::find_if(estimates.begin(), estimates.end(),
                                         [session_id = session, &track = name](const ThresholdTrackSummary& e) {
                                           return e.session == session_id && e.track == track;
                                         });
      if (estimate != estimates.end() && std::isfinite(estimate->estimate.threshold_kPa)) {
        const double t = estimate->estimate.threshold_kPa;
        ChartSeries threshold;
        threshold.label = name + " threshold " + number(t, "%.3f") + " kPa (" +
                          number(100 * estimate->estimate.target_probability, "%.1f") + " %)";
        threshold.color_rgb = rgb;
        threshold.dash = Dash::dashed;
        threshold.width_px = 1.5;
        threshold.x = {1.0, static_cast<double>(trials.size())};
        threshold.y = {t, t};
        chart.series.push_back(threshold);
      }
      ++index;
    }
    chart.y_min = 0.0;
    out.push_back({session, std::move(chart)});
  }
  return out;
}

}  // namespace palprig::charts
