// palprig calibrate sweep|fit|evaluate: the calibration workflow of a rig (calibration/README.md).
//   sweep     drive staircases (and optional identification excitations) on the rig's backend
//             and record command, monitor and sensor to a CSV file;
//   fit       regressions per branch, regulator check, stress line, force window and the
//             hysteresis model (Ceres) -> the versioned calibration file the controller reads;
//   evaluate  the same test trajectory with and without the hysteresis compensation.
// Files and arguments are checked before anything moves (exit 2); a signal vents and keeps
// what was recorded (exit 1).
#include <algorithm>
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "controller/backend_factory.hpp"
#include "calibration/calibration_fit.hpp"
#include "calibration/calibration_report.hpp"
#include "calibration/calibration_writer.hpp"
#include "calibration/compensation_evaluation.hpp"
#include "calibration/sweep_csv.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_runner.hpp"
#include "cli/commands.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "models/parse_error.hpp"
#ifdef PALPRIG_HAVE_GUI
#include "gui/chart_png.hpp"
#include "models/hysteresis.hpp"
#endif

using namespace palprig;

namespace {

// --plot needs gui's chart drawing (Qt); a build without it refuses the option up front.
void check_plot_available(const std::string& dir) {
#ifndef PALPRIG_HAVE_GUI
  if (!dir.empty())
    throw InputError("--plot", dir, "a build with the chart drawing (configure with -DPALPRIG_GUI=ON; needs Qt6)");
#else
  (void)dir;
#endif
}


#ifdef PALPRIG_HAVE_GUI
using gui::Chart;
using gui::ChartSeries;

constexpr unsigned kInflationRgb = 0x1f77b4, kDeflationRgb = 0xd62728, kBothRgb = 0x555555;

ChartSeries line_series(const std::string& label, const LineFit& f, unsigned rgb) {
  ChartSeries s;
  s.label = label;
  s.x = {f.x_min, f.x_max};
  s.y = {f.at(f.x_min), f.at(f.x_max)};
  s.color_rgb = rgb;
  return s;
}

// Staircase readings per branch with the fitted lines (paper 002 fig. 8).
Chart branch_chart(const std::string& title, const std::string& y_label, const std::vector<HoldPoint>& pts,
                   Response response, const BranchFits& fits) {
  Chart c;
  c.title = title;
  c.x_label = "commanded pressure (kPa)";
  c.y_label = y_label;
  ChartSeries up, down;
  up.style = down.style = ChartSeries::Style::points;
  up.color_rgb = kInflationRgb;
  down.color_rgb = kDeflationRgb;
  for (const auto& p : pts) {
    if (p.segment != SweepSegment::staircase || p.branch == SweepBranch::none) continue;
    ChartSeries& s = p.branch == SweepBranch::inflation ? up : down;
    s.x.push_back(p.command_kPa);
    s.y.push_back(response_of(p, response));
  }
  char text[96];
  std::snprintf(text, sizeof text, "inflation, R^2 %.4f", fits.inflation.r_squared);
  c.series.push_back(line_series(text, fits.inflation, kInflationRgb));
  std::snprintf(text, sizeof text, "deflation, R^2 %.4f", fits.deflation.r_squared);
  c.series.push_back(line_series(text, fits.deflation, kDeflationRgb));
  std::snprintf(text, sizeof text, "both, R^2 %.4f", fits.both.r_squared);
  c.series.push_back(line_series(text, fits.both, kBothRgb));
  c.series.push_back(up);
  c.series.push_back(down);
  return c;
}

std::vector<std::filesystem::path> plot_fit(const std::filesystem::path& dir, const SweepData& data,
                                            const CalibrationResult& r) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> written;
  auto save = [&](const Chart& c, const std::string& name) {
    const auto p = dir / name;
    gui::write_chart_png(c, p);
    written.push_back(p);
  };
  for (const auto& ch : r.channels) {
    if (!ch.swept) continue;
    const std::string n = std::to_string(ch.channel);
    const auto pts = data.channel_points(ch.channel);
    if (ch.regulator)
      save(branch_chart("Channel " + n + ": regulator monitor against command", "monitored pressure (kPa)", pts,
                        Response::monitor, *ch.regulator),
           "channel_" + n + "_regulator.png");
    if (ch.response)
      save(branch_chart("Channel " + n + ": " + r.sensor_name + " against command", r.sensor_name, pts, Response::sensor,
                        *ch.response),
           "channel_" + n + "_sensor.png");
    if (ch.hysteresis) {
      // Every hold's reading, and the model driven through a major loop and nested minor loops.
      Chart c;
      c.title = "Channel " + n + ": hysteresis model (Prandtl-Ishlinskii)";
      c.x_label = "commanded pressure (kPa)";
      c.y_label = ch.hysteresis_source == HysteresisSource::sensor ? "sensor as pressure (kPa)" : "monitored pressure (kPa)";
      ChartSeries measured, model;
      measured.style = ChartSeries::Style::points;
      measured.label = "holds";
      measured.color_rgb = 0x999999;
      double lo = 1e300, hi = -1e300;
      for (const auto& p : pts) {
        const double y = ch.hysteresis_source == HysteresisSource::monitor ? p.monitor_kPa : std::nan("");
        measured.x.push_back(p.command_kPa);
        measured.y.push_back(y);
        if (p.segment != SweepSegment::vent) { lo = std::min(lo, p.command_kPa); hi = std::max(hi, p.command_kPa); }
      }
      PrandtlIshlinskii m = ch.hysteresis->model;
      m.reset(0);
      model.label = "model: major and minor loops";
      model.color_rgb = kDeflationRgb;
      const double mid = 0.5 * (lo + hi);
      double at = 0;
      for (double goal : {hi, lo, hi, mid - 0.25 * (hi - lo), mid + 0.25 * (hi - lo), mid - 0.1 * (hi - lo)}) {
        const double step = goal > at ? 0.1 : -0.1;
        for (; (goal - at) * step > 0; at += step) {
          model.x.push_back(at);
          model.y.push_back(m.apply(at));
        }
      }
      if (ch.hysteresis_source == HysteresisSource::monitor) c.series.push_back(measured);
      c.series.push_back(model);
      save(c, "channel_" + n + "_hysteresis.png");
    }
  }
  return written;
}

