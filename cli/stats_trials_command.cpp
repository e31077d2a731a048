// palprig stats trials DB: scores of a trial store per group (store/trial_summary), printed as
// an aligned table, CSV or JSON.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/stats_printing.hpp"
#include "store/pulse_store.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_store.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"

using namespace palprig;

void register_stats_trials(CLI::App* stats_app) {
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
      ->check(cli::kConfidenceLevel);
  sub->callback([a] {
    SummaryOptions options;
    options.by = parse_summary_keys(a->by);
    options.include_practice = a->include_practice;
    options.confidence = a->confidence;
    const auto store = open_trial_store(a->db, TrialStore::Access::read_only);
    const std::string format = a->json ? "json" : a->format;
    // Issue 13: pulse-localisation trials (their own table, SQLite files only so far) are
    // summarised per condition.
    if (auto* sqlite = dynamic_cast<SqliteTrialStore*>(store.get())) {
      PulseStore pulse(*sqlite, false);
      if (pulse.has_trials()) {
        const auto rows = pulse.summarise(a->confidence);
        if (format == "json") std::cout << pulse_summary_json(rows, a->confidence).dump(2) << "\n";
        else std::cout << pulse_summary_table(rows, a->confidence);
        auto any = sqlite->database().prepare("SELECT count(*) FROM trials");
        if (!any.step() || any.integer(0) == 0) return;
      }
    }
    const TrialSummary summary = summarise_trials(*store, options);
    if (format == "json") std::cout << summary_json(summary, a->confidence).dump(2) << "\n";
    else if (format == "csv") std::cout << summary_csv(summary);
    else std::cout << summary_table(summary);
  });
}
