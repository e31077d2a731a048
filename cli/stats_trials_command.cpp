// palprig stats trials DB: scores of a trial store per group (store/trial_summary) with paper
// 002's tests between conditions (store/condition_comparisons), and every other task kind's
// statistics, printed as an aligned table, CSV or JSON.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/stats_printing.hpp"
#include "store/trial_store.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"

using namespace palprig;

void register_stats_trials(CLI::App* stats_app) {
  struct Args {
    std::string db, by = "condition", format = "table", rt_test = "student";
    bool json = false, include_practice = false;
    double confidence = 0.95;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "trials",
      "Scores of a trial database: TP/FN/TN/FP per finger value (discrimination) or per tumor "
      "(localisation), Se, Sp, PPV, ACC (paper 002 eq. 5-8) with Wilson 95 % intervals (no continuity "
      "correction), mean and sd of response times, and between conditions paper 002's tests: response times by "
      "Student's t-test (or --rt-test welch), one value per answered trial, and each measure by the combined "
      "interval of eq. 10; threshold stores: each track's threshold; pulse stores: hit rates; practice trials left "
      "out");
  sub->add_option("db", a->db,
                  "Trial store written by palprig experiment run: an SQLite file or postgresql://user@host:port/dbname")
      ->required();
  sub->add_option("--by", a->by,
                  "Group by a comma list of: condition, participant, finger, tumor, combination, session "
                  "(empty: everything in one row)")
      ->default_val("condition");
  sub->add_option("--format", a->format, "table, csv or json")
      ->check(CLI::IsMember({"table", "csv", "json"}))
      ->default_val("table");
  sub->add_flag("--json", a->json, "Same as --format json");
  sub->add_flag("--include-practice", a->include_practice, "Score practice trials too");
  sub->add_option("--rt-test", a->rt_test,
                  "Test of response times between conditions: student (pooled variance, paper 002; scipy ttest_ind) "
                  "or welch (R t.test's default)")
      ->check(CLI::IsMember({"student", "welch"}))
      ->default_val("student");
  sub->add_option("--confidence", a->confidence, "Confidence level of the Wilson intervals")
      ->default_val(0.95)
      ->check(cli::kConfidenceLevel);
  sub->callback([a] {
    SummaryOptions options;
    options.by = parse_summary_keys(a->by);
    options.include_practice = a->include_practice;
    options.confidence = a->confidence;
    const auto store = open_trial_store(a->db, TrialStore::Access::read_only);
    // Pulse-localisation trials first, then the rest: one library call, which the
    // GUI's statistics.json export makes too.
    std::cout << stats_trials_text(*store, options, a->json ? "json" : a->format,
                                   a->rt_test == "welch" ? ResponseTimeTest::welch : ResponseTimeTest::student);
  });
}
