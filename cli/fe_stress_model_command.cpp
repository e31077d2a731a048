// palprig fe stress-model: the stress model from physics (paper 002 section 2.3 end to end):
// the fingertip pressed into the tissue block without and with its nodule (the soft and hard
// stresses), and onto the actuator across its pressures (the stress line), written as the
// stress model file `calibrate fit --stress-model` takes instead of the paper's constants.
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/commands.hpp"
#include "cli/fe_arguments.hpp"
#include "formats/fe_body_files.hpp"
#include "formats/fe_result_files.hpp"
#include "core/input_error.hpp"

using namespace palprig;
using namespace palprig::cli;

namespace {

struct StressModelArgs {
  std::string fingertip, tissue, actuator, out, pressures = "0,10,20,30,40,50,60,70,80,90,100";
  double depth_mm = 7, press_mm = 1;
  std::string loading = "press-first";
  std::string uninflated = "fitted";
  FeAnalysisArgs analysis;
};

void run_stress_model(const StressModelArgs& a) {
  const FingertipBody finger = load_fingertip_file(a.fingertip);
  const TissueBlock nodule = load_tissue_file(a.tissue);
  const ActuatorBody actuator = load_actuator_file(a.actuator);
  if (nodule.inclusions.empty())
    throw InputError(a.tissue, "inclusions", "a nodule: the stress over it is the model's hard stress");
  TissueBlock healthy = nodule;
  healthy.inclusions.clear();
  const auto pressures = number_list(a.pressures, "--pressures", 0, 500);
  const bool together = a.loading == "together";
  std::cout << "palprig fe stress-model: " << a.fingertip << ", " << a.tissue << ", " << a.actuator << ", "
            << plane_text(a.analysis) << ", " << a.analysis.element_mm << " mm elements\n";
  mechanics::IndentationOptions io;
  io.solve = solve_options(a.analysis);
  io.depth_mm = a.depth_mm;
  FeProgress soft_progress("fe stress-model (soft tissue)"), hard_progress("fe stress-model (nodule)"),
      actuator_progress("fe stress-model (actuator)");
  const auto soft = mechanics::run_indentation(finger, healthy, io, std::ref(soft_progress));
  const auto hard = mechanics::run_indentation(finger, nodule, io, std::ref(hard_progress));
  mechanics::ActuatorOptions ao;
  ao.solve = io.solve;
  ao.press_mm = a.press_mm;
  ao.loading = actuator_loading(a.loading);
  ao.pressures_kPa = pressures;
  const auto act = mechanics::run_actuator(finger, actuator, ao, std::ref(actuator_progress));

  FeStressModelFile m;
  std::ostringstream settings;
  settings << plane_text(a.analysis) << ' ' << a.analysis.element_mm << ' ' << a.depth_mm << ' ' << a.press_mm << ' '
           << a.pressures;
  if (together) settings << " together";  // press-first files keep the hash they had before the option
  if (a.uninflated != "fitted") settings << " uninflated " << a.uninflated;
  m.inputs = {a.fingertip,
              a.tissue,
              a.actuator,
              fe_inputs_hash({a.fingertip, a.tissue, a.actuator}, settings.str()),
              plane_text(a.analysis),
              a.analysis.element_mm};
  m.indentation_mm = a.depth_mm;
  m.soft_stress_kPa = soft.steps.back().peak_kPa;
  m.hard_stress_kPa = hard.steps.back().peak_kPa;
  m.press_mm = a.press_mm;
  m.loading = a.loading;
  for (const auto& s : act.steps) {
    m.pressures_kPa.push_back(s.load);
    m.stresses_kPa.push_back(s.peak_kPa);
  }
  const mechanics::StressLine line = mechanics::fit_stress_line(m.pressures_kPa, m.stresses_kPa);
  m.uninflated = a.uninflated;
  m.actuator.slope = line.slope;
  // Paper 002's reading of its own actuator ("an inactivated actuator to simulate the situation
  // of no tumor"): the uninflated actuator stands for healthy tissue, the air adds the slope.
  m.actuator.intercept_kPa = a.uninflated == "soft-tissue" ? m.soft_stress_kPa : line.intercept_kPa;
  m.r_squared = line.r_squared;
  m.nodule_pressure_kPa = line.slope > 0 ? (m.hard_stress_kPa - m.actuator.intercept_kPa) / line.slope : 0;
  print_out("  tissue at %.2f mm: soft %.3f kPa, over the nodule %.3f kPa (ratio %.3f)\n", a.depth_mm,
            m.soft_stress_kPa, m.hard_stress_kPa, m.hard_stress_kPa / m.soft_stress_kPa);
  print_out("  actuator pressed %s%.2f mm%s: stress = %.5f x air + %.3f kPa, R^2 %.5f\n", together ? "up to " : "",
            a.press_mm, together ? " as the air rises" : "", line.slope, line.intercept_kPa, line.r_squared);
  if (a.uninflated == "soft-tissue")
    print_out("  the uninflated actuator as soft tissue: stress = %.5f x air + %.3f kPa\n", m.actuator.slope,
              m.actuator.intercept_kPa);
  print_out("  the nodule's %.3f kPa needs %.2f kPa of air\n", m.hard_stress_kPa, m.nodule_pressure_kPa);
  std::cout << std::flush;
  std::fprintf(stderr, "palprig fe stress-model: solved in %.1f s\n", soft.wall_s + hard.wall_s + act.wall_s);
  write_stress_model_file(a.out, m);  // refused (and nothing written) when calibration could not use it
  std::cout << "  wrote " << a.out << "\n";
}

}  // namespace

void register_fe_stress_model(CLI::App* fe) {
  auto a = std::make_shared<StressModelArgs>();
  CLI::App* sub = fe->add_subcommand(
      "stress-model", "Derive the stress model (soft and nodule stresses, the actuator's line) for calibrate fit");
  sub->add_option("--fingertip", a->fingertip, "Fingertip file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--tissue", a->tissue, "Tissue file with its nodule (JSON); the block without it is the soft tissue")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--actuator", a->actuator, "Actuator file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--depth-mm", a->depth_mm, "Indentation of the reference press")
      ->default_val(7.0)
      ->check(CLI::Range(0.5, 20.0));
  sub->add_option("--press-mm", a->press_mm, "Press onto the actuator")->default_val(1.0)->check(CLI::Range(0.1, 5.0));
  sub->add_option("--pressures", a->pressures, "Air pressures in kPa, comma-separated")
      ->default_val("0,10,20,30,40,50,60,70,80,90,100");
  add_fe_loading_option(sub, a->loading);
  sub->add_option("--uninflated", a->uninflated,
                  "What the uninflated actuator renders: fitted (the line's own intercept) or soft-tissue (paper "
                  "002's reading: its stress is the soft tissue's, the air adds the line's slope)")
      ->default_val("fitted")
      ->check(CLI::IsMember({"fitted", "soft-tissue"}));
  sub->add_option("--out", a->out, "Stress model file to write (JSON)")->required();
  add_fe_analysis_options(sub, a->analysis);
  sub->callback([a] { run_stress_model(*a); });
}
