#pragma once
// A calibration sweep recorded to its data file in one call: the file's header (rig, backend,
// date, p_max, rate, sensor, the plan's notes), run_calibration_sweep on an OPEN backend with
// every hold written as it ends, and the file's closing line. `palprig gui`'s calibration page
// calls this; `palprig calibrate sweep` composes the same calls (cli/calibrate_sweep_command).
// A stop (options.stop_signal) or a backend fault vents every channel and keeps what was
// recorded; the outcome says which.
#include <filesystem>

#include "calibration/sweep_csv.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_runner.hpp"
#include "formats/rig_file.hpp"

namespace palprig {

struct SweepRecording {
  SweepOutcome outcome;
  std::size_t rows = 0;
};

// Throws OutputError when `out` cannot be written (before anything moves).
SweepRecording record_calibration_sweep(RigLease& lease, const RigConfig& rig, const SweepSchedule& schedule,
                                        const SweepRunOptions& options, const std::filesystem::path& out,
                                        const SweepProgress& progress = {});

}  // namespace palprig