std::vector<std::filesystem::path> plot_evaluation(const std::filesystem::path& dir, const EvaluationResult& r,
                                                   const std::array<bool, kFingerCount>& channels) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> written;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!channels[c]) continue;
    const std::string n = std::to_string(c + 1);
    Chart error, loops;
    error.title = "Channel " + n + ": tracking error with and without compensation";
    error.x_label = "time into the scored run (s)";
    error.y_label = "monitor - target (kPa)";
    loops.title = "Channel " + n + ": output against target";
    loops.x_label = "target (kPa)";
    loops.y_label = "monitored pressure (kPa)";
    for (int with = 0; with < 2; ++with) {
      const EvaluationRun& run = with ? r.compensated : r.uncompensated;
      ChartSeries e, l;
      char label[96];
      std::snprintf(label, sizeof label, "%s, RMS %.3f kPa", with ? "compensated" : "uncompensated",
                    run.channels[c].rms_error_kPa);
      e.label = l.label = label;
      e.color_rgb = l.color_rgb = with ? kInflationRgb : kDeflationRgb;
      e.width_px = l.width_px = 1.2;
      for (const auto& row : run.trace) {
        if (row.t_s < run.scored_from_t_s) continue;  // the rest and the first approach
        e.x.push_back(row.t_s - run.scored_from_t_s);
        e.y.push_back(row.monitor_kPa[c] - row.target_kPa);
        l.x.push_back(row.target_kPa);
        l.y.push_back(row.monitor_kPa[c]);
      }
      error.series.push_back(e);
      loops.series.push_back(l);
    }
    ChartSeries identity;
    identity.label = "target";
    identity.color_rgb = kBothRgb;
    identity.width_px = 1;
    identity.x = identity.y = {r.from_kPa, r.to_kPa};
    loops.series.push_back(identity);
    for (const auto& [chart, name] : {std::pair{&error, "evaluate_channel_" + n + "_error.png"},
                                      std::pair{&loops, "evaluate_channel_" + n + "_loops.png"}}) {
      gui::write_chart_png(*chart, dir / name);
      written.push_back(dir / name);
    }
  }
  return written;
}
#endif

std::array<bool, kFingerCount> parse_channels(const std::string& text) {
  std::array<bool, kFingerCount> on{};
  std::istringstream in(text);
  std::string item;
  bool any = false;
  while (std::getline(in, item, ',')) {
    if (item.size() != 1 || item[0] < '1' || item[0] > char('0' + kFingerCount))
      throw InputError("--channels", text, "channel numbers 1.." + std::to_string(kFingerCount) + " separated by commas");
    on[std::size_t(item[0] - '1')] = true;
    any = true;
  }
  if (!any) throw InputError("--channels", text, "at least one channel");
  return on;
}

