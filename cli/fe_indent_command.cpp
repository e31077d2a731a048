// palprig fe indent: the fingertip pressed into one or more tissue blocks, step by step (paper
// 002 section 2.3): the peak contact stress per step, the stress profile along the fingertip
// (CSV), the figures (stress along the contact, the deformed mesh by von Mises stress).
#include <cstdio>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "charts/fe_charts.hpp"
#include "cli/commands.hpp"
#include "cli/fe_arguments.hpp"
#include "formats/fe_body_files.hpp"
#include "mechanics/fe_report.hpp"

using namespace palprig;
using namespace palprig::cli;

namespace {

struct IndentArgs {
  std::string fingertip, out;
  std::vector<std::string> tissues;
  double depth_mm = 7, step_mm = 1, at_mm = 0;
  bool plot = true;
  FeAnalysisArgs analysis;
};

void run_indent(const IndentArgs& a) {
  const FingertipBody finger = load_fingertip_file(a.fingertip);
  std::vector<TissueBlock> blocks;
  for (const auto& t : a.tissues) blocks.push_back(load_tissue_file(t));  // every file checked before solving
  std::filesystem::create_directories(a.out);
  mechanics::IndentationOptions o;
  o.solve = solve_options(a.analysis);
  o.depth_mm = a.depth_mm;
  o.step_mm = a.step_mm;
  o.finger_x_mm = a.at_mm;
  std::vector<mechanics::ContactRun> runs;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::string stem = std::filesystem::path(a.tissues[i]).stem().string();
    std::cout << "palprig fe indent: " << a.fingertip << " into " << a.tissues[i] << ", " << plane_text(a.analysis)
              << ", " << a.analysis.element_mm << " mm elements, to " << a.depth_mm << " mm\n";
    FeProgress progress("fe indent");
    runs.push_back(mechanics::run_indentation(finger, blocks[i], o, std::ref(progress)));
    const mechanics::ContactRun& run = runs.back();
    print_out("  %8s %9s %11s %11s %7s\n", "depth mm", "peak kPa", "force N/m", "contact mm", "Newton");
    for (const auto& s : run.steps)
      print_out("  %8.2f %9.3f %11.2f %11.2f %7d\n", s.load, s.peak_kPa, s.force_N_per_m, s.contact_length_mm,
                s.newton_iterations);
    const auto& last = run.steps.back();
    print_out("  peak at %.2f mm: %.3f kPa, %.2f mm from the fingertip's lowest point (%zu unknowns, %d step cuts)\n",
              last.load, last.peak_kPa, last.peak_s_mm, run.unknowns, run.cuts);
    std::cout << std::flush;
    std::fprintf(stderr, "palprig fe indent: solved in %.1f s\n", run.wall_s);
    write_output(std::filesystem::path(a.out) / (stem + "_steps.csv"), mechanics::steps_csv(run, "depth_mm"));
    write_output(std::filesystem::path(a.out) / (stem + "_profiles.csv"), mechanics::profiles_csv(run, "depth_mm"));
    if (a.plot) {
      char title[256];
      std::snprintf(title, sizeof title, "%s, %.2f mm deep: von Mises stress", stem.c_str(), last.load);
      print_plots(charts::write_deformed_mesh_figure(std::filesystem::path(a.out) / (stem + "_mesh"), title, run));
    }
  }
  if (a.plot) {
    std::vector<charts::ProfileCurve> curves;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      char label[256];
      std::snprintf(label, sizeof label, "%s (peak %.3f kPa)", std::filesystem::path(a.tissues[i]).stem().c_str(),
                    runs[i].steps.back().peak_kPa);
      curves.push_back({label, &runs[i].steps.back()});
    }
    char title[160];
    std::snprintf(title, sizeof title, "Contact stress on the fingertip at %.2f mm (%s)", a.depth_mm,
                  plane_text(a.analysis).c_str());
    print_plots(charts::write_contact_stress_figure(std::filesystem::path(a.out) / "contact_stress", title, curves));
  }
}

}  // namespace

void register_fe_indent(CLI::App* fe) {
  auto a = std::make_shared<IndentArgs>();
  CLI::App* sub =
      fe->add_subcommand("indent", "Press the fingertip into tissue blocks: peak stress per step, profiles, figures");
  sub->add_option("--fingertip", a->fingertip, "Fingertip file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--tissue", a->tissues, "Tissue file (JSON); repeat to compare blocks in one figure")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--depth-mm", a->depth_mm, "Indentation depth of the last step")
      ->default_val(7.0)
      ->check(CLI::Range(0.1, 20.0));
  sub->add_option("--step-mm", a->step_mm, "Indentation per step")->default_val(1.0)->check(CLI::Range(0.05, 5.0));
  sub->add_option("--at-mm", a->at_mm, "Where the fingertip presses, across from the block's middle")
      ->default_val(0.0)
      ->check(CLI::Range(-100.0, 100.0));
  sub->add_option("--out", a->out, "Folder for the CSV tables and figures")->required();
  sub->add_flag("!--no-plot", a->plot, "Write the tables only");
  add_fe_analysis_options(sub, a->analysis);
  sub->callback([a] { run_indent(*a); });
}
