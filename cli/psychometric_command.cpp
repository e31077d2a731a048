// palprig stats psychometric FILE --level COL --response COL [--n COL] [--by COL] [--json]
//   [--plot DIR] [--sigmoid S] [--guess G|fit] [--lapse L|fit] [--threshold-at P]
//   [--bootstrap N] [--seed S]
// FILE is a CSV (one row per trial with a 0/1 response, or one row per level with the count of
// yes/correct answers in --response and the number of trials in --n) or a trial database
// (threshold_trials: level_kPa, correct, response, track_name, fingers, participant). The fit
// is statistics/psychometric_fit.hpp; --plot draws each group's data and curve, and for a
// database every session's staircase tracks.
#include "cli/psychometric_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/input_error.hpp"
#include "statistics/csv_table.hpp"
#include "statistics/psychometric_fit.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_report.hpp"
#include "statistics/psychometric_groups.hpp"
#include "store/threshold_psychometric.hpp"
#include "store/threshold_summary.hpp"
#include "charts/chart_svg.hpp"
#include "charts/psychometric_charts.hpp"

using namespace palprig;

namespace {

struct PsychometricArgs {
  std::string file, level, response, n, by, plot, sigmoid = "cumulative-gaussian", guess, lapse = "fit";
  std::optional<double> threshold_at;
  double guess_max = 0.5, lapse_max = 0.1, confidence = 0.95;
  int bootstrap = 1000;
  std::uint64_t seed = 1;
  bool json = false, levels = false, svg = false;
};

std::string file_label(const std::string& text) {
  std::string s;
  for (char c : text) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

// A chart as STEM.png, and STEM.svg beside it with --svg.
void write_plot(const charts::Chart& chart, const std::filesystem::path& stem, bool svg,
                std::vector<std::string>& plots) {
  const auto png = std::filesystem::path(stem.string() + ".png");
  charts::write_chart_png(chart, png);
  plots.push_back(png.string());
  if (svg) {
    const auto file = std::filesystem::path(stem.string() + ".svg");
    charts::write_chart_svg(chart, file);
    plots.push_back(file.string());
  }
}

// One number for the table: 3 significant digits, "n/a" for NaN (no bootstrap, no interval).
std::string figure(const stats::Report& x) {
  if (!x.is_number()) return "n/a";
  const double v = x.get<double>();
  if (!std::isfinite(v)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// A guess or lapse rate: three decimals (a fitted lapse of 2e-13 is 0.000).
std::string rate(const stats::Report& x) {
  if (!x.is_number()) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x.get<double>());
  return buf;
}

std::string with_interval(const stats::Report& g, const char* value, const char* interval) {
  std::string v = figure(g[value]);
  const auto& ci = g[interval];
  if (!ci.is_object() || !ci["low"].is_number() || !std::isfinite(ci["low"].get<double>())) return v;
  return v + " [" + figure(ci["low"]) + ", " + figure(ci["high"]) + "]";
}

std::string aligned(const std::vector<std::vector<std::string>>& cells) {
  std::vector<std::size_t> width(cells[0].size(), 0);
  for (const auto& line : cells)
    for (std::size_t i = 0; i < line.size(); ++i) width[i] = std::max(width[i], line[i].size());
  std::string out;
  for (const auto& line : cells) {
    out += "  ";
    for (std::size_t i = 0; i < line.size(); ++i)
      out += line[i] + (i + 1 < line.size() ? std::string(width[i] - line[i].size() + 2, ' ') : "");
    out += "\n";
  }
  return out;
}

// The fits as a person reads them: what was fitted and where each threshold is taken, one row
// per group, then (--levels) each group's counts per level.
std::string psychometric_text(const stats::Report& r, bool levels) {
  std::string out = "palprig stats psychometric: " + r["file"].get<std::string>() + ", " +
                    r["sigmoid"].get<std::string>() + " by maximum likelihood, " + r["fitted"].get<std::string>() +
                    "\n";
  out += "  threshold: " + r["threshold_rule"].get<std::string>() + "\n";
  const std::string level = r["level"].get<std::string>();
  // A database's levels are kPa; a CSV's are in its column's unit.
  const bool kPa = level == "level_kPa";
  const std::string in = kPa ? " kPa" : " (" + level + ")";
  std::vector<std::vector<std::string>> cells{{"group", "trials", "levels", "threshold" + in + " [CI]", "psi there",
                                               kPa ? "slope per kPa [CI]" : "slope per unit [CI]", "JND" + in + " [CI]",
                                               "guess", "lapse", "deviance (df)", "GOF p"}};
  for (const auto& g : r["groups"]) {
    cells.push_back({g["group"].get<std::string>(), std::to_string(g["trials"].get<int>()),
                     std::to_string(g["levels"].size()), with_interval(g, "threshold", "threshold_ci"),
                     figure(g["threshold_proportion"]), with_interval(g, "slope", "slope_ci"),
                     with_interval(g, "jnd", "jnd_ci"),
                     rate(g["guess"]) + (g["guess_fitted"].get<bool>() ? " fit" : ""),
                     rate(g["lapse"]) + (g["lapse_fitted"].get<bool>() ? " fit" : ""),
                     figure(g["deviance"]) + " (" + std::to_string(g["deviance_df"].get<int>()) + ")",
                     g["bootstrap"].get<int>() > 0 ? figure(g["gof_p"]) : std::string("n/a")});
  }
  out += aligned(cells);
  if (r.contains("session_thresholds")) out += "  note: " + r["session_thresholds"].get<std::string>() + "\n";
  if (levels) {
    for (const auto& g : r["groups"]) {
      out += "  " + g["group"].get<std::string>() + ", trials per level:\n";
      std::vector<std::vector<std::string>> rows{{level, "n", "yes/correct", "proportion"}};
      for (const auto& c : g["levels"])
        rows.push_back({figure(c["level"]), std::to_string(c["n"].get<int>()), std::to_string(c["k"].get<int>()),
                        figure(c["proportion"])});
      out += aligned(rows);
    }
  }
  if (r.contains("plots"))
    for (const auto& p : r["plots"]) out += "  " + p.get<std::string>() + "\n";
  return out;
}

// A threshold database's own estimates: where each track's rule converges (1-up 3-down: 79.4 %
// correct), which is not where the fit's default threshold lies (F = 0.5: 75 % in 2AFC).
std::string session_threshold_note(const std::string& file, const std::optional<double>& threshold_at) {
  SqliteTrialStore store(file, TrialStore::Access::read_only);
  std::map<std::string, double> targets;
  for (const ThresholdTrackSummary& t : summarise_threshold_tracks(store))
    targets[t.track] = t.estimate.target_probability;
  if (targets.empty()) return "";
  std::string list;
  for (const auto& [track, p] : targets) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s%s at %.1f %%", list.empty() ? "" : ", ", track.c_str(), 100 * p);
    list += buf;
  }
  std::string note =
      "the sessions' own thresholds (palprig stats trials, the export's estimate_kPa) are each "
      "track's estimate where its rule converges: " +
      list;
  if (!threshold_at) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "; --threshold-at %.3f takes the fit's threshold there", targets.begin()->second);
    note += buf;
  }
  return note;
}

