// palprig calibrate sweep: drive staircases (and optional identification excitations) on the
// rig's backend and record command, monitor and sensor to a CSV file. Arguments are checked
// before the backend opens (exit 2); a signal vents and keeps what was recorded (exit 1).
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "calibration/calibration_report.hpp"
#include "calibration/calibration_writer.hpp"
#include "calibration/sweep_csv.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_runner.hpp"
#include "cli/calibrate_arguments.hpp"
#include "cli/commands.hpp"
#include "controller/rig_lease.hpp"
#include "runtime/run_control.hpp"
#include "core/input_error.hpp"

using namespace palprig;
using namespace palprig::cli;

namespace {

struct SweepArgs {
  std::string rig_path, channels = "1,2,3", excitation = "staircase", out;
  SweepPlanOptions plan;
  SweepRunOptions run;
  bool realtime = false, fast = false, quiet = false;
};

void run_sweep(const SweepArgs& a) {
  // Everything is validated before the backend opens.
  const RigConfig rig = load_rig(a.rig_path);
  SweepPlanOptions plan_options = a.plan;
  plan_options.staircase = plan_options.random = plan_options.sine = plan_options.step = plan_options.chirp = false;
  std::istringstream ex(a.excitation);
  for (std::string item; std::getline(ex, item, ',');) {
    if (item == "staircase")
      plan_options.staircase = true;
    else if (item == "random")
      plan_options.random = true;
    else if (item == "sine")
      plan_options.sine = true;
    else if (item == "step")
      plan_options.step = true;
    else if (item == "chirp")
      plan_options.chirp = true;
    else
      throw InputError("--excitation", a.excitation, "a list of staircase, random, sine, step, chirp");
  }
  const SweepSchedule plan = plan_calibration_sweep(plan_options, rig.safety.p_max_kPa);
  SweepRunOptions run = a.run;
  run.channels = parse_channels(a.channels);
  run.realtime = use_realtime(rig, a.realtime, a.fast);
  run.slew_kPa_per_s = rig.safety.slew_kPa_per_s;  // steps between holds pass the safety stage
  if (!(run.settle_window_s > 0) || !(run.settle_band_kPa > 0) || !(run.average_s > 0) ||
      !(run.max_hold_s > run.min_hold_s) || run.max_hold_s < run.settle_window_s + run.average_s ||
      !(run.max_hold_s <= 3600))
    throw InputError("--max-hold-s", std::to_string(run.max_hold_s),
                     "settle window, band and averaging window > 0, and a max hold above the min hold and both "
                     "windows, at most 3600 s");
  for (const auto& n : plan.notes) std::cerr << "palprig: note: " << n << "\n";

  std::unique_ptr<Rig> opened = make_rig(rig);
  const RigBackend& backend = opened->backend();
  SweepFileInfo info;
  info.rig_id = rig.id;
  info.backend = backend.describe();
  info.date = utc_timestamp_now();
  info.p_max_kPa = rig.safety.p_max_kPa;
  info.rate_hz = run.rate_hz;
  info.sensor_name = backend.sensor_name();
  info.notes = plan.notes;
  SweepCsvWriter writer(a.out, info, run.channels);  // a path that cannot be written fails here, before open
  // Said before anything moves (and after a refusal of the file, which is the one line then);
  // the sweep still runs (a short check of the link is a use).
  if (const std::string shortfall = sweep_fit_shortfall(plan); !shortfall.empty())
    std::cerr << "palprig: warning: this sweep is " << shortfall << "\n";
  opened->open();
  RigLease lease = opened->lease("palprig calibrate sweep");

  install_stop_signals();
  run.control = &process_run_control();
  run.fault_record_folder = std::filesystem::absolute(a.out).parent_path();  // beside the sweep data
  // A line at each segment and at least every 5 s of wall time: the share done and the time left.
  if (!a.quiet) run.progress_report = [](const ProgressReport& r) { std::cerr << progress_line(r) << "\n"; };
  auto progress = [&](std::size_t done, std::size_t, const SweepHold& hold, const HoldOutcome& result) {
    if (!result.settled && !result.timed)
      std::cerr << "palprig: warning: hold " << done << " (" << to_string(hold.segment) << " " << hold.level_kPa
                << " kPa) did not settle within " << run.max_hold_s << " s; kept, marked unsettled\n";
  };
  const SweepOutcome outcome = run_calibration_sweep(lease, plan, run, writer, progress);
  writer.finish(outcome);
  lease.release();
  opened.reset();  // vented and closed
  std::cout << "palprig calibrate sweep: rig " << rig.id << " (" << info.backend << "), channels "
            << channels_text(run.channels) << ", " << (run.realtime ? "real time" : "simulated time") << "\n"
            << "  " << outcome.holds_done << " of " << outcome.holds_planned << " holds (" << outcome.holds_unsettled
            << " not settled"
            << (outcome.holds_redone ? ", " + std::to_string(outcome.holds_redone) + " redone after a link outage" : "")
            << ") in " << outcome.duration_s << " s of rig time; " << writer.rows() << " rows -> " << a.out << "\n";
  // The plant away from a settled level by more than the regulator tolerance: a leak, a sagging
  // supply, lost frames; said with its time whether or not an outage was counted.
  for (const Excursion& e : outcome.excursions)
    std::cerr << "palprig: warning: excursion at a held level, " << excursion_text(e, run.tolerance_kPa) << "\n";
  if (outcome.stopped || outcome.faulted) {
    std::cerr << "palprig: sweep "
              << (outcome.stopped ? (outcome.stop_signal ? "stopped by signal " + std::to_string(outcome.stop_signal)
                                                         : std::string("stopped"))
                                  : "faulted: " + outcome.fault)
              << " after " << outcome.holds_done << " of " << outcome.holds_planned
              << " holds; all channels vented; what was recorded is in " << a.out
              << (outcome.fault_record.empty() ? "" : "; " + outcome.fault_record) << "\n";
    cli::finish(cli::kExitFault);
  }
}

}  // namespace

