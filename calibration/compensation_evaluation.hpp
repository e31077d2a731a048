#pragma once
// `palprig calibrate evaluate`: drive one test trajectory through the controller's own tick
// (tick_direct: hysteresis inverse, then the safety stage) on a backend, once without and
// once with the calibration's hysteresis compensation, and compare what the regulators report
// with the target:
//   - tracking RMS and worst error,
//   - the inflation/deflation gap: mean error while the target falls minus while it rises
//     (what hysteresis looks like; about twice the play half-width without compensation),
//   - R^2 of the output against the target (the identity line, not a fitted one).
// The trajectory ramps at a constant, slow rate between random turning points (reversals of
// many sizes, so minor loops too); slow, because the compensation is for the rate-independent
// hysteresis and the regulator's lag would otherwise dominate the error. The first approach
// from vented to the bottom of the range is not scored.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/excursions.hpp"
#include "calibration/progress_meter.hpp"
#include "formats/calibration_file.hpp"
#include "controller/rig_lease.hpp"
#include "rigs/rig_backend.hpp"
#include "runtime/run_control.hpp"
#include "formats/rig_file.hpp"

namespace palprig {

struct EvaluationOptions {
  double from_kPa = 10.0;
  double to_kPa = 0.0;  // 0: 80 % of the rig's p_max
  double ramp_kPa_per_s = 1.0;
  double duration_s = 120.0;  // per run, after the rest and the first approach
  double rest_s = 1.0;        // vented before each run
  double rate_hz = 1000.0;
  double record_hz = 50.0;  // trace kept for plots and --out
  unsigned seed = 7;
  bool realtime = true;
  std::array<bool, kFingerCount> channels{true, true, true};
  const RunControl* control = nullptr;  // the operator's handle: a stop request vents and ends the run
  // Where the ticks before a rig fault are written (controller/fault_recorder.hpp); empty: the
  // working folder.
  std::filesystem::path fault_record_folder;
  // A monitor further than this from the target is an excursion, reported with its time
  // (calibration/excursions.hpp).
  double tolerance_kPa = kDefaultRegulatorTolerance_kPa;
  // Progress of the two runs (phase "uncompensated run", "compensated run"; share of rig time),
  // at least every 5 s of wall time.
  ProgressSink progress;
};

struct TrackingMetrics {
  std::size_t samples = 0;
  double rms_error_kPa = 0, max_abs_error_kPa = 0;
  double mean_error_inflation_kPa = 0, mean_error_deflation_kPa = 0;
  double gap_kPa = 0;    // deflation minus inflation mean error
  double r_squared = 0;  // output against target
};

struct EvaluationTraceRow {
  double t_s = 0, target_kPa = 0;
  ChannelPressures setpoint_kPa{}, monitor_kPa{};
};

struct EvaluationRun {
  std::array<TrackingMetrics, kFingerCount> channels{};
  std::vector<EvaluationTraceRow> trace;
  double scored_from_t_s = 0;  // trace rows before this (rest, first approach) are not scored
  // Stretches of the scored part where a monitor was further from the target than the
  // tolerance, times from the run's start.
  std::vector<Excursion> excursions;
  bool stopped = false, faulted = false;
  std::string fault_record;  // after a rig fault: "the last N ticks before it: FILE"
  std::string fault;
};

struct EvaluationResult {
  double from_kPa = 0, to_kPa = 0, ramp_kPa_per_s = 0, duration_s = 0;
  double tolerance_kPa = kDefaultRegulatorTolerance_kPa;  // of the excursions
  std::size_t reversals = 0;
  EvaluationRun uncompensated, compensated;
  std::array<double, kFingerCount> improvement{};  // uncompensated RMS / compensated RMS
  double worst_improvement = 0;                    // over the evaluated channels
  bool complete() const noexcept {
    return !uncompensated.stopped && !uncompensated.faulted && !compensated.stopped && !compensated.faulted;
  }
};

// Throws InputError for a range outside 0..p_max, or a calibration without any hysteresis model
// on an evaluated channel (nothing to compare).
EvaluationResult evaluate_compensation(RigLease& lease, const RigConfig& rig, const CalibrationModels& cal,
                                       const EvaluationOptions& options);

}  // namespace palprig
