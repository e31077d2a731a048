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
#include <iostream>
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
#include "charts/psychometric_charts.hpp"

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

std::string file_label(const std::string& text) {
  std::string s;
  for (char c : text) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

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
      const auto path = std::filesystem::path(a.plot) / ("psychometric_" + file_label(g.label) + ".png");
      charts::write_chart_png(charts::psychometric_chart(g.label, fit, report["level"].get<std::string>()), path);
      plots.push_back(path.string());
    }
  }
  if (!a.plot.empty()) {
    if (database) {
      const auto tracks = charts::write_track_charts(rows, a.plot);
      plots.insert(plots.end(), tracks.begin(), tracks.end());
    }
    report["plots"] = plots;
  }
  if (a.json)
    std::cout << report.dump(2) << "\n";
  else
    std::cout << stats::render_text(report);
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
  sub->add_option("--plot", a->plot, "Folder for PNG plots: data and fit per group; a database's staircase tracks");
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] { run(*a); });
}