void run(const PsychometricArgs& a) {
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
    if (!parse_finite_number(text, v) || v < 0 || v >= 1)
      throw InputError("command line", flag, "a rate in [0, 1) or 'fit', got '" + text + "'");
    return v;
  };
  const bool database = is_sqlite_file(a.file);
  const stats::PsychometricColumns columns{a.level, a.response, a.n, a.by};
  std::vector<ThresholdTrialRow> rows;
  std::vector<stats::PsychometricGroup> groups;
  std::string guess = a.guess;
  if (database) {
    rows = read_threshold_trials(a.file);
    groups = threshold_psychometric_groups(rows, columns, a.file);
    // Threshold trials' "correct" is a 2AFC proportion correct unless the protocol was yes/no.
    if (guess.empty()) guess = (a.response.empty() || a.response == "correct") ? "0.5" : "0";
  } else {
    groups = stats::psychometric_groups(CsvTable::read(a.file), columns);
    if (guess.empty()) guess = "0";
  }
  o.guess = rate(guess, "--guess");
  o.lapse = rate(a.lapse, "--lapse");

  stats::Report report;
  report["test"] = "psychometric function, maximum likelihood (Ceres), parametric bootstrap";
  report["sigmoid"] = stats::to_string(o.sigmoid);
  report["convention"] =
      "psi = guess + (1 - guess - lapse) F; threshold at F = 0.5 (psignifit/quickpsy default) or at psi = "
      "--threshold-at; slope dpsi/dx at the threshold; JND x(F=.75) - x(F=.5); percentile bootstrap intervals; "
      "deviance GOF p = share of bootstrap deviances >= observed";
  report["file"] = a.file;
  report["level"] = database && a.level.empty() ? "level_kPa" : a.level;
  report["response"] = database && a.response.empty() ? "correct" : a.response;
  report["seed"] = a.seed;
  {
    char buf[256];
    const std::string guess_text =
        o.guess ? "guess " + figure(*o.guess) : "guess fitted in [0, " + figure(a.guess_max) + "]";
    const std::string lapse_text =
        o.lapse ? "lapse " + figure(*o.lapse) : "lapse fitted in [0, " + figure(a.lapse_max) + "]";
    std::snprintf(buf, sizeof buf, "%s, %s, %d bootstrap resamples (seed %llu), %s %% intervals", guess_text.c_str(),
                  lapse_text.c_str(), o.bootstrap, static_cast<unsigned long long>(a.seed),
                  figure(100 * a.confidence).c_str());
    report["fitted"] = buf;
  }
  report["threshold_rule"] =
      a.threshold_at
          ? "the level where psi = " + figure(*a.threshold_at) + " (--threshold-at)"
          : std::string(
                "the level where F = 0.5 (the PSE; psignifit's and quickpsy's default): psi = guess + (1 - "
                "guess - lapse) / 2 there, 0.75 in 2AFC without lapses; --threshold-at P takes it where psi = P");
  if (database) {
    const std::string note = session_threshold_note(a.file, a.threshold_at);
    if (!note.empty()) report["session_thresholds"] = note;
  }
  report["groups"] = stats::Report::array();
  std::vector<std::string> plots;
  for (const stats::PsychometricGroup& g : groups) {
    stats::PsychometricFit fit;
    try {
      fit = stats::fit_psychometric(g.counts, o);
    } catch (const stats::StatisticsError& e) {
      throw InputError(a.file, "group '" + g.label + "'", e.what());
    }
    stats::Report one;
    one["group"] = g.label;
    one.update(stats::psychometric_report(fit, a.confidence));
    report["groups"].push_back(std::move(one));
    if (!a.plot.empty()) {
      std::filesystem::create_directories(a.plot);
      const charts::Chart chart =
          charts::psychometric_chart(g.label, fit, report["level"].get<std::string>(),
                                     o.guess && *o.guess > 0 ? "correct" : report["response"].get<std::string>());
      write_plot(chart, std::filesystem::path(a.plot) / ("psychometric_" + file_label(g.label)), a.svg, plots);
    }
  }
  if (!a.plot.empty()) {
    if (database) {
      SqliteTrialStore store(a.file, TrialStore::Access::read_only);
      for (const charts::SessionTrackChart& c : charts::track_charts(rows, summarise_threshold_tracks(store)))
        write_plot(c.chart, std::filesystem::path(a.plot) / ("track_session" + std::to_string(c.session)), a.svg,
                   plots);
    }
    report["plots"] = plots;
  }
  if (a.json)
    std::cout << report.dump(2) << "\n";
  else
    std::cout << psychometric_text(report, a.levels);
}

}  // namespace