std::string channels_text(const std::array<bool, kFingerCount>& on) {
  std::string s;
  for (std::size_t c = 0; c < kFingerCount; ++c)
    if (on[c]) s += (s.empty() ? "" : ",") + std::to_string(c + 1);
  return s;
}

RigConfig load_rig(const std::string& path) {
  return path.empty() ? load_rig_file(cli::data_dir() / "rigs" / "simulated.json") : load_rig_file(path);
}

// Simulated backends run on simulated time unless asked otherwise; hardware always in real time.
bool use_realtime(const RigConfig& rig, bool realtime_flag, bool fast_flag) {
  if (fast_flag && rig.backend != "simulated")
    throw InputError("--fast", rig.backend, "a simulated rig (hardware runs in real time)");
  return realtime_flag || rig.backend != "simulated";
}

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
  plan_options.staircase = plan_options.random = plan_options.sine = false;
  std::istringstream ex(a.excitation);
  for (std::string item; std::getline(ex, item, ',');) {
    if (item == "staircase") plan_options.staircase = true;
    else if (item == "random") plan_options.random = true;
    else if (item == "sine") plan_options.sine = true;
    else throw InputError("--excitation", a.excitation, "a list of staircase, random, sine");
  }
  const SweepSchedule plan = plan_calibration_sweep(plan_options, rig.safety.p_max_kPa);
  SweepRunOptions run = a.run;
  run.channels = parse_channels(a.channels);
  run.realtime = use_realtime(rig, a.realtime, a.fast);
  if (!(run.settle_window_s > 0) || !(run.settle_band_kPa > 0) || !(run.average_s > 0) ||
      !(run.max_hold_s > run.min_hold_s) || run.max_hold_s < run.settle_window_s + run.average_s ||
      !(run.max_hold_s <= 3600))
    throw InputError("--max-hold-s", std::to_string(run.max_hold_s),
                     "settle window, band and averaging window > 0, and a max hold above the min hold and both "
                     "windows, at most 3600 s");
  for (const auto& n : plan.notes) std::cerr << "palprig: note: " << n << "\n";

  auto backend = make_backend(rig);
  SweepFileInfo info;
  info.rig_id = rig.id;
  info.backend = backend->describe();
  info.date = utc_timestamp_now();
  info.p_max_kPa = rig.safety.p_max_kPa;
  info.rate_hz = run.rate_hz;
  if (const char* s = backend->sensor_name()) info.sensor_name = s;
  info.notes = plan.notes;
  SweepCsvWriter writer(a.out, info, run.channels);  // a path that cannot be written fails here, before open
  backend->open();

  cli::install_stop_signals();
  run.stop_signal = &cli::stop_signal();
  SweepSegment last_segment = SweepSegment::vent;
  int last_repeat = -1;
  const bool quiet = a.quiet;
  auto progress = [&](std::size_t done, std::size_t total, const SweepHold& hold, const HoldOutcome& result) {
    if (!result.settled)
      std::cerr << "palprig: warning: hold " << done << " (" << to_string(hold.segment) << " " << hold.level_kPa
                << " kPa) did not settle within " << run.max_hold_s << " s; kept, marked unsettled\n";
    if (quiet || hold.segment == SweepSegment::vent) return;
    if (hold.segment != last_segment || hold.repeat != last_repeat) {
      std::cerr << "sweep: " << to_string(hold.segment);
      if (hold.segment == SweepSegment::staircase) std::cerr << " repeat " << hold.repeat << "/" << plan_options.repeats;
      std::cerr << " (" << (100 * done / total) << " %, hold " << done << "/" << total << ")\n";
      last_segment = hold.segment;
      last_repeat = hold.repeat;
    }
  };
  const SweepOutcome outcome = run_calibration_sweep(*backend, plan, run, writer, progress);
  writer.finish(outcome);
  backend->close();
  std::cout << "palprig calibrate sweep: rig " << rig.id << " (" << info.backend << "), channels "
            << channels_text(run.channels) << ", " << (run.realtime ? "real time" : "simulated time") << "\n"
            << "  " << outcome.holds_done << " of " << outcome.holds_planned << " holds (" << outcome.holds_unsettled
            << " not settled) in " << outcome.duration_s << " s of rig time; " << writer.rows() << " rows -> " << a.out
            << "\n";
  if (outcome.stopped || outcome.faulted) {
    std::cerr << "palprig: sweep " << (outcome.stopped ? "stopped by signal " + std::to_string(outcome.stop_signal)
                                                        : "faulted: " + outcome.fault)
              << " after " << outcome.holds_done << " of " << outcome.holds_planned
              << " holds; all channels vented; what was recorded is in " << a.out << "\n";
    cli::finish(cli::kExitFault);
  }
}

