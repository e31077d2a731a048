#pragma once
// A run of the loop as `palprig run`, `palprig demo` and the GUI start it: the files loaded and
// checked (InputError before anything moves), the input made, the timing settled, then the
// backend opened, the loop run and the backend closed.
#include <memory>
#include <optional>
#include <string>

#include "controller/loop_runner.hpp"
#include "controller/rig_lease.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "formats/tracking_file.hpp"
#include "inputs/input_source.hpp"
#include "inputs/tablet_input.hpp"

namespace palprig {

struct RunFiles {
  std::filesystem::path scene;
  std::filesystem::path rig;          // the caller's default when the user names none
  std::filesystem::path calibration;  // empty: paper 002's models
  // trace:FILE, sweep, tablet, tablet:/dev/input/eventN, tablet:FILE.evemu or igtl:HOST:PORT
  std::string input = "sweep";
  // igtl: the tracking file (tools -> fingers, fingertip offsets, registration); required there.
  std::filesystem::path tracking;
  // The user gave the run's length: a trace or pen recording longer than the bounds of
  // TraceLimits/PenRecordingLimits, or with gaps over the stale-input limit, is run anyway.
  bool explicit_duration = false;
  // Lag compensation of the whole target for this run (`--compensate-lag` / `--no-compensate-lag`):
  // overrides the calibration file's lag_compensation.enabled; unset: the file decides.
  std::optional<bool> compensate_lag;
};

struct LoadedRun {
  RigConfig rig;
  CalibrationModels cal;
  SceneFile scene;
  TickConfig config;
  std::unique_ptr<InputSource> input;
  std::string input_spec;
  std::optional<TrackingConfig> tracking;  // an igtl input's
  std::unique_ptr<Rig> rig_opened;         // opened by execute_run (the machine-wide lock of its device held)
  bool live = false;                       // hardware or a live pen: runs on the wall clock only
  // What the run does about the regulators' lag (controller/tick_setup.hpp's
  // describe_lag_compensation): lines for the front end to print before it runs.
  std::vector<std::string> lag_compensation_notes;
};

// How the user asked the run to be timed.
struct RunTiming {
  bool replay = false, realtime = false;  // neither: replay unless the run is live
  double duration_s = 0;                  // <= 0: the input's own length
};

// Live inputs (the pen tablet, a tracker) make a run real time.
bool is_live_input(const std::string& spec);
// Throws InputError naming the field "input" for a spec it does not know, and naming the file
// for a trace or recording over its bounds (with "give `duration_s`" as the way out). A
// tracker (igtl:HOST:PORT) needs its tracking file, and connects here: a server that cannot
// be reached is refused before anything moves.
std::unique_ptr<InputSource> make_input(const std::string& spec, const Scene& scene, double contact_force_N,
                                        const TabletConfig& tablet = {}, const TraceLimits& trace_limits = {},
                                        const TrackingConfig* tracking = nullptr, double max_pose_age_s = 0.1);

LoadedRun load_run(const RunFiles& files);  // throws InputError before anything moves
// Refused (InputError naming the calibration file and `lag_compensation`) when compensate_lag
// asks for lag compensation and no channel of the calibration has identified dynamics.
// The same without making the input (run.input stays empty): for a front end with an input of
// its own (the GUI's window pen), which then calls make_input for every other input.
LoadedRun load_run_files(const RunFiles& files);
// Mode and duration from the user's timing: a live run is real time (asking for a replay is
// refused, naming the field "replay"); a run with no length is refused ("duration_s"); a CPU
// the process may not run on is refused ("cpu").
void settle_timing(const LoadedRun& run, const RunTiming& timing, RunOptions& options);
// Opens the rig (open_rig), takes its lease, runs the loop, gives the rig back and closes it.
RunSummary execute_run(LoadedRun& run, const RunOptions& options);

}  // namespace palprig
