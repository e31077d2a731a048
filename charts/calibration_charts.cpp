#include "charts/calibration_charts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "calibration/branch_fits.hpp"
#include "charts/chart_png.hpp"
#include "charts/chart_svg.hpp"
#include "models/hysteresis.hpp"

namespace palprig::charts {

namespace {

constexpr unsigned kInflationRgb = 0x0072B2, kDeflationRgb = 0xD55E00, kBothRgb = 0x555555;

ChartSeries line_series(const std::string& label, const LineFit& f, unsigned rgb, Dash dash) {
  ChartSeries s;
  s.label = label;
  s.x = {f.x_min, f.x_max};
  s.y = {f.at(f.x_min), f.at(f.x_max)};
  s.color_rgb = rgb;
  s.dash = dash;
  s.width_px = 1.8;
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
  up.label = "inflation holds";
  down.label = "deflation holds";
  up.color_rgb = kInflationRgb;
  down.color_rgb = kDeflationRgb;
  up.marker = Marker::triangle;
  down.marker = Marker::inverted_triangle;
  up.marker_px = down.marker_px = 7;
  for (const auto& p : pts) {
    if (p.segment != SweepSegment::staircase || p.branch == SweepBranch::none) continue;
    ChartSeries& s = p.branch == SweepBranch::inflation ? up : down;
    s.x.push_back(p.command_kPa);
    s.y.push_back(response_of(p, response));
  }
  char text[96];
  std::snprintf(text, sizeof text, "inflation line, R^2 %.4f", fits.inflation.r_squared);
  c.series.push_back(line_series(text, fits.inflation, kInflationRgb, Dash::solid));
  std::snprintf(text, sizeof text, "deflation line, R^2 %.4f", fits.deflation.r_squared);
  c.series.push_back(line_series(text, fits.deflation, kDeflationRgb, Dash::dashed));
  std::snprintf(text, sizeof text, "both branches, R^2 %.4f", fits.both.r_squared);
  c.series.push_back(line_series(text, fits.both, kBothRgb, Dash::dotted));
  c.series.push_back(up);
  c.series.push_back(down);
  return c;
}

}  // namespace

std::vector<NamedChart> fit_charts(const SweepData& data, const CalibrationResult& r) {
  std::vector<NamedChart> out;
  for (const auto& ch : r.channels) {
    if (!ch.swept) continue;
    const std::string n = std::to_string(ch.channel);
    const auto pts = data.channel_points(ch.channel);
    if (ch.regulator)
      out.push_back({"channel_" + n + "_regulator",
                     branch_chart("Channel " + n + ": regulator monitor against command", "monitored pressure (kPa)",
                                  pts, MeasuredSignal::monitor, *ch.regulator)});
    if (ch.response)
      out.push_back(
          {"channel_" + n + "_sensor", branch_chart("Channel " + n + ": " + r.sensor_name + " against command",
                                                    r.sensor_name, pts, MeasuredSignal::sensor, *ch.response)});
    if (ch.hysteresis) {
      // Every hold's reading, and the model driven through a major loop and nested minor loops.
      Chart c;
      c.title = "Channel " + n + ": hysteresis model (Prandtl-Ishlinskii)";
      c.x_label = "commanded pressure (kPa)";
      c.y_label =
          ch.hysteresis_source == HysteresisSource::sensor ? "sensor as pressure (kPa)" : "monitored pressure (kPa)";
      ChartSeries measured, model;
      measured.style = ChartSeries::Style::points;
      measured.label = "recorded holds";
      measured.color_rgb = 0x999999;
      measured.marker = Marker::circle;
      measured.marker_px = 5;
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
      model.label = "fitted model: major and minor loops";
      model.color_rgb = kDeflationRgb;
      const double mid = 0.5 * (lo + hi);
      double at = 0;
      for (double goal : {hi, lo, hi, mid - 0.25 * (hi - lo), mid + 0.25 * (hi - lo), mid - 0.1 * (hi - lo)}) {
        const double step = goal > at ? 0.1 : -0.1;
        for (; (goal - at) * step > 0; at += step) {
          model.x.push_back(at);
          model.y.push_back(m.apply_exhausting(at));  // as the fit and the tick run the plays
        }
      }
      if (ch.hysteresis_source == HysteresisSource::monitor) c.series.push_back(measured);
      c.series.push_back(model);
      out.push_back({"channel_" + n + "_hysteresis", std::move(c)});
    }
  }
  return out;
}

std::vector<NamedChart> evaluation_charts(const EvaluationResult& r, const std::array<bool, kFingerCount>& channels) {
  std::vector<NamedChart> out;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!channels[c]) continue;
    const std::string n = std::to_string(c + 1);
    Chart error, loops;
    error.title = "Channel " + n + ": tracking error with and without compensation";
    error.x_label = "time into the scored run (s)";
    error.y_label = "monitor minus target (kPa)";
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
      e.dash = l.dash = with ? Dash::solid : Dash::dashed;
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
    identity.label = "monitor = target";
    identity.color_rgb = kBothRgb;
    identity.dash = Dash::dotted;
    identity.width_px = 1.5;
    identity.x = identity.y = {r.from_kPa, r.to_kPa};
    loops.series.push_back(identity);
    out.push_back({"evaluate_channel_" + n + "_error", std::move(error)});
    out.push_back({"evaluate_channel_" + n + "_loops", std::move(loops)});
  }
  return out;
}

std::vector<std::filesystem::path> write_charts(const std::filesystem::path& dir, const std::vector<NamedChart>& charts,
                                                bool svg) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> written;
  for (const NamedChart& c : charts) {
    const auto png = dir / (c.stem + ".png");
    write_chart_png(c.chart, png);
    written.push_back(png);
    if (svg) {
      const auto file = dir / (c.stem + ".svg");
      write_chart_svg(c.chart, file);
      written.push_back(file);
    }
  }
  return written;
}

std::vector<std::filesystem::path> plot_fit(const std::filesystem::path& dir, const SweepData& data,
                                            const CalibrationResult& r, bool svg) {
  return write_charts(dir, fit_charts(data, r), svg);
}

std::vector<std::filesystem::path> plot_evaluation(const std::filesystem::path& dir, const EvaluationResult& r,
                                                   const std::array<bool, kFingerCount>& channels, bool svg) {
  return write_charts(dir, evaluation_charts(r, channels), svg);
}

}  // namespace palprig::charts
