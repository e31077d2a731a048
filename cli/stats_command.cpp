// palprig stats: the statistics of papers 002, 000 and 003 on the command line. Each
// subcommand reads its input, calls experiments/statistics_*, and prints aligned text or, with
// --json, one JSON object. Every help text names the convention, matching R / scipy defaults.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "statistics/csv_groups.hpp"
#include "statistics/csv_table.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_report.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"
#include "models/parse_error.hpp"

using namespace palprig;

namespace {

void print(const stats::Report& report, bool json) {
  if (json) std::cout << report.dump(2) << "\n";
  else std::cout << stats::render_text(report);
}

// Run a computation; a StatisticsError (too few values, constant data) becomes a refusal of
// the input that names the file and the column.
template <class Compute>
stats::Report refuse_bad_data(const std::string& file, const std::string& where, Compute compute) {
  try {
    return compute();
  } catch (const stats::StatisticsError& e) {
    throw InputError(file, where, e.what());
  }
}

stats::RankOptions rank_options(const std::string& method, bool no_correction) {
  stats::RankOptions o;
  o.method = method == "exact" ? stats::RankMethod::exact
             : method == "normal" ? stats::RankMethod::normal
                                  : stats::RankMethod::automatic;
  o.continuity_correction = !no_correction;
  return o;
}

void add_rank_options(CLI::App* sub, std::string& method, bool& no_correction) {
  sub->add_option("--method", method,
                  "auto: exact p when every sample has < 50 values and there are no ties (or zero differences), "
                  "else normal approximation (R wilcox.test default); exact; normal")
      ->check(CLI::IsMember({"auto", "exact", "normal"}))
      ->default_val("auto");
  sub->add_flag("--no-correction", no_correction,
                "Normal approximation without the 0.5 continuity correction (SPSS; scipy wilcoxon default). "
                "Default: corrected, as R wilcox.test and scipy mannwhitneyu");
}

void register_proportion(CLI::App* stats_app) {
  struct Args { std::int64_t k = 0, n = 0; double confidence = 0.95; bool json = false; };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "proportion", "k/n with its Wilson score interval (paper 002 eq. 9), no continuity correction: "
                    "statsmodels proportion_confint(method='wilson'), R prop.test(correct=FALSE)");
  sub->add_option("--k", a->k, "Successes")->required();
  sub->add_option("--n", a->n, "Trials")->required();
  sub->add_option("--confidence", a->confidence, "Confidence level")->default_val(0.95);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] {
    print(refuse_bad_data("command line", "--k/--n", [&] { return stats::to_report(stats::wilson_interval(a->k, a->n, a->confidence)); }),
          a->json);
  });
}