void register_calibrate_sweep(CLI::App* cal) {
  auto sa = std::make_shared<SweepArgs>();
  CLI::App* sweep =
      cal->add_subcommand("sweep", "Record inflation/deflation staircases (and identification excitations)");
  sweep->add_option("--rig", sa->rig_path, "Rig file (JSON); default: the simulated rig in data/rigs/simulated.json");
  sweep->add_option("--channels", sa->channels, "Channels to drive, e.g. 1,2,3 (the others stay vented)")
      ->default_val("1,2,3");
  sweep->add_option("--from-kPa", sa->plan.from_kPa, "Lowest staircase level")->default_val(10.0);
  sweep->add_option("--to-kPa", sa->plan.to_kPa, "Highest staircase level (clamped to the rig's p_max)")
      ->default_val(100.0);
  sweep->add_option("--step-kPa", sa->plan.step_kPa, "Staircase step")->default_val(10.0);
  sweep->add_option("--repeats", sa->plan.repeats, "Staircase repeats, each from vented")->default_val(5);
  sweep
      ->add_option("--excitation", sa->excitation,
                   "staircase, random, sine, step, chirp (comma-separated); random and sine add reversals for the "
                   "hysteresis fit, step and chirp identify the regulators' dynamics for lag compensation")
      ->default_val("staircase");
  sweep->add_option("--random-levels", sa->plan.random_levels, "Levels of the random excitation")->default_val(60);
  sweep->add_option("--sine-cycles", sa->plan.sine_cycles, "Cycles of the shrinking stepped sine")->default_val(4);
  sweep->add_option("--sine-steps", sa->plan.sine_steps_per_cycle, "Levels per sine cycle")->default_val(16);
  sweep->add_option("--seed", sa->plan.seed, "Seed of the random excitation")->default_val(1u);
  sweep->add_option("--step-hold-s", sa->plan.step_hold_s, "How long each step of the step excitation is held")
      ->default_val(0.6);
  sweep->add_option("--chirp-s", sa->plan.chirp_s, "Length of the chirp excitation")->default_val(8.0);
  sweep->add_option("--chirp-from-hz", sa->plan.chirp_from_hz, "The chirp's first frequency")->default_val(0.5);
  sweep->add_option("--chirp-to-hz", sa->plan.chirp_to_hz, "The chirp's last frequency")->default_val(12.0);
  sweep
      ->add_option("--dynamics-rate-hz", sa->run.dynamics_rate_hz,
                   "Command/record rate of the step and chirp excitations (the loop's rate)")
      ->default_val(1000.0)
      ->check(CLI::Range(1.0, 10000.0));
  sweep->add_option("--rate-hz", sa->run.rate_hz, "Command/record rate")
      ->default_val(100.0)
      ->check(CLI::Range(1.0, 10000.0));
  sweep->add_option("--settle-band-kPa", sa->run.settle_band_kPa, "Settled: window halves differ by at most this")
      ->default_val(0.2);
  sweep->add_option("--settle-window-s", sa->run.settle_window_s, "Settle test window")->default_val(0.3);
  sweep->add_option("--average-s", sa->run.average_s, "Averaging window once settled (the hold's reading)")
      ->default_val(0.3);
  sweep->add_option("--min-hold-s", sa->run.min_hold_s, "Shortest hold")->default_val(0.2);
  sweep->add_option("--max-hold-s", sa->run.max_hold_s, "Longest hold; a hold that does not settle is marked")
      ->default_val(10.0);
  auto* rt = sweep->add_flag("--realtime", sa->realtime, "Real time even on the simulated rig");
  sweep->add_flag("--fast", sa->fast, "Simulated time (simulated rig only; the default there)")->excludes(rt);
  sweep->add_flag("--quiet", sa->quiet, "No progress lines");
  sweep
      ->add_option("--regulator-tolerance-kPa", sa->run.tolerance_kPa,
                   "A settled reading further than this from its command is an excursion, reported with its time")
      ->default_val(kDefaultRegulatorTolerance_kPa)
      ->check(CLI::Range(0.01, 1000.0));
  sweep->add_option("--out", sa->out, "Data file to write (CSV)")->required();
  sweep->callback([sa] { run_sweep(*sa); });
}
