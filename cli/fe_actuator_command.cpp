// palprig fe actuator: the fingertip pressed onto the pneumatic actuator, then the air pressure
// raised in steps (paper 002 section 2.3, fig. 11-13): the peak contact stress per pressure, its
// straight line and R^2, the pressure that renders a given fingertip stress, the profiles (CSV)
// and the figures.
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

struct ActuatorArgs {
  std::string fingertip, actuator, out, pressures = "0,10,20,30,40,50,60,70,80,90,100";
  double press_mm = 1, target_kPa = 7.967, soft_kPa = 4.990;
  std::string loading = "press-first";
  bool plot = true;
  FeAnalysisArgs analysis;
};

void run_actuator(const ActuatorArgs& a) {
  const FingertipBody finger = load_fingertip_file(a.fingertip);
  const ActuatorBody actuator = load_actuator_file(a.actuator);
  mechanics::ActuatorOptions o;
  o.solve = solve_options(a.analysis);
  o.press_mm = a.press_mm;
  o.loading = actuator_loading(a.loading);
  o.pressures_kPa = number_list(a.pressures, "--pressures", 0, 500);
  std::filesystem::create_directories(a.out);
  std::cout << "palprig fe actuator: " << a.fingertip << " pressed " << (a.loading == "together" ? "up to " : "")
            << a.press_mm << " mm onto " << a.actuator << (a.loading == "together" ? " as the air rises" : "") << ", "
            << plane_text(a.analysis) << ", " << a.analysis.element_mm << " mm elements\n";
  FeProgress progress("fe actuator");
  const mechanics::ContactRun run = mechanics::run_actuator(finger, actuator, o, std::ref(progress));
  std::vector<double> p, s;
  print_out("  %8s %9s %11s %7s\n", "air kPa", "peak kPa", "force N/m", "Newton");
  for (const auto& step : run.steps) {
    print_out("  %8.1f %9.3f %11.2f %7d\n", step.load, step.peak_kPa, step.force_N_per_m, step.newton_iterations);
    p.push_back(step.load);
    s.push_back(step.peak_kPa);
  }
  const mechanics::StressLine line = mechanics::fit_stress_line(p, s);
  print_out("  line: stress = %.5f x air + %.3f kPa, R^2 %.5f (%zu pressures)\n", line.slope, line.intercept_kPa,
            line.r_squared, line.points);
  if (line.slope > 0)
    print_out("  %.3f kPa of fingertip stress needs %.2f kPa of air (%zu unknowns, %d step cuts)\n", a.target_kPa,
              (a.target_kPa - line.intercept_kPa) / line.slope, run.unknowns, run.cuts);
  // Paper 002's reading: the uninflated actuator stands for healthy tissue and the air adds the
  // line's slope to that stress (fe stress-model --uninflated soft-tissue).
  if (line.slope > 0 && a.target_kPa > a.soft_kPa)
    print_out("  the uninflated actuator as soft tissue at %.3f kPa: %.3f kPa needs %.2f kPa of air\n", a.soft_kPa,
              a.target_kPa, (a.target_kPa - a.soft_kPa) / line.slope);
  std::cout << std::flush;
  std::fprintf(stderr, "palprig fe actuator: solved in %.1f s\n", run.wall_s);
  const std::filesystem::path out(a.out);
  write_output(out / "actuator_steps.csv", mechanics::steps_csv(run, "pressure_kPa"));
  write_output(out / "actuator_profiles.csv", mechanics::profiles_csv(run, "pressure_kPa"));
  if (!a.plot) return;
  charts::PeakSeries series{"peak contact stress", p, s, line};
  print_plots(charts::write_peak_figure(out / "actuator_line", "Fingertip stress on the actuator against air pressure",
                                        "air pressure (kPa)", {series}));
  std::vector<charts::ProfileCurve> curves;
  std::vector<std::string> labels;
  labels.reserve(2);
  for (const auto* step : {&run.steps.front(), &run.steps.back()}) {
    char label[96];
    std::snprintf(label, sizeof label, "%.0f kPa of air (peak %.3f kPa)", step->load, step->peak_kPa);
    labels.push_back(label);
    curves.push_back({labels.back(), step});
  }
  print_plots(charts::write_contact_stress_figure(out / "actuator_contact_stress",
                                                  "Contact stress on the fingertip pressing the actuator", curves));
  char title[160];
  std::snprintf(title, sizeof title, "The actuator at %.0f kPa: von Mises stress", run.steps.back().load);
  print_plots(charts::write_deformed_mesh_figure(out / "actuator_mesh", title, run));
}

}  // namespace

void register_fe_actuator(CLI::App* fe) {
  auto a = std::make_shared<ActuatorArgs>();
  CLI::App* sub = fe->add_subcommand("actuator", "Press the fingertip onto the actuator and sweep its air pressure");
  sub->add_option("--fingertip", a->fingertip, "Fingertip file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--actuator", a->actuator, "Actuator file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--press-mm", a->press_mm, "How far the fingertip's bone is pressed down")
      ->default_val(1.0)
      ->check(CLI::Range(0.1, 5.0));
  sub->add_option("--pressures", a->pressures, "Air pressures in kPa, comma-separated")
      ->default_val("0,10,20,30,40,50,60,70,80,90,100");
  sub->add_option("--target-kPa", a->target_kPa, "Fingertip stress whose air pressure to report (paper 002's nodule)")
      ->default_val(7.967);
  sub->add_option("--soft-kPa", a->soft_kPa,
                  "Soft tissue's stress, for the air the target needs over it when the uninflated actuator stands "
                  "for soft tissue (paper 002's healthy peak)")
      ->default_val(4.990)
      ->check(CLI::Range(0.0, 1000.0));
  add_fe_loading_option(sub, a->loading);
  sub->add_option("--out", a->out, "Folder for the CSV tables and figures")->required();
  sub->add_flag("!--no-plot", a->plot, "Write the tables only");
  add_fe_analysis_options(sub, a->analysis);
  sub->callback([a] { run_actuator(*a); });
}