struct FitArgs {
  std::string data, out, rig_id, stress, presses, base, plot_dir, loss = "none", source;
  double regulator_tolerance_kPa = 3.0, diastolic_mmHg = 60, systolic_mmHg = 120;
  HysteresisFitOptions hysteresis;
  bool no_refine = false, json = false;
  bool operators_given = false;
};

void run_fit(const FitArgs& a) {
  check_plot_available(a.plot_dir);
  CalibrationFitOptions o;
  o.hysteresis = a.hysteresis;
  o.operators_from_data = !a.operators_given;
  o.hysteresis.refine_thresholds = !a.no_refine;
  if (a.loss == "huber") o.hysteresis.loss = RobustLoss::huber;
  else if (a.loss == "cauchy") o.hysteresis.loss = RobustLoss::cauchy;
  if (a.source == "monitor") o.hysteresis_from = HysteresisSource::monitor;
  else if (a.source == "sensor") o.hysteresis_from = HysteresisSource::sensor;
  else if (a.source == "none") o.hysteresis_from = HysteresisSource::none;
  o.regulator_tolerance_kPa = a.regulator_tolerance_kPa;
  o.rig_id = a.rig_id;
  o.date = utc_timestamp_now();
  if (!a.base.empty()) o.base = load_calibration_file(a.base);
  if (!a.stress.empty()) {
    o.stress_pairs = read_stress_pairs_csv(a.stress);
    o.stress_file = a.stress;
  }
  if (!a.presses.empty()) {
    o.force_window = force_window_from_presses(a.presses, a.diastolic_mmHg, a.systolic_mmHg);
    o.force_file = a.presses;
  }
  const SweepData data = read_sweep_csv(a.data);
  const CalibrationResult result = fit_calibration(data, o);
  const nlohmann::json doc = calibration_json(result);
  write_calibration_file(a.out, doc);
  if (a.json) std::cout << doc.dump(2) << "\n";
  else print_fit_report(std::cout, result, a.out);
#ifdef PALPRIG_HAVE_GUI
  if (!a.plot_dir.empty())
    for (const auto& p : plot_fit(a.plot_dir, data, result)) std::cout << "  plot: " << p.string() << "\n";
#endif
}

struct EvaluateArgs {
  std::string rig_path, cal_path, channels = "1,2,3", out, plot_dir;
  EvaluationOptions options;
  bool realtime = false, fast = false, json = false;
  double min_improvement = 0;
};

