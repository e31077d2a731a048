// palprig stats mannwhitney|wilcoxon|pearson|describe: rank tests, correlation and descriptions
// of CSV columns (statistics/), printed as text or --json.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
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

namespace {

void register_mannwhitney(CLI::App* stats_app) {
  struct Args {
    std::string file, column, by, method = "auto";
    std::vector<std::string> groups;
    bool no_correction = false, json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "mannwhitney",
      "Mann-Whitney U (Wilcoxon rank-sum), two-sided, average ranks for ties: U, z, p and effect size "
      "r = z / sqrt(N) (papers 000, 003). Defaults of R wilcox.test");
  sub->add_option("file", a->file, "CSV file with a header row")->required();
  sub->add_option("--column", a->column, "Numeric column tested")->required();
  sub->add_option("--by", a->by, "Group column (two groups)")->required();
  sub->add_option("--groups", a->groups, "The two group labels to compare, in this order (default: the only two)")
      ->delimiter(',');
  add_rank_options(sub, a->method, a->no_correction);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] {
    const CsvTable table = CsvTable::read(a->file);
    const std::vector<std::string> warnings = one_value_per_trial_warnings(table);
    for (const std::string& w : warnings) std::cerr << "palprig: warning: " << w << "\n";
    const auto groups = two_groups(table, a->column, a->by, a->groups);
    stats::Report report = refuse_bad_data(a->file, "column '" + a->column + "'", [&] {
      return stats::to_report(
          stats::mann_whitney(groups[0].values, groups[1].values, rank_options(a->method, a->no_correction)));
    });
    report["group1"] = groups[0].label;
    report["group2"] = groups[1].label;
    if (!warnings.empty() && a->json) report["warnings"] = warnings;  // text: on standard error only
    print(report, a->json);
  });
}

void register_wilcoxon(CLI::App* stats_app) {
  struct Args {
    std::string file, column, paired_with, method = "auto";
    double against = 0;
    bool no_correction = false, json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "wilcoxon",
      "Wilcoxon signed-rank test, two-sided: one column against a value (e.g. a Likert scale's neutral "
      "point, paper 003) or paired columns. Zero differences dropped (Wilcoxon's method), average ranks "
      "for ties. Defaults of R wilcox.test");
  sub->add_option("file", a->file, "CSV file with a header row")->required();
  sub->add_option("--column", a->column, "Numeric column tested")->required();
  auto* against = sub->add_option("--against", a->against, "Hypothesised location");
  auto* paired = sub->add_option("--paired-with", a->paired_with, "Second numeric column, paired row by row");
  against->excludes(paired);
  add_rank_options(sub, a->method, a->no_correction);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a, against, paired] {
    if (!*against && !*paired) throw InputError("command line", "wilcoxon", "--against VALUE or --paired-with COLUMN");
    const CsvTable table = CsvTable::read(a->file);
    const auto x = table.numbers(a->column);
    const auto options = rank_options(a->method, a->no_correction);
    stats::Report report;
    if (*paired) {
      const auto y = table.numbers(a->paired_with);
      report = refuse_bad_data(a->file, "columns '" + a->column + "', '" + a->paired_with + "'",
                               [&] { return stats::to_report(stats::wilcoxon_signed_rank_paired(x, y, options)); });
    } else {
      report = refuse_bad_data(a->file, "column '" + a->column + "'",
                               [&] { return stats::to_report(stats::wilcoxon_signed_rank(x, a->against, options)); });
      report["against"] = a->against;
    }
    print(report, a->json);
  });
}

void register_pearson(CLI::App* stats_app) {
  struct Args {
    std::string file, x, y;
    double confidence = 0.95;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "pearson",
      "Pearson's r with t = r sqrt((n-2)/(1-r^2)), df = n-2, two-sided p and the Fisher z interval "
      "(R cor.test; scipy pearsonr)");
  sub->add_option("file", a->file, "CSV file with a header row")->required();
  sub->add_option("--x", a->x, "First numeric column")->required();
  sub->add_option("--y", a->y, "Second numeric column")->required();
  sub->add_option("--confidence", a->confidence, "Confidence level of the interval")
      ->default_val(0.95)
      ->check(kConfidenceLevel);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] {
    const CsvTable table = CsvTable::read(a->file);
    const auto x = table.numbers(a->x);
    const auto y = table.numbers(a->y);
    print(refuse_bad_data(a->file, "columns '" + a->x + "', '" + a->y + "'",
                          [&] { return stats::to_report(stats::pearson(x, y, a->confidence)); }),
          a->json);
  });
}

void register_describe(CLI::App* stats_app) {
  struct Args {
    std::string file, column, by;
    int quantile_type = 7;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "describe",
      "n, mean, sd (n-1), min, quartiles, median, max, IQR of a CSV column, optionally per group. "
      "Quartiles: R type 7 (R quantile() and numpy default) or --quantile-type 6 (SPSS)");
  sub->add_option("file", a->file, "CSV file with a header row")->required();
  sub->add_option("--column", a->column, "Numeric column")->required();
  sub->add_option("--by", a->by, "Group column: one description per group, in order of appearance");
  sub->add_option("--quantile-type", a->quantile_type, "Hyndman-Fan quantile type: 7 (default) or 6")
      ->check(CLI::IsMember({6, 7}))
      ->default_val(7);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] {
    const CsvTable table = CsvTable::read(a->file);
    const auto rule = a->quantile_type == 6 ? stats::QuantileRule::r_type6 : stats::QuantileRule::r_type7;
    stats::Report report;
    report["column"] = a->column;
    if (a->by.empty()) {
      const auto values = table.numbers(a->column);
      report.update(refuse_bad_data(a->file, "column '" + a->column + "'",
                                    [&] { return stats::to_report(stats::describe(values, rule), rule); }));
    } else {
      report["by"] = a->by;
      report["groups"] = stats::Report::array();
      const auto groups = group_numbers(table, a->column, a->by);
      if (groups.empty())
        throw InputError(a->file, "column '" + a->by + "'", "at least one data row to group (the table is empty)");
      for (const auto& g : groups) {
        stats::Report one;
        one["group"] = g.label;
        one.update(refuse_bad_data(a->file, "column '" + a->column + "', group '" + g.label + "'",
                                   [&] { return stats::to_report(stats::describe(g.values, rule), rule); }));
        report["groups"].push_back(std::move(one));
      }
    }
    print(report, a->json);
  });
}

}  // namespace

void register_stats_rank_tests(CLI::App* stats_app) {
  register_mannwhitney(stats_app);
  register_wilcoxon(stats_app);
  register_pearson(stats_app);
  register_describe(stats_app);
}
