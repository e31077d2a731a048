// palprig calibrate fit: regressions per branch, regulator check, stress line, force window and
// the hysteresis model (Ceres) from sweep data -> the versioned calibration file the controller
// reads; --plot draws the fits (gui/calibration_charts).
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "calibration/calibration_fit.hpp"
#include "calibration/calibration_report.hpp"
#include "calibration/calibration_writer.hpp"
#include "calibration/sweep_csv.hpp"
#include "cli/calibrate_arguments.hpp"
#include "cli/commands.hpp"
#include "formats/calibration_file.hpp"
#include "formats/fe_result_files.hpp"
#include "core/input_error.hpp"
#include "charts/calibration_charts.hpp"

using namespace palprig;
using namespace palprig::cli;

namespace {

struct FitArgs {
  std::string data, out, rig_id, stress, presses, base, plot_dir, loss = "none", source, model = "auto", stress_model;
  double regulator_tolerance_kPa = 3.0, diastolic_mmHg = 60, systolic_mmHg = 120;
  HysteresisFitOptions hysteresis;
  bool no_refine = false, json = false, lag_compensation = false, svg = false;
  double max_lead_kPa = 10, min_r_squared = kDefaultMinDynamicsRSquared;
  bool operators_given = false;  // --operators named: refuse data that cannot support it
};

void run_fit(const FitArgs& a) {
  CalibrationFitOptions o;
  o.hysteresis = a.hysteresis;
  o.operators_from_data = !a.operators_given;
  o.hysteresis.refine_thresholds = !a.no_refine;
  if (a.loss == "huber")
    o.hysteresis.loss = RobustLoss::huber;
  else if (a.loss == "cauchy")
    o.hysteresis.loss = RobustLoss::cauchy;
  if (a.source == "monitor")
    o.hysteresis_from = HysteresisSource::monitor;
  else if (a.source == "sensor")
    o.hysteresis_from = HysteresisSource::sensor;
  else if (a.source == "none")
    o.hysteresis_from = HysteresisSource::none;
  if (a.model == "symmetric")
    o.hysteresis_model = HysteresisModelClass::symmetric;
  else if (a.model == "asymmetric")
    o.hysteresis_model = HysteresisModelClass::asymmetric;
  o.regulator_tolerance_kPa = a.regulator_tolerance_kPa;
  o.lag_compensation.enabled = a.lag_compensation;
  o.lag_compensation.max_lead_kPa = a.max_lead_kPa;
  o.lag_compensation.min_r_squared = a.min_r_squared;
  o.rig_id = a.rig_id;
  o.date = utc_timestamp_now();
  o.progress = [](const ProgressReport& r) { std::cerr << progress_line(r) << "\n"; };
  if (!a.base.empty()) o.base = load_calibration_file(a.base);
  if (!a.stress_model.empty()) {  // the stress model from physics (`palprig fe stress-model`)
    const FeStressModelFile fe = load_stress_model_file(a.stress_model);
    o.base.stress.soft_stress_kPa = fe.soft_stress_kPa;
    o.base.stress.hard_stress_kPa = fe.hard_stress_kPa;
    o.base.actuators.fill(fe.actuator);
    o.base.source = "the finite-element stress model " + a.stress_model;
  }
  if (!a.stress.empty()) {
    o.stress_pairs = read_stress_pairs_csv(a.stress);
    o.stress_file = a.stress;
  }
  if (!a.presses.empty()) {
    o.force_window = force_window_from_presses(a.presses, a.diastolic_mmHg, a.systolic_mmHg);
    o.force_file = a.presses;
  }
  const SweepData data = read_sweep_csv(a.data);
  CalibrationResult result = fit_calibration(data, o);
  if (!a.stress_model.empty()) {
    std::ostringstream note;
    note << "stress model from " << a.stress_model << ": soft " << o.base.stress.soft_stress_kPa << " kPa, nodule "
         << o.base.stress.hard_stress_kPa << " kPa (finite elements)";
    result.notes.push_back(note.str());
  }
  const nlohmann::json doc = calibration_json(result);
  write_calibration_file(a.out, doc);
  if (a.json)
    std::cout << doc.dump(2) << "\n";
  else
    print_fit_report(std::cout, result, a.out);
  if (!a.plot_dir.empty())
    for (const auto& p : charts::plot_fit(a.plot_dir, data, result, a.svg))
      std::cout << "  plot: " << p.string() << "\n";
}

}  // namespace

