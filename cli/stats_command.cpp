// palprig stats: the statistics of papers 002, 000 and 003 on the command line. Each
// subcommand reads its input, calls statistics/statistics_*, and prints aligned text or, with
// --json, one JSON object. Every help text names the convention, matching R / scipy defaults.
// This file: proportions and t-tests, and the registration of every stats subcommand (rank
// tests, correlation and descriptions in stats_rank_command.cpp, trial scores in
// stats_trials_command.cpp).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/psychometric_command.hpp"
#include "cli/stats_printing.hpp"
#include "statistics/csv_groups.hpp"
#include "statistics/csv_table.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_report.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"
#include "core/input_error.hpp"

using namespace palprig;
using namespace palprig::cli;

void register_stats_rank_tests(CLI::App* stats_app);
void register_stats_trials(CLI::App* stats_app);
void register_stats_learning(CLI::App* stats_app);

namespace {

void register_proportion(CLI::App* stats_app) {
  struct Args {
    std::int64_t k = 0, n = 0;
    double confidence = 0.95;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub =
      stats_app->add_subcommand("proportion",
                                "k/n with its Wilson score interval (paper 002 eq. 9), no continuity correction: "
                                "statsmodels proportion_confint(method='wilson'), R prop.test(correct=FALSE)");
  sub->add_option("--k", a->k, "Successes")->required();
  sub->add_option("--n", a->n, "Trials")->required();
  sub->add_option("--confidence", a->confidence, "Confidence level")->default_val(0.95)->check(kConfidenceLevel);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] {
    print(refuse_bad_data("command line", "--k/--n",
                          [&] { return stats::to_report(stats::wilson_interval(a->k, a->n, a->confidence)); }),
          a->json);
  });
}

void register_compare_proportions(CLI::App* stats_app) {
  struct Args {
    std::int64_t k1 = 0, n1 = 0, k2 = 0, n2 = 0;
    double confidence = 0.95;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "compare-proportions",
      "p1 - p2 with paper 002's combined interval (eq. 10, Wallis/Newcombe from Wilson bounds: "
      "CI = sqrt((P1-p1)^2 + (P2-p2)^2), significant if |p1-p2| > CI) and Newcombe's hybrid score interval");
  sub->add_option("--k1", a->k1, "Successes in the first sample")->required();
  sub->add_option("--n1", a->n1, "Size of the first sample")->required();
  sub->add_option("--k2", a->k2, "Successes in the second sample")->required();
  sub->add_option("--n2", a->n2, "Size of the second sample")->required();
  sub->add_option("--confidence", a->confidence, "Confidence level of the Wilson bounds")
      ->default_val(0.95)
      ->check(kConfidenceLevel);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] {
    print(refuse_bad_data(
              "command line", "--k1/--n1/--k2/--n2",
              [&] { return stats::to_report(stats::compare_proportions(a->k1, a->n1, a->k2, a->n2, a->confidence)); }),
          a->json);
  });
}

void register_ttest(CLI::App* stats_app) {
  struct Args {
    std::string file, column, by, paired_with;
    std::vector<std::string> groups;
    double against = 0, confidence = 0.95;
    bool student = false, welch = false, json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "ttest",
      "Two-sided t-test on a CSV column: two groups (--by; Welch by default as R t.test, --student for "
      "pooled variance as scipy ttest_ind and paper 002), paired (--paired-with, R t.test paired=TRUE), "
      "or one sample (--against, R t.test mu=)");
  sub->add_option("file", a->file, "CSV file with a header row")->required();
  sub->add_option("--column", a->column, "Numeric column tested")->required();
  auto* by = sub->add_option("--by", a->by, "Group column (two groups)");
  auto* paired = sub->add_option("--paired-with", a->paired_with, "Second numeric column, paired row by row");
  auto* against = sub->add_option("--against", a->against, "Hypothesised mean for a one-sample test");
  by->excludes(paired)->excludes(against);
  paired->excludes(against);
  sub->add_option("--groups", a->groups, "The two group labels to compare, in this order (default: the only two)")
      ->delimiter(',')
      ->needs(by);
  auto* student = sub->add_flag("--student", a->student, "Pooled variance, df = n1 + n2 - 2")->needs(by);
  sub->add_flag("--welch", a->welch, "Unequal variances, Welch-Satterthwaite df (default)")
      ->needs(by)
      ->excludes(student);
  sub->add_option("--confidence", a->confidence, "Confidence level of the interval")
      ->default_val(0.95)
      ->check(kConfidenceLevel);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a, by, paired, against] {
    if (!*by && !*paired && !*against)
      throw InputError("command line", "ttest", "one of --by, --paired-with or --against");
    const CsvTable table = CsvTable::read(a->file);
    stats::Report report;
    // Said before the result: a long file (several rows per trial) or practice rows inflate n.
    const std::vector<std::string> warnings = one_value_per_trial_warnings(table);
    for (const std::string& w : warnings) std::cerr << "palprig: warning: " << w << "\n";
    if (*by) {
      const auto groups = two_groups(table, a->column, a->by, a->groups);
      report = refuse_bad_data(a->file, "column '" + a->column + "'", [&] {
        return stats::to_report(
            stats::two_sample_t_test(groups[0].values, groups[1].values, a->student, a->confidence));
      });
      report["x"] = groups[0].label;
      report["y"] = groups[1].label;
    } else if (*paired) {
      const auto x = table.numbers(a->column);
      const auto y = table.numbers(a->paired_with);
      report = refuse_bad_data(a->file, "columns '" + a->column + "', '" + a->paired_with + "'",
                               [&] { return stats::to_report(stats::paired_t_test(x, y, a->confidence)); });
    } else {
      const auto x = table.numbers(a->column);
      report = refuse_bad_data(a->file, "column '" + a->column + "'", [&] {
        return stats::to_report(stats::one_sample_t_test(x, a->against, a->confidence));
      });
    }
    if (!warnings.empty() && a->json) report["warnings"] = warnings;  // text: on standard error only
    print(report, a->json);
  });
}

}  // namespace

void register_stats_command(CLI::App& app) {
  auto* stats_app = app.add_subcommand("stats",
                                       "Statistics of papers 002, 000 and 003: proportions, t, rank and "
                                       "correlation tests, descriptions, per-trial scores of a trial database");
  stats_app->require_subcommand(1);
  register_proportion(stats_app);
  register_compare_proportions(stats_app);
  register_ttest(stats_app);
  register_stats_rank_tests(stats_app);
  register_stats_trials(stats_app);
  register_stats_learning(stats_app);
  register_psychometric_command(*stats_app);  // stats psychometric
}
