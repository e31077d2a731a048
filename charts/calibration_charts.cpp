#include "charts/calibration_charts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "calibration/branch_fits.hpp"
#include "charts/chart_png.hpp"
#include "models/hysteresis.hpp"

namespace palprig::charts {

namespace {

constexpr unsigned kInflationRgb = 0x1f77b4, kDeflationRgb = 0xd62728, kBothRgb = 0x555555;

ChartSeries line_series(const std::string& label, const LineFit& f, unsigned rgb) {
  ChartSeries s;
  s.label = label;
  s.x = {f.x_min, f.x_max};
  s.y = {f.at(f.x_min), f.at(f.x_max)};
  s.color_rgb = rgb;
  return s;
}

// Staircase readings per branch with the fitted lines (paper 002 fig. 8).
Chart branch_chart(const std::string& title, const std::string& y_label, const std::vector<HoldPoint>& pts,
                   MeasuredSignal response, const BranchFits& fits) {
  Chart c;
  c.title = title;
  c.x_label = "commanded pressure (kPa)";
  c.y_label = y_label;
  ChartSeries up, down;
  up.style = down.style = ChartSeries::Style::points;
  up.color_rgb = kInflationRgb;
  down.color_rgb = kDeflationRgb;
  for (const auto& p : pts) {
    if (p.segment != SweepSegment::staircase || p.branch == SweepBranch::none) continue;
    ChartSeries& s = p.branch == SweepBranch::inflation ? up : down;
    s.x.push_back(p.command_kPa);
    s.y.push_back(response_of(p, response));
  }
  char text[96];
  std::snprintf(text, sizeof text, "inflation, R^2 %.4f", fits.inflation.r_squared);
  c.series.push_back(line_series(text, fits.inflation, kInflationRgb));
  std::snprintf(text, sizeof text, "deflation, R^2 %.4f", fits.deflation.r_squared);
  c.series.push_back(line_series(text, fits.deflation, kDeflationRgb));
  std::snprintf(text, sizeof text, "both, R^2 %.4f", fits.both.r_squared);
  c.series.push_back(line_series(text, fits.both, kBothRgb));
  c.series.push_back(up);
  c.series.push_back(down);
  return c;
}

}  // namespace

std::vector<std::filesystem::path> plot_fit(const std::filesystem::path& dir, const SweepData& data,
                                            const CalibrationResult& r) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> written;
  auto save = [&](const Chart& c, const std::string& name) {
    const auto p = dir / name;
    charts::write_chart_png(c, p);
    written.push_back(p);
  };
  for (const auto& ch : r.channels) {
    if (!ch.swept) continue;
    const std::string n = std::to_string(ch.channel);
    const auto pts = data.channel_points(ch.channel);
    if (ch.regulator)
      save(branch_chart("Channel " + n + ": regulator monitor against command", "monitored pressure (kPa)", pts,
                        MeasuredSignal::monitor, *ch.regulator),
           "channel_" + n + "_regulator.png");
    if (ch.response)
      save(branch_chart("Channel " + n + ": " + r.sensor_name + " against command", r.sensor_name, pts,
                        MeasuredSignal::sensor, *ch.response),
           "channel_" + n + "_sensor.png");
    if (ch.hysteresis) {
      // Every hold's reading, and the model driven through a major loop and nested minor loops.
      Chart c;
      c.title = "Channel " + n + ": hysteresis model (Prandtl-Ishlinskii)";
      c.x_label = "commanded pressure (kPa)";
      c.y_label =
          ch.hysteresis_source == HysteresisSource::sensor ? "sensor as pressure (kPa)" : "monitored pressure (kPa)";
      ChartSeries measured, model;
      measured.style = ChartSeries::Style::points;
      measured.label = "holds";
      measured.color_rgb = 0x999999;
      double lo = 1e300, hi = -1e300;
      for (const auto& p : pts) {
        const double y = ch.hysteresis_source == HysteresisSource::monitor ? p.monitor_kPa : std::nan("");
        measured.x.push_back(p.command_kPa);
        measured.y.push_back(y);
        if (p.segment != SweepSegment::vent) {
          lo = std::min(lo, p.command_kPa);
          hi = std::max(hi, p.command_kPa);
        }
      }
      PrandtlIshlinskii m = ch.hysteresis->model;
      m.reset(0);
      model.label = "model: major and minor loops";
      model.color_rgb = kDeflationRgb;
      const double mid = 0.5 * (lo + hi);
      double at = 0;
      for (double goal : {hi, lo, hi, mid - 0.25 * (hi - lo), mid + 0.25 * (hi - lo), mid - 0.1 * (hi - lo)}) {
        const double step = goal > at ? 0.1 : -0.1;
        for (; (goal - at) * step > 0; at += step) {
          model.x.push_back(at);
          model.y.push_back(m.apply(at));
        }
      }
      if (ch.hysteresis_source == HysteresisSource::monitor) c.series.push_back(measured);
      c.series.push_back(model);
      save(c, "channel_" + n + "_hysteresis.png");
    }
  }
  return written;
}

std::vector<std::filesystem::path> plot_evaluation(const std::filesystem::path& dir, const EvaluationResult& r,
                                                   const std::array<bool, kFingerCount>& channels) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> written;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!channels[c]) continue;
    const std::string n = std::to_string(c + 1);
    Chart error, loops;
    error.title = "Channel " + n + ": tracking error with and without compensation";
    error.x_label = "time into the scored run (s)";
    error.y_label = "monitor - target (kPa)";
    loops.title = "Channel " + n + ": output against target";
    loops.x_label = "target (kPa)";
    loops.y_label = "monitored pressure (kPa)";
    for (int with = 0; with < 2; ++with) {
      const EvaluationRun& run = with ? r.compensated : r.uncompensated;
      ChartSeries e, l;
      char label[96];
      std::snprintf(label, sizeof label, "%s, RMS %.3f kPa", with ? "compensated" : "uncompensated",
                    run.channels[c].rms_error_kPa);
      e.label = l.label = label;
      e.color_rgb = l.color_rgb = with ? kInflationRgb : kDeflationRgb;
      e.width_px = l.width_px = 1.2;
      for (const auto& row : run.trace) {
        if (row.t_s < run.scored_from_t_s) continue;  // the rest and the first approach
        e.x.push_back(row.t_s - run.scored_from_t_s);
        e.y.push_back(row.monitor_kPa[c] - row.target_kPa);
        l.x.push_back(row.target_kPa);
        l.y.push_back(row.monitor_kPa[c]);
      }
      error.series.push_back(e);
      loops.series.push_back(l);
    }
    ChartSeries identity;
    identity.label = "target";
    identity.color_rgb = kBothRgb;
    identity.width_px = 1;
    identity.x = identity.y = {r.from_kPa, r.to_kPa};
    loops.series.push_back(identity);
    for (const auto& [chart, name] : {std::pair{&error, "evaluate_channel_" + n + "_error.png"},
                                      std::pair{&loops, "evaluate_channel_" + n + "_loops.png"}}) {
      charts::write_chart_png(*chart, dir / name);
      written.push_back(dir / name);
    }
  }
  return written;
}

}  // namespace palprig::charts
