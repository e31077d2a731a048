#include "charts/learning_charts.hpp"

#include <cctype>
#include <cstdio>
#include <algorithm>
#include <cmath>
#include <limits>

#include "charts/chart_svg.hpp"

namespace palprig::charts {

namespace {

constexpr unsigned kCurveRgb = 0x1f77b4, kBenchmarkRgb = 0xd62728, kLimitRgb = 0x7f7f7f, kSignalRgb = 0xd62728;

const std::vector<stats::LearningPoint>& points_of(const TrainingCurves& c, LearningMeasure m) {
  switch (m) {
    case LearningMeasure::found: return c.found;
    case LearningMeasure::false_marks: return c.false_marks;
    case LearningMeasure::time_per_case: return c.time_per_case;
    case LearningMeasure::normal_called: return c.normal_called;
  }
  return c.found;
}

const std::vector<std::optional<double>>& benchmark_of(const TrainingCurves& c, LearningMeasure m) {
  switch (m) {
    case LearningMeasure::found: return c.found_min;
    case LearningMeasure::false_marks: return c.false_marks_max;
    case LearningMeasure::time_per_case: return c.time_max_s;
    case LearningMeasure::normal_called: return c.normal_called_min;
  }
  return c.found_min;
}

const char* title_of(LearningMeasure m) {
  switch (m) {
    case LearningMeasure::found: return "Tumors found per session";
    case LearningMeasure::false_marks: return "False marks per case";
    case LearningMeasure::time_per_case: return "Seconds per case";
    case LearningMeasure::normal_called: return "Normal cases called normal";
  }
  return "";
}

std::string trainee_file_label(const std::string& code) {
  std::string out;
  for (char ch : code) out += std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' ? ch : '_';
  return out.empty() ? std::string("trainee") : out;
}

}  // namespace

const char* to_string(LearningMeasure m) noexcept {
  switch (m) {
    case LearningMeasure::found: return "found";
    case LearningMeasure::false_marks: return "false_marks";
    case LearningMeasure::time_per_case: return "time_per_case";
    case LearningMeasure::normal_called: return "normal_called";
  }
  return "found";
}

Chart learning_curve_chart(const TrainingCurves& curves, LearningMeasure measure, const std::string& trainee) {
  Chart chart;
  chart.title = std::string(title_of(measure)) + ": " + trainee;
  chart.x_label = "session";
  chart.x_whole_numbers = true;
  chart.y_label = measure == LearningMeasure::time_per_case ? "s per case"
                  : measure == LearningMeasure::false_marks ? "false marks per case"
                                                            : "proportion (95 % interval)";
  const auto& points = points_of(curves, measure);
  ChartSeries curve;
  curve.label = "session value";
  curve.color_rgb = kCurveRgb;
  bool any = false;
  for (const auto& p : points) {
    curve.x.push_back(p.session);
    curve.y.push_back(p.defined ? p.value : std::numeric_limits<double>::quiet_NaN());
    curve.y_low.push_back(p.defined ? p.lower : std::numeric_limits<double>::quiet_NaN());
    curve.y_high.push_back(p.defined ? p.upper : std::numeric_limits<double>::quiet_NaN());
    any = any || p.defined;
  }
  if (!any) return chart;
  ChartSeries marks = curve;
  marks.label.clear();
  marks.style = ChartSeries::Style::points;
  curve.y_low.clear();
  curve.y_high.clear();
  chart.series.push_back(std::move(curve));
  chart.series.push_back(std::move(marks));
  // The benchmark of each session's level, drawn from half a session before to half after.
  ChartSeries line;
  line.label = "benchmark";
  line.color_rgb = kBenchmarkRgb;
  const auto& benchmark = benchmark_of(curves, measure);
  for (std::size_t i = 0; i < benchmark.size(); ++i) {
    const double y = benchmark[i] ? *benchmark[i] : std::numeric_limits<double>::quiet_NaN();
    line.x.push_back(static_cast<double>(i) + 0.5);
    line.y.push_back(y);
    line.x.push_back(static_cast<double>(i) + 1.5);
    line.y.push_back(y);
  }
  if (!line.x.empty()) chart.series.push_back(std::move(line));
  chart.x_min = 0.5;
  chart.x_max = static_cast<double>(points.size()) + 0.5;
  if (measure == LearningMeasure::found || measure == LearningMeasure::normal_called) {
    chart.y_min = 0.0;
    chart.y_max = 1.0;
  } else {
    chart.y_min = 0.0;
  }
  return chart;
}

Chart cusum_chart(const TrainingCurves& curves, stats::CusumChart which, const std::string& trainee) {
  const bool learning = which == stats::CusumChart::learning;
  const auto& points = learning ? curves.lc_cusum : curves.cusum;
  const stats::CusumLimit& limit = learning ? curves.lc_cusum_limit : curves.cusum_limit;
  Chart chart;
  chart.title =
      std::string(learning ? "LC-CUSUM (competence declared at the limit): " : "CUSUM (an alarm at the limit): ") +
      trainee;
  chart.x_label = "case";
  chart.x_whole_numbers = true;
  // Short enough for the Training tab's chart at 1280 x 800; the title says which hypotheses.
  chart.y_label = learning ? "S (log likelihood ratio)" : "C (log likelihood ratio)";
  ChartSeries value;
  value.label = learning ? "LC-CUSUM" : "CUSUM";
  value.color_rgb = kCurveRgb;
  ChartSeries signal_points;
  signal_points.label = learning ? "competence declared" : "alarm";
  signal_points.style = ChartSeries::Style::points;
  signal_points.color_rgb = kSignalRgb;
  signal_points.width_px = 3.0;
  value.x.push_back(0);
  value.y.push_back(0);
  for (const auto& p : points) {
    value.x.push_back(p.case_number);
    value.y.push_back(p.value);
    if (p.signal) {
      signal_points.x.push_back(p.case_number);
      signal_points.y.push_back(p.value);
    }
  }
  const double last = points.empty() ? 1.0 : static_cast<double>(points.back().case_number);
  ChartSeries h;
  char label[64];
  std::snprintf(label, sizeof label, "limit h = %.2f", limit.limit);
  h.label = label;
  h.color_rgb = kLimitRgb;
  h.x = {0.0, last};
  h.y = {limit.limit, limit.limit};
  chart.series.push_back(std::move(value));
  chart.series.push_back(std::move(h));
  if (!signal_points.x.empty()) chart.series.push_back(std::move(signal_points));
  chart.x_min = 0.0;
  chart.x_max = last;
  chart.y_min = 0.0;
  double top = limit.limit;
  for (const auto& p : points) top = std::max(top, p.value);
  chart.y_max = 1.12 * top;  // the limit below the frame, not on it
  return chart;
}

std::vector<std::filesystem::path> plot_learning(const Curriculum& curriculum,
                                                 const std::vector<TraineeStanding>& trainees,
                                                 const std::filesystem::path& dir, bool svg) {
  std::vector<std::filesystem::path> written;
  const auto write = [&](const Chart& chart, const std::string& stem) {
    const auto png = dir / (stem + ".png");
    write_chart_png(chart, png);
    written.push_back(png);
    if (svg) {
      const auto vector = dir / (stem + ".svg");
      write_chart_svg(chart, vector);
      written.push_back(vector);
    }
  };
  for (const TraineeStanding& t : trainees) {
    const TrainingCurves curves = training_curves(curriculum, t);
    if (curves.level.empty()) continue;  // no completed session: nothing to draw
    const std::string who = trainee_file_label(t.trainee);
    for (LearningMeasure m : {LearningMeasure::found, LearningMeasure::false_marks, LearningMeasure::time_per_case,
                              LearningMeasure::normal_called}) {
      const Chart chart = learning_curve_chart(curves, m, t.trainee);
      if (!chart.series.empty()) write(chart, "learning_" + who + "_" + to_string(m));
    }
    write(cusum_chart(curves, stats::CusumChart::monitoring, t.trainee), "cusum_" + who);
    write(cusum_chart(curves, stats::CusumChart::learning, t.trainee), "lc_cusum_" + who);
  }
  return written;
}

}  // namespace palprig::charts
