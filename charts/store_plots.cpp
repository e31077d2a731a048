#include "charts/store_plots.hpp"

#include <cctype>
#include <cmath>

#include "charts/chart_png.hpp"
#include "charts/chart_svg.hpp"
#include "charts/measures_chart.hpp"
#include "charts/psychometric_charts.hpp"
#include "core/input_error.hpp"
#include "statistics/statistics_error.hpp"
#include "store/pulse_store.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/threshold_psychometric.hpp"
#include "store/threshold_store.hpp"
#include "store/threshold_summary.hpp"
#include "store/trial_summary.hpp"

namespace palprig::charts {

namespace {

std::string group_file_label(const std::string& text) {
  std::string s;
  for (char c : text) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

void write(const Chart& chart, const std::filesystem::path& dir, const std::string& stem, const StorePlotOptions& o,
           std::vector<std::filesystem::path>& written) {
  const auto png = dir / (stem + ".png");
  write_chart_png(chart, png);
  written.push_back(png);
  if (o.svg) {
    const auto svg = dir / (stem + ".svg");
    write_chart_svg(chart, svg);
    written.push_back(svg);
  }
}

// 2AFC sessions guess at 0.5; a yes/no session's "correct" is a yes, whose floor is the
// false-alarm rate: fitted.
std::optional<double> threshold_guess(TrialStore& store) {
  for (const SessionOverview& s : store.list_sessions()) {
    if (s.task != "threshold") continue;
    const nlohmann::json p = store.protocol_snapshot(s.id);
    if (p.is_object() && p.value("method", std::string("2afc")) == "yes-no") return std::nullopt;
  }
  return 0.5;
}

}  // namespace

std::vector<std::filesystem::path> plot_store(TrialStore& store, const std::filesystem::path& dir,
                                              const StorePlotOptions& options) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(dir.string(), "--plot", "a folder that can be created");
  std::vector<std::filesystem::path> written;

  SummaryOptions by_condition;
  by_condition.by = {SummaryKey::condition};
  by_condition.include_practice = false;
  const Chart measures = measures_chart(summarise_trials(store, by_condition));
  if (!measures.series.empty()) write(measures, dir, "measures_by_condition", options, written);
  // Per finger value (discrimination) and per tumor (localisation), as the window shows them.
  for (SummaryKey key : {SummaryKey::finger, SummaryKey::tumor}) {
    SummaryOptions by = by_condition;
    by.by = {key};
    TrialSummary summary = summarise_trials(store, by);
    std::erase_if(summary.rows, [](const SummaryRow& r) { return r.key.empty() || r.key[0] == "-"; });
    if (summary.rows.empty()) continue;
    if (key == SummaryKey::finger)
      write(measures_chart(summary, "Se, Sp, PPV and ACC per finger value (Wilson 95 % intervals)", "finger "), dir,
            "measures_by_finger", options, written);
    else
      write(tumor_sensitivity_chart(summary), dir, "sensitivity_by_tumor", options, written);
  }

  if (auto* sqlite = dynamic_cast<SqliteTrialStore*>(&store)) {
    ThresholdStore threshold(*sqlite, false);
    const std::vector<ThresholdTrialRow> rows = threshold.trials();
    bool answered = false;
    for (const ThresholdTrialRow& r : rows) answered = answered || r.trial.answered;
    if (answered) {
      for (const SessionTrackChart& c : track_charts(rows, summarise_threshold_tracks(*sqlite)))
        write(c.chart, dir, "track_session" + std::to_string(c.session), options, written);
      stats::PsychometricOptions fit_options;
      fit_options.guess = threshold_guess(store);
      fit_options.bootstrap = options.bootstrap;
      fit_options.seed = options.seed;
      const stats::PsychometricColumns columns{"", "", "", "track_name"};
      for (const stats::PsychometricGroup& g : threshold_psychometric_groups(rows, columns, store.location())) {
        stats::PsychometricFit fit;
        try {
          fit = stats::fit_psychometric(g.counts, fit_options);
        } catch (const stats::StatisticsError& e) {
          throw InputError(store.location(), "threshold trials of track '" + g.label + "'", e.what());
        }
        write(psychometric_chart(g.label, fit, "level_kPa", fit_options.guess ? "correct" : "yes"), dir,
              "psychometric_" + group_file_label(g.label), options, written);
      }
    }
    PulseStore pulse(*sqlite, false);
    if (pulse.has_trials()) {
      const auto summary = pulse.summarise();
      if (!summary.empty())
        write(pulse_hit_rate_chart(summary, 0.95), dir, "pulse_hits_by_condition", options, written);
      if (!summary.empty()) write(pulse_distance_chart(summary), dir, "pulse_distance_by_condition", options, written);
    }
  }
  if (written.empty()) throw InputError(store.location(), "trials", "at least one scored trial to plot");
  return written;
}

}  // namespace palprig::charts