void run_evaluate(const EvaluateArgs& a) {
  check_plot_available(a.plot_dir);
  const RigConfig rig = load_rig(a.rig_path);
  const CalibrationModels cal = load_calibration_file(a.cal_path);
  check_calibration_matches(cal, rig.id, rig.source);
  EvaluationOptions o = a.options;
  o.channels = parse_channels(a.channels);
  o.realtime = use_realtime(rig, a.realtime, a.fast);
  auto backend = make_backend(rig);
  backend->open();
  cli::install_stop_signals();
  o.stop_signal = &cli::stop_signal();
  const EvaluationResult r = evaluate_compensation(*backend, rig, cal, o);
  backend->close();
  if (a.json) {
    std::cout << evaluation_json(r, o.channels).dump(2) << "\n";
  } else {
    std::cout << "palprig calibrate evaluate: rig " << rig.id << " (" << backend->describe() << "), calibration "
              << a.cal_path << ", " << (o.realtime ? "real time" : "simulated time") << " at " << o.rate_hz << " Hz\n";
    print_evaluation_report(std::cout, r, o.channels);
  }
  if (!a.out.empty()) write_evaluation_trace_csv(a.out, r);
#ifdef PALPRIG_HAVE_GUI
  if (!a.plot_dir.empty())
    for (const auto& p : plot_evaluation(a.plot_dir, r, o.channels)) std::cout << "  plot: " << p.string() << "\n";
#endif
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

void register_calibrate_command(CLI::App& app) {
  CLI::App* cal = app.add_subcommand("calibrate", "Calibrate a rig: sweep, fit the models, evaluate the compensation");
  cal->require_subcommand(1);

  auto sa = std::make_shared<SweepArgs>();
  CLI::App* sweep = cal->add_subcommand("sweep", "Record inflation/deflation staircases (and identification excitations)");
  sweep->add_option("--rig", sa->rig_path, "Rig file (JSON); default: the simulated rig in data/rigs/simulated.json");
  sweep->add_option("--channels", sa->channels, "Channels to drive, e.g. 1,2,3 (the others stay vented)")->default_val("1,2,3");
  sweep->add_option("--from-kPa", sa->plan.from_kPa, "Lowest staircase level")->default_val(10.0);
  sweep->add_option("--to-kPa", sa->plan.to_kPa, "Highest staircase level (clamped to the rig's p_max)")->default_val(100.0);
  sweep->add_option("--step-kPa", sa->plan.step_kPa, "Staircase step")->default_val(10.0);
  sweep->add_option("--repeats", sa->plan.repeats, "Staircase repeats, each from vented")->default_val(5);
  sweep->add_option("--excitation", sa->excitation,
                    "staircase, random, sine (comma-separated); random and sine add reversals for the hysteresis fit")
      ->default_val("staircase");
  sweep->add_option("--random-levels", sa->plan.random_levels, "Levels of the random excitation")->default_val(60);
  sweep->add_option("--sine-cycles", sa->plan.sine_cycles, "Cycles of the shrinking stepped sine")->default_val(4);
  sweep->add_option("--sine-steps", sa->plan.sine_steps_per_cycle, "Levels per sine cycle")->default_val(16);
  sweep->add_option("--seed", sa->plan.seed, "Seed of the random excitation")->default_val(1u);
  sweep->add_option("--rate-hz", sa->run.rate_hz, "Command/record rate")->default_val(100.0)->check(CLI::Range(1.0, 10000.0));
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
  sweep->add_option("--out", sa->out, "Data file to write (CSV)")->required();
  sweep->callback([sa] { run_sweep(*sa); });

  auto fa = std::make_shared<FitArgs>();
  CLI::App* fit = cal->add_subcommand("fit", "Fit the models to sweep data and write the calibration file");
  fit->add_option("data", fa->data, "Sweep data (CSV from calibrate sweep, or a table typed in)")
      ->required()
      ->check(CLI::ExistingFile);
  fit->add_option("--out", fa->out, "Calibration file to write (JSON)")->required();
  fit->add_option("--rig-id", fa->rig_id, "Rig id (default: the data file's)");
  fit->add_option("--base", fa->base, "Calibration whose stress model and actuator lines are kept (default: paper 002)")
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
  fit->add_option("--max-threshold-kPa", fa->hysteresis.max_threshold_kPa, "Largest initial threshold (0: from the data)")
      ->default_val(0.0);
  fit->add_flag("--no-refine", fa->no_refine, "Keep the thresholds on the grid (weights only)");
  fit->add_option("--robust-loss", fa->loss, "none, huber or cauchy")
      ->default_val("none")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}));
  fit->add_option("--robust-scale-kPa", fa->hysteresis.loss_scale_kPa, "Where the robust loss bends")->default_val(1.0);
  fit->add_option("--hysteresis-from", fa->source, "monitor, sensor or none (default: monitor when recorded)")
      ->check(CLI::IsMember({"monitor", "sensor", "none"}));
  fit->add_option("--regulator-tolerance-kPa", fa->regulator_tolerance_kPa,
                  "Refuse a regulator whose monitor line is off the command by more")
      ->default_val(3.0);
  fit->add_option("--plot", fa->plot_dir, "Write PNG plots of the data and fitted lines to DIR");
  fit->add_flag("--json", fa->json, "Print the calibration file instead of the tables");
  fit->callback([fa, operators] {
    fa->operators_given = operators->count() > 0;
    run_fit(*fa);
  });

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
  ev->add_option("--min-improvement", ea->min_improvement, "Exit 1 when RMS off/on is below this on any channel")
      ->default_val(0.0);
  ev->add_flag("--json", ea->json, "Print the figures as one JSON object");
  ev->callback([ea] { run_evaluate(*ea); });
}
