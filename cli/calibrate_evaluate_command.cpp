// palprig calibrate evaluate: the same test trajectory with and without the hysteresis
// compensation, RMS tracking error per channel; --plot draws both runs (gui/calibration_charts).
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "calibration/calibration_report.hpp"
#include "calibration/compensation_evaluation.hpp"
#include "cli/calibrate_arguments.hpp"
#include "cli/commands.hpp"
#include "controller/rig_lease.hpp"
#include "formats/calibration_file.hpp"
#include "core/input_error.hpp"
#include "charts/calibration_charts.hpp"
#include "runtime/run_control.hpp"

using namespace palprig;
using namespace palprig::cli;

namespace {

struct EvaluateArgs {
  std::string rig_path, cal_path, channels = "1,2,3", out, plot_dir;
  EvaluationOptions options;
  bool realtime = false, fast = false, json = false, svg = false, quiet = false;
  double min_improvement = 0;
};

void run_evaluate(const EvaluateArgs& a) {
  const RigConfig rig = load_rig(a.rig_path);
  const CalibrationModels cal = load_calibration_file(a.cal_path);
  check_calibration_matches(cal, rig.id, rig.source);
  EvaluationOptions o = a.options;
  o.channels = parse_channels(a.channels);
  o.realtime = use_realtime(rig, a.realtime, a.fast);
  std::unique_ptr<Rig> opened = open_rig(rig);
  const std::string described = opened->backend().describe();
  install_stop_signals();
  o.control = &process_run_control();
  // A line at each run and at least every 5 s of wall time: the share done and the time left.
  if (!a.quiet) o.progress = [](const ProgressReport& r) { std::cerr << progress_line(r) << "\n"; };
  EvaluationResult r;
  {
    RigLease lease = opened->lease("palprig calibrate evaluate");
    r = evaluate_compensation(lease, rig, cal, o);
  }
  opened.reset();  // vented and closed
  if (a.json) {
    std::cout << evaluation_json(r, o.channels).dump(2) << "\n";
  } else {
    std::cout << "palprig calibrate evaluate: rig " << rig.id << " (" << described << "), calibration " << a.cal_path
              << ", " << (o.realtime ? "real time" : "simulated time") << " at " << o.rate_hz << " Hz\n";
    print_evaluation_report(std::cout, r, o.channels);
  }
  if (!a.out.empty()) write_evaluation_trace_csv(a.out, r);
  if (!a.plot_dir.empty())
    for (const auto& p : charts::plot_evaluation(a.plot_dir, r, o.channels, a.svg))
      std::cout << "  plot: " << p.string() << "\n";
  std::size_t excursions = r.uncompensated.excursions.size() + r.compensated.excursions.size();
  if (excursions > 0)
    std::cerr << "palprig: warning: " << excursions << " excursion" << (excursions == 1 ? "" : "s") << " beyond "
              << o.tolerance_kPa
              << " kPa of the target (listed above): a leak, a sagging supply or lost frames; check the rig before "
                 "trusting these figures\n";
  if (!r.complete()) {
    std::cerr << "palprig: evaluation did not complete (signal or fault); all channels vented\n";
    cli::finish(cli::kExitFault);
  }
  if (a.min_improvement > 0 && r.worst_improvement < a.min_improvement) {
    std::cerr << "palprig: compensation improves tracking only " << r.worst_improvement << "x (asked at least "
              << a.min_improvement << "x)\n";
    cli::finish(cli::kExitFault);
  }
}

}  // namespace

void register_calibrate_evaluate(CLI::App* cal) {
  auto ea = std::make_shared<EvaluateArgs>();
  CLI::App* ev = cal->add_subcommand("evaluate", "Track a test trajectory with and without hysteresis compensation");
  ev->add_option("--rig", ea->rig_path, "Rig file (JSON); default: the simulated rig in data/rigs/simulated.json");
  ev->add_option("--cal", ea->cal_path, "Calibration file (JSON)")->required()->check(CLI::ExistingFile);
  ev->add_option("--channels", ea->channels, "Channels to drive")->default_val("1,2,3");
  ev->add_option("--from-kPa", ea->options.from_kPa, "Bottom of the trajectory")->default_val(10.0);
  ev->add_option("--to-kPa", ea->options.to_kPa, "Top of the trajectory (default: 80 % of p_max)");
  ev->add_option("--ramp-kPa-per-s", ea->options.ramp_kPa_per_s, "Ramp rate between reversals")->default_val(1.0);
  ev->add_option("--duration-s", ea->options.duration_s, "Scored length of each run")->default_val(120.0);
  ev->add_option("--rate-hz", ea->options.rate_hz, "Loop rate")->default_val(1000.0)->check(CLI::Range(1.0, 100000.0));
  ev->add_option("--seed", ea->options.seed, "Seed of the trajectory's turning points")->default_val(7u);
  auto* ert = ev->add_flag("--realtime", ea->realtime, "Real time even on the simulated rig");
  ev->add_flag("--fast", ea->fast, "Simulated time (simulated rig only; the default there)")->excludes(ert);
  ev->add_option("--out", ea->out, "Write the trace of both runs (CSV)");
  ev->add_option("--plot", ea->plot_dir, "Write PNG plots of both runs to DIR");
  ev->add_flag("--svg", ea->svg, "With --plot: an SVG beside every PNG");
  ev->add_option("--min-improvement", ea->min_improvement, "Exit 1 when RMS off/on is below this on any channel")
      ->default_val(0.0);
  ev->add_flag("--json", ea->json, "Print the figures as one JSON object");
  ev->add_option("--regulator-tolerance-kPa", ea->options.tolerance_kPa,
                 "A monitor further than this from the target is an excursion, reported with its time")
      ->default_val(kDefaultRegulatorTolerance_kPa)
      ->check(CLI::Range(0.01, 1000.0));
  ev->add_flag("--quiet", ea->quiet, "No progress lines");
  ev->callback([ea] { run_evaluate(*ea); });
}
