// palprig stats psychometric FILE --level COL --response COL [--n COL] [--by COL] [--json]
//   [--plot DIR] [--sigmoid S] [--guess G|fit] [--lapse L|fit] [--threshold-at P]
//   [--bootstrap N] [--seed S]
// FILE is a CSV (one row per trial with a 0/1 response, or one row per level with the count of
// yes/correct answers in --response and the number of trials in --n) or a trial database
// (threshold_trials: level_kPa, correct, response, track_name, fingers, participant). The fit
// is statistics/psychometric_fit.hpp; --plot draws each group's data and curve, and for a
// database every session's staircase tracks.
#include "cli/psychometric_command.hpp"

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "models/parse_error.hpp"
#include "statistics/csv_table.hpp"
#include "statistics/psychometric_fit.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_report.hpp"
#include "store/threshold_store.hpp"
#include "store/sqlite_trial_store.hpp"
#ifdef PALPRIG_HAVE_GUI
#include "gui/chart_png.hpp"
#endif

using namespace palprig;

namespace {

struct Args {
  std::string file, level, response, n, by, plot, sigmoid = "cumulative-gaussian", guess, lapse = "fit";
  std::optional<double> threshold_at;
  double guess_max = 0.5, lapse_max = 0.1, confidence = 0.95;
  int bootstrap = 1000;
  std::uint64_t seed = 1;
  bool json = false;
};

struct Group {
  std::string label;
  std::vector<stats::LevelCounts> counts;
};

bool is_sqlite(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[16] = {};
  in.read(magic, sizeof magic);
  return in.gcount() == 16 && std::string(magic, 15) == "SQLite format 3";
}

// Groups in order of first appearance; per-trial rows are counted per level.
std::vector<Group> groups_from_csv(const Args& a) {
  const CsvTable table = CsvTable::read(a.file);
  if (a.level.empty() || a.response.empty()) throw InputError("command line", "--level/--response", "both columns for a CSV file");
  const std::size_t level = table.column(a.level), response = table.column(a.response);
  const std::optional<std::size_t> n = a.n.empty() ? std::nullopt : std::optional<std::size_t>(table.column(a.n));
  const std::optional<std::size_t> by = a.by.empty() ? std::nullopt : std::optional<std::size_t>(table.column(a.by));
  std::vector<std::string> order;
  std::map<std::string, std::map<double, stats::LevelCounts>> grouped;
  for (std::size_t row = 0; row < table.rows(); ++row) {
    const std::string label = by ? table.label(row, *by) : "all";
    if (!grouped.count(label)) order.push_back(label);
    auto& c = grouped[label][table.number(row, level)];
    c.level = table.number(row, level);
    const double k = table.number(row, response);
    const std::string where = "line " + std::to_string(table.line_of_row(row));
    if (n) {
      const double trials = table.number(row, *n);
      if (trials != std::floor(trials) || trials < 0 || k != std::floor(k) || k < 0 || k > trials) {
        throw InputError(table.source(), where + ", columns '" + a.response + "', '" + a.n + "'",
                         "whole counts with 0 <= " + a.response + " <= " + a.n);
      }
      c.n += static_cast<int>(trials);
      c.k += static_cast<int>(k);
    } else {
      if (k != 0 && k != 1) {
        throw InputError(table.source(), where + ", column '" + a.response + "'",
                         "a response of 0 or 1 per trial (or give --n COL for counts per level), got " + table.text(row, response));
      }
      ++c.n;
      c.k += static_cast<int>(k);
    }
  }
  std::vector<Group> out;
  for (const auto& label : order) {
    Group g{label, {}};
    for (const auto& [level, c] : grouped[label]) g.counts.push_back(c);
    out.push_back(std::move(g));
  }
  return out;
}

double db_number(const ThresholdTrialRow& r, const std::string& column, const std::string& file) {
  if (column == "level_kPa") return r.trial.level_kPa;
  if (column == "correct") return r.trial.correct ? 1 : 0;
  if (column == "response") return r.trial.response;
  if (column == "reference_kPa") return r.trial.reference_kPa;
  throw InputError(file, "column '" + column + "'",
                   "a threshold_trials column: level_kPa, reference_kPa (levels); correct, response (responses)");
}

std::string db_label(const ThresholdTrialRow& r, const std::string& column, const std::string& file) {
  if (column.empty()) return "all";
  if (column == "track_name" || column == "track") return r.trial.track_name;
  if (column == "fingers") return r.trial.fingers;
  if (column == "participant") return r.participant;
  if (column == "session_id" || column == "session") return std::to_string(r.session_id);
  throw InputError(file, "column '" + column + "'", "a threshold_trials group column: track_name, fingers, participant, session_id");
}

std::vector<ThresholdTrialRow> database_rows(const std::string& file) {
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(file);
  ThresholdStore threshold(store, false);
  return threshold.trials();
}

std::vector<Group> groups_from_database(const Args& a, const std::vector<ThresholdTrialRow>& rows) {
  const std::string level = a.level.empty() ? "level_kPa" : a.level;
  const std::string response = a.response.empty() ? "correct" : a.response;
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> levels;
  std::map<std::string, std::vector<int>> responses;
  for (const ThresholdTrialRow& r : rows) {
    if (!r.trial.answered) continue;
    const std::string label = db_label(r, a.by, a.file);
    if (!levels.count(label)) order.push_back(label);
    levels[label].push_back(db_number(r, level, a.file));
    responses[label].push_back(static_cast<int>(db_number(r, response, a.file)));
  }
  if (order.empty()) throw InputError(a.file, "threshold_trials", "answered threshold trials (the database has none)");
  std::vector<Group> out;
  for (const auto& label : order) out.push_back({label, stats::counts_per_level(levels[label], responses[label])});
  return out;
}

stats::Report interval_report(const stats::Interval& i) { return {{"low", i.low}, {"high", i.high}}; }

stats::Report fit_report(const stats::PsychometricFit& f, double confidence) {
  stats::Report r;
  r["sigmoid"] = stats::to_string(f.sigmoid);
  r["trials"] = f.trials;
  r["alpha"] = f.alpha;
  r["beta"] = f.beta;
  r["guess"] = f.guess;
  r["guess_fitted"] = f.guess_fitted;
  r["lapse"] = f.lapse;
  r["lapse_fitted"] = f.lapse_fitted;
  r["threshold"] = f.threshold;
  r["threshold_proportion"] = f.threshold_proportion;
  r["slope"] = f.slope;
  r["jnd"] = f.jnd;
  r["confidence"] = confidence;
  r["bootstrap"] = f.bootstrap;
  r["bootstrap_failed"] = f.bootstrap_failed;
  r["alpha_ci"] = interval_report(f.alpha_ci);
  r["beta_ci"] = interval_report(f.beta_ci);
  r["threshold_ci"] = interval_report(f.threshold_ci);
  r["slope_ci"] = interval_report(f.slope_ci);
  r["jnd_ci"] = interval_report(f.jnd_ci);
  r["log_likelihood"] = f.log_likelihood;
  r["deviance"] = f.deviance;
  r["deviance_df"] = f.deviance_df;
  r["gof_p"] = f.gof_p;
  r["fit_seconds"] = f.fit_seconds;
  r["bootstrap_seconds"] = f.bootstrap_seconds;
  stats::Report levels = stats::Report::array();
  for (const auto& c : f.levels) {
    levels.push_back({{"level", c.level}, {"n", c.n}, {"k", c.k}, {"proportion", static_cast<double>(c.k) / c.n}});
  }
  r["levels"] = levels;
  return r;
}

std::string file_label(const std::string& text) {
  std::string s;
  for (char c : text) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

#ifdef PALPRIG_HAVE_GUI
void plot_fit(const Group& g, const stats::PsychometricFit& f, const std::string& level_name,
              const std::filesystem::path& path) {
  gui::Chart chart;
  chart.title = "Psychometric function: " + g.label + " (" + stats::to_string(f.sigmoid) + ")";
  chart.x_label = level_name;
  chart.y_label = "proportion yes / correct";
  chart.y_min = 0;
  chart.y_max = 1;
  int max_n = 1;
  for (const auto& c : f.levels) max_n = std::max(max_n, c.n);
  for (std::size_t i = 0; i < f.levels.size(); ++i) {
    const auto& c = f.levels[i];
    gui::ChartSeries point;
    point.label = i == 0 ? "data (point area ~ n)" : "";
    point.style = gui::ChartSeries::Style::points;
    point.x = {c.level};
    point.y = {static_cast<double>(c.k) / c.n};
    point.color_rgb = 0x1f77b4;
    point.width_px = 1.0 + 5.0 * std::sqrt(static_cast<double>(c.n) / max_n);
    chart.series.push_back(point);
  }
  const double lo = f.levels.front().level, hi = f.levels.back().level;
  gui::ChartSeries curve;
  curve.label = "ML fit";
  curve.color_rgb = 0xd62728;
  for (int i = 0; i <= 200; ++i) {
    const double x = lo + (hi - lo) * i / 200.0;
    curve.x.push_back(x);
    curve.y.push_back(stats::psychometric_value(f.sigmoid, f.alpha, f.beta, f.guess, f.lapse, x));
  }
  chart.series.push_back(curve);
  gui::ChartSeries threshold;
  threshold.label = "threshold";
  threshold.color_rgb = 0x2ca02c;
  threshold.x = {f.threshold, f.threshold};
  threshold.y = {0.0, f.threshold_proportion};
  chart.series.push_back(threshold);
  if (std::isfinite(f.threshold_ci.low)) {
    gui::ChartSeries ci;
    ci.label = "95 % bootstrap interval";
    ci.color_rgb = 0x2ca02c;
    ci.width_px = 4;
    ci.x = {f.threshold_ci.low, f.threshold_ci.high};
    ci.y = {f.threshold_proportion, f.threshold_proportion};
    chart.series.push_back(ci);
  }
  gui::write_chart_png(chart, path);
}

void plot_tracks(const std::vector<ThresholdTrialRow>& rows, const std::filesystem::path& dir,
                 std::vector<std::string>& written) {
  std::map<std::int64_t, std::map<std::string, std::vector<const ThresholdTrialRow*>>> sessions;
  for (const auto& r : rows) sessions[r.session_id][r.trial.track_name].push_back(&r);
  for (const auto& [session, tracks] : sessions) {
    gui::Chart chart;
    chart.title = "Adaptive tracks, session " + std::to_string(session);
    chart.x_label = "trial of the track";
    chart.y_label = "level (increment, kPa)";
    for (const auto& [name, trials] : tracks) {
      gui::ChartSeries line, reversals;
      line.label = name;
      reversals.label = name + " reversals";
      reversals.style = gui::ChartSeries::Style::points;
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
    const auto path = dir / ("track_session" + std::to_string(session) + ".png");
    gui::write_chart_png(chart, path);
    written.push_back(path.string());
  }
}
#endif

void run(const Args& a) {
  stats::PsychometricOptions o;
  const auto sigmoid = stats::sigmoid_from_string(a.sigmoid);
  if (!sigmoid) throw InputError("command line", "--sigmoid", "cumulative-gaussian, logistic or weibull");
  o.sigmoid = *sigmoid;
  o.bootstrap = a.bootstrap;
  o.seed = a.seed;
  o.confidence = a.confidence;
  o.guess_max = a.guess_max;
  o.lapse_max = a.lapse_max;
  o.threshold_at = a.threshold_at;
  auto rate = [](const std::string& text, const std::string& flag) -> std::optional<double> {
    if (text == "fit") return std::nullopt;
    double v = 0;
    if (!parse_finite_number(text, v) || v < 0 || v >= 1) throw InputError("command line", flag, "a rate in [0, 1) or 'fit', got '" + text + "'");
    return v;
  };
  const bool database = is_sqlite(a.file);
  std::vector<ThresholdTrialRow> rows;
  std::vector<Group> groups;
  std::string guess = a.guess;
  if (database) {
    rows = database_rows(a.file);
    groups = groups_from_database(a, rows);
    // Threshold trials' "correct" is a 2AFC proportion correct unless the protocol was yes/no.
    if (guess.empty()) guess = (a.response.empty() || a.response == "correct") ? "0.5" : "0";
  } else {
    groups = groups_from_csv(a);
    if (guess.empty()) guess = "0";
  }
  o.guess = rate(guess, "--guess");
  o.lapse = rate(a.lapse, "--lapse");

  stats::Report report;
  report["test"] = "psychometric function, maximum likelihood (Ceres), parametric bootstrap";
  report["convention"] =
      "psi = guess + (1 - guess - lapse) F; threshold at F = 0.5 (psignifit/quickpsy default) or at psi = "
      "--threshold-at; slope dpsi/dx at the threshold; JND x(F=.75) - x(F=.5); percentile bootstrap intervals; "
      "deviance GOF p = share of bootstrap deviances >= observed";
  report["file"] = a.file;
  report["level"] = database && a.level.empty() ? "level_kPa" : a.level;
  report["response"] = database && a.response.empty() ? "correct" : a.response;
  report["seed"] = a.seed;
  report["groups"] = stats::Report::array();
  std::vector<std::string> plots;
  for (const Group& g : groups) {
    stats::PsychometricFit fit;
    try {
      fit = stats::fit_psychometric(g.counts, o);
    } catch (const stats::StatisticsError& e) {
      throw InputError(a.file, "group '" + g.label + "'", e.what());
    }
    stats::Report one;
    one["group"] = g.label;
    one.update(fit_report(fit, a.confidence));
    report["groups"].push_back(std::move(one));
    if (!a.plot.empty()) {
#ifdef PALPRIG_HAVE_GUI
      std::filesystem::create_directories(a.plot);
      const auto path = std::filesystem::path(a.plot) / ("psychometric_" + file_label(g.label) + ".png");
      plot_fit(g, fit, report["level"].get<std::string>(), path);
      plots.push_back(path.string());
#endif
    }
  }
  if (!a.plot.empty()) {
#ifdef PALPRIG_HAVE_GUI
    if (database) plot_tracks(rows, a.plot, plots);
    report["plots"] = plots;
#else
    throw InputError("--plot", a.plot, "a build with the chart drawing (configure with -DPALPRIG_GUI=ON; needs Qt6)");
#endif
  }
  if (a.json) std::cout << report.dump(2) << "\n";
  else std::cout << stats::render_text(report);
}

}  // namespace

void register_psychometric_command(CLI::App& stats_app) {
  auto a = std::make_shared<Args>();
  auto* sub = stats_app.add_subcommand(
      "psychometric",
      "Psychometric function fit (cumulative Gaussian, logistic, Weibull) by maximum likelihood: threshold, slope, "
      "JND with parametric-bootstrap intervals, deviance and its bootstrap p. Conventions of quickpsy (ML, "
      "threshold at F = 0.5 or a given proportion) and psignifit (threshold at F = 0.5, GOF by deviance)");
  sub->add_option("file", a->file, "CSV (per trial, or per level with --n) or a trial database")->required();
  sub->add_option("--level", a->level, "Stimulus level column (database default: level_kPa)");
  sub->add_option("--response", a->response, "Response column: 0/1 per trial, or the count of yes/correct with --n "
                                              "(database default: correct)");
  sub->add_option("--n", a->n, "CSV with counts per level: the column with the number of trials");
  sub->add_option("--by", a->by, "Group column: one fit per group (database: track_name, fingers, participant, session_id)");
  sub->add_option("--sigmoid", a->sigmoid, "cumulative-gaussian (default), logistic or weibull")
      ->check(CLI::IsMember({"cumulative-gaussian", "logistic", "weibull"}));
  sub->add_option("--guess", a->guess, "Guess rate, fixed (0 yes/no, 0.5 2AFC) or 'fit'; default 0 for a CSV, 0.5 for "
                                       "a database's 'correct' column");
  sub->add_option("--lapse", a->lapse, "Lapse rate, fixed or 'fit' (default: fitted within [0, --lapse-max])")->default_val("fit");
  sub->add_option("--guess-max", a->guess_max, "Upper bound of a fitted guess rate")->default_val(0.5)->check(CLI::Range(0.001, 0.999));
  sub->add_option("--lapse-max", a->lapse_max, "Upper bound of a fitted lapse rate")->default_val(0.1)->check(CLI::Range(0.001, 0.999));
  sub->add_option("--threshold-at", a->threshold_at, "Threshold at this proportion of psi (default: F = 0.5, the PSE)")
      ->check(CLI::Range(0.001, 0.999));
  sub->add_option("--bootstrap", a->bootstrap, "Parametric bootstrap resamples (0: none)")->default_val(1000)->check(CLI::Range(0, 1000000));
  sub->add_option("--seed", a->seed, "Seed of the bootstrap")->default_val(1);
  sub->add_option("--confidence", a->confidence, "Confidence level of the intervals")->default_val(0.95)->check(CLI::Range(0.5, 0.9999));
  sub->add_option("--plot", a->plot, "Folder for PNG plots: data and fit per group; a database's staircase tracks");
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] { run(*a); });
}