void register_calibrate_fit(CLI::App* cal) {
  auto fa = std::make_shared<FitArgs>();
  CLI::App* fit = cal->add_subcommand("fit", "Fit the models to sweep data and write the calibration file");
  fit->add_option("data", fa->data, "Sweep data (CSV from calibrate sweep, or a table typed in)")
      ->required()
      ->check(CLI::ExistingFile);
  fit->add_option("--out", fa->out, "Calibration file to write (JSON)")->required();
  fit->add_option("--rig-id", fa->rig_id, "Rig id (default: the data file's)");
  fit->add_option("--base", fa->base, "Calibration whose stress model and actuator lines are kept (default: paper 002)")
      ->check(CLI::ExistingFile);
  fit->add_option("--stress-model", fa->stress_model,
                  "Stress model file from `palprig fe stress-model`: its soft and nodule stresses and its actuator "
                  "line, instead of paper 002's constants (--stress pairs still refit the lines)")
      ->check(CLI::ExistingFile);
  fit->add_option("--stress", fa->stress, "Stress pairs CSV pressure_kPa,stress_kPa[,channel] for the actuator lines")
      ->check(CLI::ExistingFile);
  fit->add_option("--force-presses", fa->presses, "Force-window presses CSV reference_mmHg,force_N (paper 003)")
      ->check(CLI::ExistingFile);
  fit->add_option("--diastolic-mmHg", fa->diastolic_mmHg, "Lower reference press")->default_val(60.0);
  fit->add_option("--systolic-mmHg", fa->systolic_mmHg, "Upper reference press")->default_val(120.0);
  auto* operators = fit->add_option("--operators", fa->hysteresis.operator_count,
                                    "Play operators of the hysteresis model (default: 8, or as many as the data "
                                    "supports, with a note)")
                        ->default_val(8)
                        ->check(CLI::Range(1, int(kMaxPlayOperators)));
  fit->add_option("--max-threshold-kPa", fa->hysteresis.max_threshold_kPa,
                  "Largest initial threshold (0: from the data)")
      ->default_val(0.0);
  fit->add_flag("--no-refine", fa->no_refine, "Keep the thresholds on the grid (weights only)");
  fit->add_option("--robust-loss", fa->loss, "none, huber or cauchy")
      ->default_val("none")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}));
  fit->add_option("--robust-scale-kPa", fa->hysteresis.loss_scale_kPa, "Where the robust loss bends")->default_val(1.0);
  fit->add_option("--hysteresis-from", fa->source, "monitor, sensor or none (default: monitor when recorded)")
      ->check(CLI::IsMember({"monitor", "sensor", "none"}));
  fit->add_option("--hysteresis-model", fa->model,
                  "auto (the class with the lower held-out error over the sweep's runs), symmetric or asymmetric")
      ->default_val("auto")
      ->check(CLI::IsMember({"auto", "symmetric", "asymmetric"}));
  fit->add_option("--regulator-tolerance-kPa", fa->regulator_tolerance_kPa,
                  "Refuse a regulator whose monitor line is off the command by more")
      ->default_val(3.0);
  fit->add_flag("--lag-compensation", fa->lag_compensation,
                "Write the file with lag compensation on (lag_compensation.enabled; needs step and chirp rows)");
  fit->add_option("--max-lead-kPa", fa->max_lead_kPa, "Lag compensation: the command at most this far above the target")
      ->default_val(10.0)
      ->check(CLI::Range(0.0, 100.0));
  fit->add_option("--min-r-squared", fa->min_r_squared,
                  "Lag compensation: a channel whose dynamics fit with a lower R^2 keeps it off")
      ->default_val(kDefaultMinDynamicsRSquared)
      ->check(CLI::Range(kLowestMinDynamicsRSquared, 1.0));
  fit->add_option("--plot", fa->plot_dir, "Write PNG plots of the data and fitted lines to DIR");
  fit->add_flag("--svg", fa->svg, "With --plot: an SVG beside every PNG");
  fit->add_flag("--json", fa->json, "Print the calibration file instead of the tables");
  fit->callback([fa, operators] {
    fa->operators_given = operators->count() > 0;
    run_fit(*fa);
  });
}