void register_compare_proportions(CLI::App* stats_app) {
  struct Args { std::int64_t k1 = 0, n1 = 0, k2 = 0, n2 = 0; double confidence = 0.95; bool json = false; };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "compare-proportions",
      "p1 - p2 with paper 002's combined interval (eq. 10, Wallis/Newcombe from Wilson bounds: "
      "CI = sqrt((P1-p1)^2 + (P2-p2)^2), significant if |p1-p2| > CI) and Newcombe's hybrid score interval");
  sub->add_option("--k1", a->k1, "Successes in the first sample")->required();
  sub->add_option("--n1", a->n1, "Size of the first sample")->required();
  sub->add_option("--k2", a->k2, "Successes in the second sample")->required();
  sub->add_option("--n2", a->n2, "Size of the second sample")->required();
  sub->add_option("--confidence", a->confidence, "Confidence level of the Wilson bounds")->default_val(0.95);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a] {
    print(refuse_bad_data("command line", "--k1/--n1/--k2/--n2",
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
      "ttest", "Two-sided t-test on a CSV column: two groups (--by; Welch by default as R t.test, --student for "
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
  sub->add_flag("--welch", a->welch, "Unequal variances, Welch-Satterthwaite df (default)")->needs(by)->excludes(student);
  sub->add_option("--confidence", a->confidence, "Confidence level of the interval")->default_val(0.95);
  sub->add_flag("--json", a->json, "Print one JSON object");
  sub->callback([a, by, paired, against] {
    if (!*by && !*paired && !*against) throw InputError("command line", "ttest", "one of --by, --paired-with or --against");
    const CsvTable table = CsvTable::read(a->file);
    stats::Report report;
    if (*by) {
      const auto groups = two_groups(table, a->column, a->by, a->groups);
      report = refuse_bad_data(a->file, "column '" + a->column + "'", [&] {
        return stats::to_report(stats::two_sample_t_test(groups[0].values, groups[1].values, a->student, a->confidence));
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
      report = refuse_bad_data(a->file, "column '" + a->column + "'",
                               [&] { return stats::to_report(stats::one_sample_t_test(x, a->against, a->confidence)); });
    }
    print(report, a->json);
  });
}

void register_mannwhitney(CLI::App* stats_app) {
  struct Args {
    std::string file, column, by, method = "auto";
    std::vector<std::string> groups;
    bool no_correction = false, json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "mannwhitney", "Mann-Whitney U (Wilcoxon rank-sum), two-sided, average ranks for ties: U, z, p and effect size "
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
    const auto groups = two_groups(table, a->column, a->by, a->groups);
    stats::Report report = refuse_bad_data(a->file, "column '" + a->column + "'", [&] {
      return stats::to_report(stats::mann_whitney(groups[0].values, groups[1].values, rank_options(a->method, a->no_correction)));
    });
    report["group1"] = groups[0].label;
    report["group2"] = groups[1].label;
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
      "wilcoxon", "Wilcoxon signed-rank test, two-sided: one column against a value (e.g. a Likert scale's neutral "
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
  struct Args { std::string file, x, y; double confidence = 0.95; bool json = false; };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "pearson", "Pearson's r with t = r sqrt((n-2)/(1-r^2)), df = n-2, two-sided p and the Fisher z interval "
                 "(R cor.test; scipy pearsonr)");
  sub->add_option("file", a->file, "CSV file with a header row")->required();
  sub->add_option("--x", a->x, "First numeric column")->required();
  sub->add_option("--y", a->y, "Second numeric column")->required();
  sub->add_option("--confidence", a->confidence, "Confidence level of the interval")->default_val(0.95);
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
  struct Args { std::string file, column, by; int quantile_type = 7; bool json = false; };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "describe", "n, mean, sd (n-1), min, quartiles, median, max, IQR of a CSV column, optionally per group. "
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
      for (const auto& g : group_numbers(table, a->column, a->by)) {
        stats::Report one;
        one["group"] = g.label;
        one.update(stats::to_report(stats::describe(g.values, rule), rule));
        report["groups"].push_back(std::move(one));
      }
    }
    print(report, a->json);
  });
}

void register_trials(CLI::App* stats_app) {
  struct Args {
    std::string db, by = "condition", format = "table";
    bool json = false, include_practice = false;
    double confidence = 0.95;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "trials", "Scores of a trial database: TP/FN/TN/FP per finger value (discrimination) or per tumor "
                "(localisation), Se, Sp, PPV, ACC (paper 002 eq. 5-8) with Wilson 95 % intervals (no continuity "
                "correction), mean and sd of response times; practice trials left out");
  sub->add_option("db", a->db, "Trial store written by palprig experiment run: an SQLite file or postgresql://user@host:port/dbname")->required();
  sub->add_option("--by", a->by, "Group by a comma list of: condition, participant, finger, tumor, combination, session "
                                 "(empty: everything in one row)")
      ->default_val("condition");
  sub->add_option("--format", a->format, "table, csv or json")->check(CLI::IsMember({"table", "csv", "json"}))->default_val("table");
  sub->add_flag("--json", a->json, "Same as --format json");
  sub->add_flag("--include-practice", a->include_practice, "Score practice trials too");
  sub->add_option("--confidence", a->confidence, "Confidence level of the Wilson intervals")->default_val(0.95)
      ->check(CLI::Range(0.5, 0.9999));
  sub->callback([a] {
    SummaryOptions options;
    options.by = parse_summary_keys(a->by);
    options.include_practice = a->include_practice;
    options.confidence = a->confidence;
    const auto store = open_trial_store(a->db, TrialStore::Access::read_only);
    const TrialSummary summary = summarise_trials(*store, options);
    const std::string format = a->json ? "json" : a->format;
    if (format == "json") std::cout << summary_json(summary, a->confidence).dump(2) << "\n";
    else if (format == "csv") std::cout << summary_csv(summary);
    else std::cout << summary_table(summary);
  });
}

}  // namespace

void register_stats_command(CLI::App& app) {
  auto* stats_app = app.add_subcommand("stats", "Statistics of papers 002, 000 and 003: proportions, t, rank and "
                                                "correlation tests, descriptions, per-trial scores of a trial database");
  stats_app->require_subcommand(1);
  register_proportion(stats_app);
  register_compare_proportions(stats_app);
  register_ttest(stats_app);
  register_mannwhitney(stats_app);
  register_wilcoxon(stats_app);
  register_pearson(stats_app);
  register_describe(stats_app);
  register_trials(stats_app);
}
