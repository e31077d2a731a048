#pragma once
// What `palprig run` and `palprig demo` share: load and validate the files, open the backend,
// run the loop, and report.
#include <iosfwd>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/calibration_file.hpp"
#include "inputs/input_source.hpp"
#include "controller/loop_runner.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"

namespace palprig::cli {

struct RunArgs {
  std::string scene_path, input_spec = "sweep", rig_path, cal_path;
  // --duration-s was given: a trace longer than TraceLimits, or with long gaps, is run anyway
  // (the run stops at the given length).
  bool explicit_duration = false;
};

struct LoadedRun {
  RigConfig rig;
  CalibrationModels cal;
  SceneFile scene;
  TickConfig config;
  std::unique_ptr<InputSource> input;
  std::unique_ptr<RigBackend> backend;
};

// Live inputs (the pen tablet) make `palprig run` real time.
bool is_live_input(const std::string& spec);
std::unique_ptr<InputSource> make_input(const std::string& spec, const Scene& scene, double contact_force_N,
                                        const TabletConfig& tablet = {}, const TraceLimits& trace_limits = {});
LoadedRun load_run(const RunArgs& args);  // throws InputError before anything moves
RunSummary execute(LoadedRun& run, const RunOptions& opt);
nlohmann::json summary_json(const RunSummary& s, const LoadedRun& run, const RunOptions& opt);
void print_summary(std::ostream& out, const RunSummary& s, const LoadedRun& run, const RunOptions& opt);

}  // namespace palprig::cli
