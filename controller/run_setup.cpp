#include "controller/run_setup.hpp"

#include <algorithm>
#include <cmath>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "formats/function_scene_file.hpp"
#include "inputs/igtl_input.hpp"
#include "models/tissue_scene.hpp"
#include "core/input_error.hpp"
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
      throw InputError("input", spec,
                       "a tracking file with it (--tracking FILE: which tool is which finger, docs/tracking.md)");
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
      return std::make_unique<TraceInput>(load_trace_csv(p, contact_force_N, trace_limits), p.string(),
                                          contact_force_N);
    } catch (const TraceBoundError& e) {
      throw InputError(e.file(), e.where(), e.expected() + "; give `duration_s` to run it anyway");
    }
  }
  throw InputError("input", spec,
                   "trace:FILE, sweep, tablet, tablet:/dev/input/eventN, tablet:FILE.evemu or igtl:HOST:PORT");
}

LoadedRun load_run_files(const RunFiles& files) {
  LoadedRun run;
  run.rig = load_rig_file(files.rig);
  run.cal = files.calibration.empty() ? CalibrationModels{} : load_calibration_file(files.calibration);
  check_calibration_matches(run.cal, run.rig.id, run.rig.source);
  if (files.compensate_lag) {
    run.cal.lag_compensation.enabled = *files.compensate_lag;
    bool any = false;
    for (std::size_t i = 0; i < kFingerCount; ++i) any = any || run.cal.dynamics[i].has_value();
    if (*files.compensate_lag && !any)
      throw InputError(
          files.calibration.empty() ? std::string("(paper 002's models: no --cal)") : files.calibration.string(),
          "lag_compensation",
          "identified regulator dynamics (channels[].dynamics) for --compensate-lag: calibrate sweep "
          "--excitation staircase,random,sine,step,chirp, then calibrate fit");
  }
  run.scene = load_scene_file(files.scene);
  run.config = make_tick_config(run.rig, run.cal);
  run.lag_compensation_notes = describe_lag_compensation(run.cal);
  // Compensating the whole target samples the scene ahead too (up to three more times per finger
  // and tick): on a function scene only as often as the tick's sampling budget leaves room for.
  if (const auto* fs = dynamic_cast<const FunctionScene*>(run.scene.scene.get());
      fs && run.config.lag_compensation.whole_target) {
    const double per_tick = double(kFingerCount) * fs->field().worst_case_sample_cost();
    const int room = per_tick > 0 ? static_cast<int>(std::floor(kMaxTickShapeCost / per_tick)) - 1 : 3;
    LagCompensationSetting& lag = run.config.lag_compensation;
    lag.samples_ahead = std::clamp(room, 0, lag.samples_ahead);
    if (lag.samples_ahead < 3)
      run.lag_compensation_notes.push_back(
          lag.samples_ahead == 0
              ? "the scene is too costly to sample ahead within a tick: lag compensation "
                "compensates toward the target now, without looking ahead"
              : "the scene is costly to sample: lag compensation looks ahead " + std::to_string(lag.samples_ahead) +
                    " time(s) per finger and tick (edges " +
                    std::string(lag.samples_ahead < 2 ? "not anticipated" : "anticipated coarsely") + ")");
  }
  run.input_spec = files.input;
  run.live = run.rig.backend != "simulated" || is_live_input(files.input);
  if (is_igtl_input(files.input)) {
    (void)parse_igtl_spec(files.input);
    if (files.tracking.empty())
      throw InputError("tracking", "input " + files.input,
                       "a tracking file (--tracking FILE) that maps the tracker's tools to fingers (docs/tracking.md)");
    run.tracking = load_tracking_file(files.tracking);
    // A tracker gives positions only: the pressing force is the load cells'.
    if (!run.rig.load_cells)
      throw InputError(run.rig.source, "load_cells",
                       "load cells measuring the pressing force, for input " + files.input +
                           " (a tracker gives positions only; docs/tracking.md)");
  } else if (!files.tracking.empty()) {
    throw InputError("tracking", files.tracking.string(),
                     "--input igtl:HOST:PORT with it (a tracking file is for a tracker)");
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
    throw InputError("cpu", std::to_string(options.realtime.cpu),
                     "a CPU this process may run on (" + allowed_cpus_text() + ")");
}

RunSummary execute_run(LoadedRun& run, const RunOptions& options) {
  run.rig_opened = open_rig(run.rig);
  RigLease lease = run.rig_opened->lease("palprig run");
  return run_loop(run.config, *run.scene.scene, *run.input, lease, options);
}

}  // namespace palprig
