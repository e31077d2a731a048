// palprig run: the main job. Loads and validates every file first (exit 2 on a bad one, before
// anything is commanded), opens the backend, runs the loop and prints a summary.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "cli/commands.hpp"
#include "cli/run_setup.hpp"
#include "controller/loop_runner.hpp"
#include "inputs/tablet_input.hpp"
#include "models/parse_error.hpp"

using namespace palprig;

namespace palprig::cli {

bool is_live_input(const std::string& spec) { return spec == "tablet" || spec.rfind("tablet:", 0) == 0; }

std::unique_ptr<InputSource> make_input(const std::string& spec, const Scene& scene, double contact_force_N,
                                        const TabletConfig& tablet) {
  if (is_live_input(spec)) return make_tablet_input(spec, tablet);
  if (spec == "sweep") return std::make_unique<SweepInput>(scene.bounds(), SweepPlan{});
  if (spec.rfind("trace:", 0) == 0) {
    const std::filesystem::path p = spec.substr(6);
    return std::make_unique<TraceInput>(load_trace_csv(p, contact_force_N), p.string(), contact_force_N);
  }
  throw InputError("--input", spec, "trace:FILE, sweep, tablet, tablet:/dev/input/eventN or tablet:FILE.evemu");
}

LoadedRun load_run(const RunArgs& a) {
  LoadedRun run;
  run.rig = a.rig_path.empty() ? load_rig_file(data_dir() / "rigs" / "simulated.json") : load_rig_file(a.rig_path);
  run.cal = a.cal_path.empty() ? CalibrationModels{} : load_calibration_file(a.cal_path);
  check_calibration_matches(run.cal, run.rig.id, run.rig.source);
  run.scene = load_scene_file(a.scene_path);
  run.config = make_tick_config(run.rig, run.cal);
  run.input = make_input(a.input_spec, *run.scene.scene, run.rig.contact_force_N, run.rig.tablet);
  return run;
}

nlohmann::json summary_json(const RunSummary& s, const LoadedRun& run, const RunOptions& opt) {
  using nlohmann::json;
  auto stats = [](const std::array<RangeStats, kFingerCount>& a) {
    json arr = json::array();
    for (const auto& r : a) arr.push_back({{"min", r.min}, {"mean", r.mean()}, {"max", r.max}});
    return arr;
  };
  auto lat = [](const LatencySummary& l) {
    return json{{"p50_us", l.p50_us}, {"p99_us", l.p99_us}, {"p999_us", l.p999_us}, {"max_us", l.max_us}};
  };
  json j = {
      {"scene", run.scene.source},
      {"rig", run.rig.id},
      {"backend", run.backend ? run.backend->describe() : std::string("none")},
      {"input", run.input->describe()},
      {"mode", opt.mode == LoopMode::realtime ? "realtime" : "replay"},
      {"rate_hz", opt.rate_hz},
      {"ticks", s.ticks},
      {"overruns", s.overruns},
      {"missed_periods", s.missed_periods},
      {"link_outages", s.link_outages},
      {"unlinked_ticks", s.unlinked_ticks},
      {"sim_time_s", s.sim_time_s},
      {"wall_time_s", s.wall_time_s},
      {"speedup", s.wall_time_s > 0 ? s.sim_time_s / s.wall_time_s : 0.0},
      {"target_kPa", stats(s.target_kPa)},
      {"setpoint_kPa", stats(s.setpoint_kPa)},
      {"plant_kPa", stats(s.monitor_kPa)},
      {"fault", s.fault == FaultCode::none ? json(nullptr)
                                            : json{{"code", static_cast<int>(s.fault)},
                                                   {"reason", to_string(s.fault)},
                                                   {"detail", s.fault_detail},
                                                   {"t_s", s.fault_t_s}}},
      {"tick_time", lat(s.tick_time)},
      {"io_time", lat(s.io_time)},
      {"telemetry", s.telemetry_path.empty() ? json(nullptr) : json(s.telemetry_path)},
      {"telemetry_dropped", s.telemetry_dropped},
  };
  if (opt.mode == LoopMode::realtime) {
    j["wake_latency"] = lat(s.wake_latency);
    j["realtime_note"] = s.realtime_note;
  }
  return j;
}

void print_summary(std::ostream& out, const RunSummary& s, const LoadedRun& run, const RunOptions& opt) {
  out << "palprig run: " << run.scene.source << " on " << (run.backend ? run.backend->describe() : "?") << " ("
      << run.rig.id << "), input " << run.input->describe() << "\n";
  out << "  " << s.ticks << " ticks at " << opt.rate_hz << " Hz, " << std::fixed << std::setprecision(3);
  // A replay says how much faster than real time it ran; a real-time run took its own length
  // by design, so it says so rather than "13.290 s simulated in 13.290 s wall (1x)".
  if (opt.mode == LoopMode::realtime) {
    out << s.wall_time_s << " s in real time";
  } else {
    out << s.sim_time_s << " s simulated in " << s.wall_time_s << " s wall (" << std::setprecision(0)
        << (s.wall_time_s > 0 ? s.sim_time_s / s.wall_time_s : 0) << "x faster than real time)";
  }
  out << ", overruns " << s.overruns << " (" << s.missed_periods << " periods skipped)\n";
  out << std::setprecision(2);
  out << "  finger   target kPa min/mean/max      plant kPa min/mean/max\n";
  for (int i = 0; i < kFingerCount; ++i)
    out << "  " << i + 1 << "        " << std::setw(6) << s.target_kPa[i].min << " / " << std::setw(6)
        << s.target_kPa[i].mean() << " / " << std::setw(6) << s.target_kPa[i].max << "    " << std::setw(6)
        << s.monitor_kPa[i].min << " / " << std::setw(6) << s.monitor_kPa[i].mean() << " / " << std::setw(6)
        << s.monitor_kPa[i].max << "\n";
  out << std::setprecision(1) << "  tick time p50/p99/max " << s.tick_time.p50_us << "/" << s.tick_time.p99_us << "/"
      << s.tick_time.max_us << " us, backend I/O p50/p99/p99.9/max " << s.io_time.p50_us << "/" << s.io_time.p99_us
      << "/" << s.io_time.p999_us << "/" << s.io_time.max_us << " us\n";
  if (s.link_outages)
    out << "  link outages: " << s.link_outages << " (" << s.unlinked_ticks << " ticks vented while reconnecting)\n";
  if (opt.mode == LoopMode::realtime) {
    out << "  wake-up latency p50/p99/p99.9/max " << s.wake_latency.p50_us << "/" << s.wake_latency.p99_us << "/"
        << s.wake_latency.p999_us << "/" << s.wake_latency.max_us << " us\n";
    if (!s.realtime_note.empty()) out << "  note: " << s.realtime_note << "\n";
  }
  out << "  faults: " << (s.fault == FaultCode::none ? std::string("none") : std::string(to_string(s.fault)) +
                                                                               (s.fault_detail.empty() ? "" : ": " + s.fault_detail))
      << "\n";
  if (!s.telemetry_path.empty())
    out << "  telemetry: " << s.telemetry_path << (s.telemetry_dropped ? " (" + std::to_string(s.telemetry_dropped) + " records dropped)" : "")
        << "\n";
}

RunSummary execute(LoadedRun& run, const RunOptions& opt) {
  run.backend = make_backend(run.rig);
  run.backend->open();
  RunSummary s = run_loop(run.config, *run.scene.scene, *run.input, *run.backend, opt);
  run.backend->close();
  return s;
}

}  // namespace palprig::cli

