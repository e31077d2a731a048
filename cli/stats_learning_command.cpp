// palprig stats learning DB --curriculum C: each trainee's learning curves and CUSUM charts
// (store/training_report), as a table or JSON; --plot DIR draws them (charts/learning_charts).
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "charts/learning_charts.hpp"
#include "store/export_file.hpp"
#include "store/training_report.hpp"

using namespace palprig;

void register_stats_learning(CLI::App* stats_app) {
  struct Args {
    std::string db, curriculum, trainee, plot;
    bool json = false, svg = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = stats_app->add_subcommand(
      "learning",
      "Trainees' learning curves per measure (per session, with the benchmark met or not) and CUSUM / LC-CUSUM charts "
      "over their cases, the limits computed from the curriculum's error rates with their run lengths");
  sub->add_option("db", a->db, "Trial store: an SQLite file or postgresql://user@host:port/dbname")->required();
  sub->add_option("--curriculum", a->curriculum, "Curriculum file (JSON) the trainees are enrolled in")->required();
  sub->add_option("--trainee", a->trainee, "One trainee (default: every trainee enrolled in the curriculum)");
  sub->add_flag("--json", a->json, "JSON instead of a table");
  sub->add_option("--plot", a->plot, "Also draw each trainee's learning curves and CUSUM charts as PNG in DIR");
  sub->add_flag("--svg", a->svg, "With --plot: an SVG beside every PNG");
  sub->callback([a] {
    const Curriculum c = load_curriculum(a->curriculum);
    std::vector<TraineeStanding> trainees;
    if (a->trainee.empty())
      trainees = curriculum_standings(a->db, c);
    else
      trainees.push_back(trainee_standing(a->db, c, a->trainee));
    if (a->json)
      std::cout << learning_report_json(c, trainees).dump(2) << "\n";
    else
      std::cout << learning_report_text(c, trainees);
    if (!a->plot.empty()) {
      make_export_dir(a->plot);
      for (const auto& f : charts::plot_learning(c, trainees, a->plot, a->svg)) std::cout << "  " << f.string() << "\n";
    }
  });
}
