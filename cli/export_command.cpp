// palprig export DB --format csv|bids --out DIR: the trial database as files analysts open in
// R, Python or a spreadsheet (long CSV), or as BIDS behavioural files with JSON sidecars.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "store/trial_export.hpp"
#include "store/trial_store.hpp"
#include "store/trial_summary.hpp"
#include "models/parse_error.hpp"
#include "charts/trial_charts.hpp"

using namespace palprig;

void register_export_command(CLI::App& app) {
  struct Args {
    std::string db, format = "csv", out;
    bool no_practice = false;
    std::string plot_dir;
  };
  auto a = std::make_shared<Args>();
  auto* sub = app.add_subcommand(
      "export", "Export a trial database: --format csv writes trials_long.csv (one row per finger value or tumor) and "
                "marks.csv; --format bids writes sub-<id>/beh/sub-<id>_task-<task>_beh.tsv with JSON sidecars");
  sub->add_option("db", a->db, "Trial store written by palprig experiment run: an SQLite file or postgresql://user@host:port/dbname")->required();
  sub->add_option("--format", a->format, "csv or bids")->check(CLI::IsMember({"csv", "bids"}))->default_val("csv");
  sub->add_option("--out", a->out, "Output folder (created when missing)")->required();
  sub->add_flag("--no-practice", a->no_practice, "Leave practice trials out (they are marked by a column otherwise)");
  sub->add_option("--plot", a->plot_dir,
                  "Also write DIR/measures_by_condition.png: Se, Sp, PPV, ACC per condition with Wilson 95 % error "
                  "bars (paper 002 fig. 15), practice trials left out as in stats trials");
  sub->callback([a] {
    const auto opened = open_trial_store(a->db, TrialStore::Access::read_only);
    TrialStore& store = *opened;
    ExportOptions options;
    options.include_practice = !a->no_practice;
    const ExportResult r =
        a->format == "bids" ? export_bids(store, a->out, options) : export_long_csv(store, a->out, options);
    std::cout << "palprig export: " << r.trials << " trials from " << a->db << " into " << r.files.size() << " files in "
              << a->out << "\n";
    const std::size_t shown = std::min<std::size_t>(r.files.size(), 8);
    for (std::size_t i = 0; i < shown; ++i) std::cout << "  " << r.files[i].string() << "\n";
    if (shown < r.files.size()) std::cout << "  ... and " << r.files.size() - shown << " more\n";
    if (!a->plot_dir.empty())
      // The chart is a statistic: practice trials are left out, as `stats trials` and the
      // statistics view leave them out (a chart cannot mark them as the data files do).
      std::cout << "  " << charts::plot_measures_by_condition(store, a->plot_dir, false).string() << "\n";
  });
}