void register_run_command(CLI::App& app) {
  // CLI11 binds options to these fields, so they live as long as the app (one shared object,
  // captured by the callback).
  struct Options {
    cli::RunArgs args;
    RunOptions run;
    bool json = false, replay = false, realtime = false;
    double duration_s = 0.0;
    std::string telemetry;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("run", "Run the loop: pen input -> scene -> pressures -> rig, and print a summary");
  sub->add_option("--scene", o->args.scene_path, "Scene file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--input", o->args.input_spec, "Pen input: trace:FILE (CSV t_s,x_mm,y_mm,force_N), sweep, tablet (the first pen tablet), "
                 "tablet:/dev/input/eventN, or tablet:FILE.evemu (a recording replayed in real time)")
      ->default_val("sweep");
  sub->add_option("--rig", o->args.rig_path, "Rig file (JSON); default: the simulated rig in data/rigs/simulated.json");
  sub->add_option("--cal", o->args.cal_path, "Calibration file (JSON); default: paper 002's models");
  sub->add_option("--rate-hz", o->run.rate_hz, "Loop rate in Hz")->default_val(1000.0)->check(CLI::Range(1.0, 100000.0));
  sub->add_option("--duration-s", o->duration_s, "Run length in seconds; default: the length of the input");
  auto* rt = sub->add_flag("--realtime", o->realtime, "Real time: absolute deadlines on the monotonic clock");
  sub->add_flag("--replay", o->replay, "As fast as possible on simulated time (default)")->excludes(rt);
  sub->add_flag("--no-fifo", [o](std::int64_t) { o->run.want_fifo = false; }, "Real time without SCHED_FIFO");
  sub->add_option("--telemetry", o->telemetry, "Write every tick to FILE (.csv, or .bin for the compact binary)");
  sub->add_flag("--json", o->json, "Print the summary as one JSON object");
  sub->callback([o]() {
    cli::LoadedRun run = cli::load_run(o->args);
    RunOptions opt = o->run;
    // Hardware and live pen input run on the wall clock: a replay would command real
    // regulators (or read a real pen) on simulated time.
    const bool live = run.rig.backend != "simulated" || cli::is_live_input(o->args.input_spec);
    if (live && o->replay)
      throw InputError("--replay", run.rig.backend != "simulated" ? "backend " + run.rig.backend : "--input " + o->args.input_spec,
                       "--realtime: hardware and live pen input run on the wall clock");
    opt.mode = (o->realtime || live) ? LoopMode::realtime : LoopMode::replay;
    opt.duration_s = o->duration_s > 0 ? o->duration_s : run.input->duration_s();
    if (!(opt.duration_s > 0))
      throw InputError("--duration-s", "value", "a positive duration (the input has no length of its own)");
    opt.telemetry_path = o->telemetry;
    cli::install_stop_signals();
    opt.stop_signal = &cli::stop_signal();
    const RunSummary s = cli::execute(run, opt);
    if (o->json) std::cout << cli::summary_json(s, run, opt).dump(2) << "\n";
    else cli::print_summary(std::cout, s, run, opt);
    if (s.fault != FaultCode::none) {
      std::cerr << "palprig: fault at t=" << s.fault_t_s << " s: " << to_string(s.fault)
                << (s.fault_detail.empty() ? "" : " (" + s.fault_detail + ")") << "; all channels vented\n";
      cli::finish(cli::kExitFault);
    }
  });
}
