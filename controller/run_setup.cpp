#include "controller/run_setup.hpp"

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "inputs/igtl_input.hpp"
#include "models/parse_error.hpp"
#include "runtime/realtime.hpp"

namespace palprig {

bool is_live_input(const std::string& spec) {
  return spec == "tablet" || spec.rfind("tablet:", 0) == 0 || is_igtl_input(spec);
}

std::unique_ptr<InputSource> make_input(const std::string& spec, const Scene& scene, double contact_force_N,
                                        const TabletConfig& tablet, const TraceLimits& trace_limits,
                                        const TrackingConfig* tracking, double max_pose_age_s) {
  if (is_igtl_input(spec)) {
    const IgtlEndpoint endpoint = parse_igtl_spec(spec);
    if (!tracking)
      throw InputError("input", spec, "a tracking file with it (--tracking FILE: which tool is which finger, docs/tracking.md)");
    return std::make_unique<IgtlInput>(endpoint, *tracking, max_pose_age_s);
  }
  const bool unbounded = trace_limits.max_length_s == TraceLimits::unbounded().max_length_s;
  if (is_live_input(spec)) {
    try {
      return make_tablet_input(spec, tablet, unbounded ? PenRecordingLimits::unbounded() : PenRecordingLimits{});
    } catch (const PenRecordingBoundError& e) {
      throw InputError(e.file(), e.where(), e.expected() + "; give `duration_s` to run it anyway");
    }
  }
  // "sweep" is the command line's historical word for the pen raster; "raster" is its name in code.
  if (spec == "sweep" || spec == "raster") return std::make_unique<RasterInput>(scene.bounds(), RasterPlan{});
  if (spec.rfind("trace:", 0) == 0) {
    const std::filesystem::path p = spec.substr(6);
    try {
      return std::make_unique<TraceInput>(load_trace_csv(p, contact_force_N, trace_limits), p.string(), contact_force_N);
    } catch (const TraceBoundError& e) {
      throw InputError(e.file(), e.where(), e.expected() + "; give `duration_s` to run it anyway");
    }
  }
  throw InputError("input", spec, "trace:FILE, sweep, tablet, tablet:/dev/input/eventN, tablet:FILE.evemu or igtl:HOST:PORT");
}

LoadedRun load_run_files(const RunFiles& files) {
  LoadedRun run;
  run.rig = load_rig_file(files.rig);
  run.cal = files.calibration.empty() ? CalibrationModels{} : load_calibration_file(files.calibration);
  check_calibration_matches(run.cal, run.rig.id, run.rig.source);
  run.scene = load_scene_file(files.scene);
  run.config = make_tick_config(run.rig, run.cal);
  run.input_spec = files.input;
  run.live = run.rig.backend != "simulated" || is_live_input(files.input);
  if (is_igtl_input(files.input)) {
    (void)parse_igtl_spec(files.input);
    if (files.tracking.empty())
      throw InputError("tracking", "input " + files.input, "a tracking file (--tracking FILE) that maps the tracker's tools to fingers (docs/tracking.md)");
    run.tracking = load_tracking_file(files.tracking);
    // A tracker gives positions only: the pressing force is the load cells'.
    if (!run.rig.load_cells)
      throw InputError(run.rig.source, "load_cells",
                       "load cells measuring the pressing force, for input " + files.input +
                           " (a tracker gives positions only; docs/tracking.md)");
  } else if (!files.tracking.empty()) {
    throw InputError("tracking", files.tracking.string(), "--input igtl:HOST:PORT with it (a tracking file is for a tracker)");
  }
  return run;
}

LoadedRun load_run(const RunFiles& files) {
  LoadedRun run = load_run_files(files);
  TraceLimits limits;
  limits.max_gap_s = run.rig.safety.max_input_age_s;
  run.input = make_input(files.input, *run.scene.scene, run.rig.contact_force_N, run.rig.tablet,
                         files.explicit_duration ? TraceLimits::unbounded() : limits,
                         run.tracking ? &*run.tracking : nullptr, run.rig.safety.max_input_age_s);
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
                     "`realtime`: hardware, live pen and tracker input run on the wall clock");
  }
  options.mode = (timing.realtime || run.live) ? LoopMode::realtime : LoopMode::replay;
  options.duration_s = timing.duration_s > 0 ? timing.duration_s : run.input->duration_s();
  if (!(options.duration_s > 0)) {
    throw InputError("duration_s", "value", "a positive duration (the input has no length of its own)");
  }
  if (options.realtime.cpu >= 0 && !cpu_allowed(options.realtime.cpu))
    throw InputError("cpu", std::to_string(options.realtime.cpu), "a CPU this process may run on (" + allowed_cpus_text() + ")");
}

RunSummary execute_run(LoadedRun& run, const RunOptions& options) {
  run.backend = make_backend(run.rig);
  run.backend->open();
  RunSummary s = run_loop(run.config, *run.scene.scene, *run.input, *run.backend, options);
  run.backend->close();
  return s;
}

}  // namespace palprig