void register_psychometric_command(CLI::App& stats_app) {
  auto a = std::make_shared<PsychometricArgs>();
  auto* sub = stats_app.add_subcommand(
      "psychometric",
      "Psychometric function fit (cumulative Gaussian, logistic, Weibull) by maximum likelihood: threshold, slope, "
      "JND with parametric-bootstrap intervals, deviance and its bootstrap p. Conventions of quickpsy (ML, "
      "threshold at F = 0.5 or a given proportion) and psignifit (threshold at F = 0.5, GOF by deviance)");
  sub->add_option("file", a->file, "CSV (per trial, or per level with --n) or a trial database")->required();
  sub->add_option("--level", a->level, "Stimulus level column (database default: level_kPa)");
  sub->add_option("--response", a->response,
                  "Response column: 0/1 per trial, or the count of yes/correct with --n "
                  "(database default: correct)");
  sub->add_option("--n", a->n, "CSV with counts per level: the column with the number of trials");
  sub->add_option("--by", a->by,
                  "Group column: one fit per group (database: track_name, fingers, participant, session_id)");
  sub->add_option("--sigmoid", a->sigmoid, "cumulative-gaussian (default), logistic or weibull")
      ->check(CLI::IsMember({"cumulative-gaussian", "logistic", "weibull"}));
  sub->add_option("--guess", a->guess,
                  "Guess rate, fixed (0 yes/no, 0.5 2AFC) or 'fit'; default 0 for a CSV, 0.5 for "
                  "a database's 'correct' column");
  sub->add_option("--lapse", a->lapse, "Lapse rate, fixed or 'fit' (default: fitted within [0, --lapse-max])")
      ->default_val("fit");
  sub->add_option("--guess-max", a->guess_max, "Upper bound of a fitted guess rate")
      ->default_val(0.5)
      ->check(CLI::Range(0.001, 0.999));
  sub->add_option("--lapse-max", a->lapse_max, "Upper bound of a fitted lapse rate")
      ->default_val(0.1)
      ->check(CLI::Range(0.001, 0.999));
  sub->add_option("--threshold-at", a->threshold_at, "Threshold at this proportion of psi (default: F = 0.5, the PSE)")
      ->check(CLI::Range(0.001, 0.999));
  sub->add_option("--bootstrap", a->bootstrap, "Parametric bootstrap resamples (0: none)")
      ->default_val(1000)
      ->check(CLI::Range(0, 1000000));
  sub->add_option("--seed", a->seed, "Seed of the bootstrap")->default_val(1);
  sub->add_option("--confidence", a->confidence, "Confidence level of the intervals")
      ->default_val(0.95)
      ->check(CLI::Range(0.5, 0.9999));
  sub->add_option("--plot", a->plot,
                  "Folder for the charts (PNG at print size): data and fit per group; a database's staircase tracks");
  sub->add_flag("--svg", a->svg, "With --plot: an SVG beside every PNG");
  sub->add_flag("--json", a->json, "Print one JSON object (every group's counts per level, intervals, timings)");
  sub->add_flag("--levels", a->levels, "Table: each group's trials and answers per level too");
  sub->callback([a] { run(*a); });
}
