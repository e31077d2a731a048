// palprig export DB --format csv|bids --out DIR [--plot DIR [--svg]]: the trial database, every
// task kind in it, as files analysts open in R, Python or a spreadsheet (long CSV), or as BIDS
// behavioural files with JSON sidecars; --plot draws each kind's figures.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "store/trial_export.hpp"
#include "store/trial_store.hpp"
#include "store/trial_summary.hpp"
#include "core/input_error.hpp"
#include "charts/learning_charts.hpp"
#include "charts/store_plots.hpp"

using namespace palprig;

void register_export_command(CLI::App& app) {
  struct Args {
    std::string db, format = "csv", out;
    bool no_practice = false, svg = false;
    std::string plot_dir, name, curriculum;
    std::vector<std::string> authors;
  };
  auto a = std::make_shared<Args>();
  auto* sub = app.add_subcommand(
      "export",
      "Export a trial database, every task kind in it: --format csv writes trials_long.csv (one row per "
      "finger value or tumor) and marks.csv, threshold_trials.csv and pulse_trials.csv (one row per trial), each "
      "when the store holds such trials; --format bids writes sub-<id>/beh/sub-<id>_task-<task>_beh.tsv with "
      "JSON sidecars. A store with no trial to export is refused (exit 2)");
  sub->add_option("db", a->db,
                  "Trial store written by palprig experiment run: an SQLite file or postgresql://user@host:port/dbname")
      ->required();
  sub->add_option("--format", a->format, "csv or bids")->check(CLI::IsMember({"csv", "bids"}))->default_val("csv");
  sub->add_option("--out", a->out, "Output folder (created when missing)")->required();
  sub->add_flag("--no-practice", a->no_practice, "Leave practice trials out (they are marked by a column otherwise)");
  sub->add_option("--plot", a->plot_dir,
                  "Also draw each task kind's figures into DIR: measures_by_condition.png (Se, Sp, PPV, ACC per "
                  "condition with Wilson 95 % error bars, paper 002 fig. 15), track_session<N>.png and "
                  "psychometric_<track>.png (threshold tracks with reversals; fit with bootstrap interval), "
                  "pulse_hits_by_condition.png; practice trials left out as in stats trials");
  sub->add_flag("--svg", a->svg, "With --plot: an SVG beside every PNG");
  sub->add_option("--curriculum", a->curriculum,
                  "With --plot: also each trainee of this curriculum's learning curves "
                  "(learning_<trainee>_<measure>.png, the benchmark line per level) and CUSUM charts "
                  "(cusum_<trainee>.png, lc_cusum_<trainee>.png)");
  sub->add_option("--author", a->authors, "BIDS: an author of the dataset (repeat for each; dataset_description.json)");
  sub->add_option("--name", a->name, "BIDS: the dataset's name (default: palprig trial export)");
  sub->callback([a] {
    const auto opened = open_trial_store(a->db, TrialStore::Access::read_only);
    TrialStore& store = *opened;
    ExportOptions options;
    options.include_practice = !a->no_practice;
    options.authors = a->authors;
    options.dataset_name = a->name;
    if (a->svg && a->plot_dir.empty())
      throw InputError("command line", "--svg", "--plot DIR as well (SVG files go beside its PNGs)");
    if (!a->curriculum.empty() && a->plot_dir.empty())
      throw InputError("command line", "--curriculum", "--plot DIR as well (the learning figures go there)");
    const std::optional<Curriculum> curriculum =
        a->curriculum.empty() ? std::nullopt : std::optional(load_curriculum(a->curriculum));
    const ExportResult r =
        a->format == "bids" ? export_bids(store, a->out, options) : export_long_csv(store, a->out, options);
    std::cout << "palprig export: " << r.trials << " trials";
    if (r.threshold_trials || r.pulse_trials) {
      std::cout << " (" << r.trials - r.threshold_trials - r.pulse_trials << " discrimination/localisation, "
                << r.threshold_trials << " threshold, " << r.pulse_trials << " pulse)";
    }
    std::cout << " from " << a->db << " into " << r.files.size() << " files in " << a->out << "\n";
    const std::size_t shown = std::min<std::size_t>(r.files.size(), 8);
    for (std::size_t i = 0; i < shown; ++i) std::cout << "  " << r.files[i].string() << "\n";
    if (shown < r.files.size()) std::cout << "  ... and " << r.files.size() - shown << " more\n";
    if (!a->plot_dir.empty()) {
      // The charts are statistics: practice trials are left out, as `stats trials` and the
      // statistics view leave them out (a chart cannot mark them as the data files do).
      charts::StorePlotOptions plot;
      plot.svg = a->svg;
      for (const auto& file : charts::plot_store(store, a->plot_dir, plot)) std::cout << "  " << file.string() << "\n";
      if (curriculum) {
        const auto trainees = curriculum_standings(a->db, *curriculum);
        for (const auto& file : charts::plot_learning(*curriculum, trainees, a->plot_dir, a->svg))
          std::cout << "  " << file.string() << "\n";
      }
    }
  });
}
