#include "controller/run_setup.hpp"

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "models/parse_error.hpp"

namespace palprig {

bool is_live_input(const std::string& spec) { return spec == "tablet" || spec.rfind("tablet:", 0) == 0; }

std::unique_ptr<InputSource> make_input(const std::string& spec, const Scene& scene, double contact_force_N,
                                        const TabletConfig& tablet) {
  if (is_live_input(spec)) return make_tablet_input(spec, tablet);
  if (spec == "sweep") return std::make_unique<SweepInput>(scene.bounds(), SweepPlan{});
  if (spec.rfind("trace:", 0) == 0) {
    const std::filesystem::path p = spec.substr(6);
    return std::make_unique<TraceInput>(load_trace_csv(p, contact_force_N), p.string(), contact_force_N);
  }
  throw InputError("input", spec, "trace:FILE, sweep, tablet, tablet:/dev/input/eventN or tablet:FILE.evemu");
}

LoadedRun load_run(const RunFiles& files) {
  LoadedRun run;
  run.rig = load_rig_file(files.rig);
  run.cal = files.calibration.empty() ? CalibrationModels{} : load_calibration_file(files.calibration);
  check_calibration_matches(run.cal, run.rig.id, run.rig.source);
  run.scene = load_scene_file(files.scene);
  run.config = make_tick_config(run.rig, run.cal);
  run.input = make_input(files.input, *run.scene.scene, run.rig.contact_force_N, run.rig.tablet);
  // Hardware and live pen input run on the wall clock: a replay would command real regulators
  // (or read a real pen) on simulated time.
  run.input_spec = files.input;
  run.live = run.rig.backend != "simulated" || is_live_input(files.input);
  return run;
}

void settle_timing(const LoadedRun& run, const RunTiming& timing, RunOptions& options) {
  if (run.live && timing.replay) {
    throw InputError("replay",
                     run.rig.backend != "simulated" ? "backend " + run.rig.backend : "input " + run.input_spec,
                     "`realtime`: hardware and live pen input run on the wall clock");
  }
  options.mode = (timing.realtime || run.live) ? LoopMode::realtime : LoopMode::replay;
  options.duration_s = timing.duration_s > 0 ? timing.duration_s : run.input->duration_s();
  if (!(options.duration_s > 0)) {
    throw InputError("duration_s", "value", "a positive duration (the input has no length of its own)");
  }
}

RunSummary execute_run(LoadedRun& run, const RunOptions& options) {
  run.backend = make_backend(run.rig);
  run.backend->open();
  RunSummary s = run_loop(run.config, *run.scene.scene, *run.input, *run.backend, options);
  run.backend->close();
  return s;
}

}  // namespace palprig
