// palprig demo: the bundled phantom (tumors A, B, C), a pen trace passing over them and the
// default simulated rig, with a table showing that fingers over a tumor get more pressure than
// fingers over soft tissue. No hardware, no display.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <vector>

#include "cli/commands.hpp"
#include "controller/region_table.hpp"
#include "controller/run_report.hpp"
#include "controller/run_setup.hpp"
#include "runtime/run_control.hpp"

using namespace palprig;

void register_demo_command(CLI::App& app) {
  auto out_dir = std::make_shared<std::string>("/tmp/palprig-demo");
  auto json_out = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "demo",
      "Run the bundled phantom (tumors A, B, C) with a recorded pen pass on the simulated rig and show the "
      "pressure each finger got over each tumor and over soft tissue");
  sub->add_option("--out", *out_dir, "Directory for the telemetry file")->default_val("/tmp/palprig-demo");
  sub->add_flag("--json", *json_out, "Print the run summary and the table as JSON");
  auto cal_file = std::make_shared<std::string>();
  auto compensate = std::make_shared<bool>(false);
  sub->add_option("--cal", *cal_file,
                  "Calibration file (JSON); default: paper 002's models (with --compensate-lag: "
                  "the simulated rig's calibration, data/calibration/sim-default.json)");
  sub->add_flag("--compensate-lag", *compensate,
                "Lag-compensate the whole target with the calibration's identified regulator dynamics");
  sub->callback([=]() {
    const auto data = cli::data_dir();
    RunFiles files;
    files.scene = data / "scenes" / "phantom_abc.json";
    files.input = "trace:" + (data / "traces" / "phantom_abc_pass.csv").string();
    files.rig = data / "rigs" / "simulated.json";
    files.calibration = !cal_file->empty() ? std::filesystem::path(*cal_file)
                        : *compensate      ? data / "calibration" / "sim-default.json"
                                           : data / "calibration" / "paper002.json";
    if (*compensate) files.compensate_lag = true;
    LoadedRun run = load_run(files);
    for (const auto& note : run.lag_compensation_notes) std::cerr << "palprig: " << note << "\n";
    std::filesystem::create_directories(*out_dir);
    RegionTable table(run.scene.tumors, run.config.contact_force_N, 8.0);
    RunOptions opt;
    opt.rate_hz = 1000;
    opt.duration_s = run.input->duration_s();
    opt.mode = LoopMode::replay;
    opt.telemetry_path = std::filesystem::path(*out_dir) / "telemetry.csv";
    opt.observer = &table;
    install_stop_signals();
    opt.control = &process_run_control();
    const RunSummary s = execute_run(run, opt);

    const bool all_higher = table.tumors_feel_harder();
    if (*json_out) {
      nlohmann::json j = run_summary_json(s, run, opt);
      j["regions"] = table.json();
      j["tumors_feel_harder"] = all_higher;
      std::cout << j.dump(2) << "\n";
    } else {
      print_run_summary(std::cout, s, run, opt);
      table.print(std::cout, s.fault == FaultCode::none ? "" : std::string(to_string(s.fault.code)), s.fault.t_s);
    }
    if (s.fault != FaultCode::none) cli::finish(cli::kExitFault);
    if (!all_higher) cli::finish(cli::kExitFault);
  });
}
