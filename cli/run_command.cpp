// palprig run: the main job. Parses the options, then controller/run_setup loads and validates
// every file (exit 2 on a bad one, before anything is commanded), opens the backend and runs the
// loop; the summary is printed here.
#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "controller/region_table.hpp"
#include "controller/run_report.hpp"
#include "controller/run_setup.hpp"
#include "runtime/run_control.hpp"

using namespace palprig;

void register_run_command(CLI::App& app) {
  // CLI11 binds options to these fields, so they live as long as the app (one shared object,
  // captured by the callback).
  struct Options {
    RunFiles files;
    RunTiming timing;
    RunOptions run;
    bool json = false;
    bool regions = false;
    std::string telemetry;
    int compensate_lag = 0;  // +1 --compensate-lag, -1 --no-compensate-lag, 0 the calibration file decides
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      app.add_subcommand("run", "Run the loop: pen input -> scene -> pressures -> rig, and print a summary");
  sub->add_option("--scene", o->files.scene, "Scene file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--input", o->files.input,
                  "Pen input: trace:FILE (CSV t_s,x_mm,y_mm,force_N), sweep, tablet (the first pen tablet), "
                  "tablet:/dev/input/eventN, tablet:FILE.evemu (a recording replayed in real time), or igtl:HOST:PORT "
                  "(tracked fingers from an OpenIGTLink server, with --tracking)")
      ->default_val("sweep");
  sub->add_option("--tracking", o->files.tracking,
                  "With --input igtl:HOST:PORT: the tracking file (which tool is which finger, fingertip offsets, "
                  "tracker-to-scene registration)")
      ->check(CLI::ExistingFile);
  sub->add_option("--rig", o->files.rig, "Rig file (JSON); default: the simulated rig in data/rigs/simulated.json");
  sub->add_option("--cal", o->files.calibration, "Calibration file (JSON); default: paper 002's models");
  sub->add_option("--rate-hz", o->run.rate_hz, "Loop rate in Hz")
      ->default_val(1000.0)
      ->check(CLI::Range(1.0, 100000.0));
  sub->add_option("--duration-s", o->timing.duration_s, "Run length in seconds; default: the length of the input");
  auto* rt = sub->add_flag("--realtime", o->timing.realtime, "Real time: absolute deadlines on the monotonic clock");
  sub->add_flag("--replay", o->timing.replay, "As fast as possible on simulated time (default)")->excludes(rt);
  sub->add_flag(
      "--no-fifo", [o](std::int64_t) { o->run.want_fifo = false; }, "Real time without SCHED_FIFO");
  sub->add_option(
         "--priority", o->run.realtime.fifo_priority,
         "SCHED_FIFO priority of the loop in real time (the Modbus bus thread and the tablet reader run below it)")
      ->default_val(80)
      ->check(CLI::Range(1, 98));
  sub->add_option("--cpu", o->run.realtime.cpu,
                  "Pin the real-time loop to this CPU (e.g. one in isolcpus); default: not pinned")
      ->check(CLI::Range(0, 1023));
  sub->add_flag(
      "--no-pm-qos", [o](std::int64_t) { o->run.realtime.pm_qos = false; },
      "Real time without holding /dev/cpu_dma_latency at 0 (lets the CPUs sleep deeply: a laptop on battery)");
  sub->add_flag("--compensate-lag,!--no-compensate-lag", o->compensate_lag,
                "Lag-compensate the whole target with the calibration's identified regulator dynamics (or not), "
                "whatever the calibration file's lag_compensation.enabled says");
  sub->add_option("--telemetry", o->telemetry, "Write every tick to FILE (.csv, or .bin for the compact binary)");
  sub->add_flag("--json", o->json, "Print the summary as one JSON object");
  sub->add_flag("--regions", o->regions,
                "Also print the pressure per region (each tumor, soft tissue) as the demo does");
  sub->callback([o]() {
    RunFiles files = o->files;
    files.explicit_duration = o->timing.duration_s > 0;
    if (o->compensate_lag != 0) files.compensate_lag = o->compensate_lag > 0;
    if (files.rig.empty()) files.rig = cli::data_dir() / "rigs" / "simulated.json";
    LoadedRun run = load_run(files);
    for (const auto& note : run.lag_compensation_notes) std::cerr << "palprig: " << note << "\n";
    RunOptions opt = o->run;
    settle_timing(run, o->timing, opt);
    opt.telemetry_path = o->telemetry;
    install_stop_signals();
    opt.control = &process_run_control();
    RegionTable table(run.scene.tumors, run.config.contact_force_N);
    if (o->regions) opt.observer = &table;
    const RunSummary s = execute_run(run, opt);
    if (o->json) {
      nlohmann::json j = run_summary_json(s, run, opt);
      if (o->regions) j["regions"] = table.json();
      std::cout << j.dump(2) << "\n";
    } else {
      print_run_summary(std::cout, s, run, opt);
      if (o->regions)
        table.print(std::cout, s.fault == FaultCode::none ? "" : std::string(to_string(s.fault.code)), s.fault.t_s);
    }
    if (s.fault != FaultCode::none) {
      std::cerr << "palprig: fault at t=" << s.fault.t_s << " s: " << to_string(s.fault)
                << (s.fault.detail().empty() ? "" : " (" + s.fault.detail() + ")") << "; all channels vented; "
                << s.fault_record << "\n";
      cli::finish(cli::kExitFault);
    }
  });
}
