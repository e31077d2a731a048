#pragma once
// A run of the loop as `palprig run`, `palprig demo` and the GUI start it: the files loaded and
// checked (InputError before anything moves), the input made, the timing settled, then the
// backend opened, the loop run and the backend closed.
#include <memory>
#include <string>

#include "controller/loop_runner.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "inputs/input_source.hpp"
#include "inputs/tablet_input.hpp"

namespace palprig {

struct RunFiles {
  std::filesystem::path scene;
  std::filesystem::path rig;          // the caller's default when the user names none
  std::filesystem::path calibration;  // empty: paper 002's models
  // trace:FILE, sweep, tablet, tablet:/dev/input/eventN or tablet:FILE.evemu
  std::string input = "sweep";
};

struct LoadedRun {
  RigConfig rig;
  CalibrationModels cal;
  SceneFile scene;
  TickConfig config;
  std::unique_ptr<InputSource> input;
  std::string input_spec;
  std::unique_ptr<RigBackend> backend;  // made by execute_run
  bool live = false;  // hardware or a live pen: runs on the wall clock only
};

// How the user asked the run to be timed.
struct RunTiming {
  bool replay = false, realtime = false;  // neither: replay unless the run is live
  double duration_s = 0;                  // <= 0: the input's own length
};

// Live inputs (the pen tablet) make a run real time.
bool is_live_input(const std::string& spec);
// Throws InputError naming the field "input" for a spec it does not know.
std::unique_ptr<InputSource> make_input(const std::string& spec, const Scene& scene, double contact_force_N,
                                        const TabletConfig& tablet = {});

LoadedRun load_run(const RunFiles& files);  // throws InputError before anything moves
// Mode and duration from the user's timing: a live run is real time (asking for a replay is
// refused, naming the field "replay"); a run with no length is refused ("duration_s").
void settle_timing(const LoadedRun& run, const RunTiming& timing, RunOptions& options);
// Opens the backend, runs the loop, closes the backend.
RunSummary execute_run(LoadedRun& run, const RunOptions& options);

}  // namespace palprig
