#pragma once
// `palprig calibrate fit` as a library call: from sweep data (and optional stress pairs and
// force-window presses) to every model the controller's calibration file holds, with the fit
// quality a lab engineer reads before trusting it. Nothing is written when any check fails:
// each refusal is an InputError naming the data file, the channel and what was wrong.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "calibration/branch_fits.hpp"
#include "calibration/dynamics_fit.hpp"
#include "calibration/force_window.hpp"
#include "calibration/hysteresis_fit.hpp"
#include "calibration/hysteresis_selection.hpp"
#include "calibration/stress_fit.hpp"
#include "calibration/progress_meter.hpp"
#include "calibration/sweep_csv.hpp"
#include "formats/calibration_file.hpp"

namespace palprig {

// What the hysteresis model maps the command to. monitor: the regulator's reported pressure
// (the simulated plant's hysteresis is there). sensor: the sensor reading converted to the
// pressure that gives it on the both-branch line, for actuators whose own deformation lags
// (paper 002's case), so the tick lands the deformation on the line.
enum class HysteresisSource { monitor, sensor, none };
const char* to_string(HysteresisSource s) noexcept;

// Which hysteresis model class a channel gets: chosen by held-out error over the sweep's runs
// (calibration/hysteresis_selection.hpp), or the one asked for.
enum class HysteresisModelClass { automatic, symmetric, asymmetric };
const char* to_string(HysteresisModelClass c) noexcept;

struct CalibrationFitOptions {
  HysteresisFitOptions hysteresis;
  HysteresisModelClass hysteresis_model = HysteresisModelClass::automatic;
  // When true (no --operators given), hysteresis.operator_count is the most a channel gets:
  // fewer when its quasi-static samples support fewer (4 per parameter), with a note saying so.
  bool operators_from_data = false;
  std::optional<HysteresisSource> hysteresis_from;  // default: monitor when the data has it, else none
  double regulator_tolerance_kPa = 3.0;
  double monotone_tolerance = 0.02;  // fraction of a branch's span a reading may step back
  std::string rig_id;                // overrides the data file's "# rig_id"
  std::string date;                  // when the fit was made (ISO 8601)
  CalibrationModels base;            // stress model and the lines of channels without stress data
  std::vector<StressPair> stress_pairs;
  std::string stress_file;
  std::optional<ForceWindowFit> force_window;
  std::string force_file;
  // The regulator dynamics fit (from step and chirp rows) and what the file's lag_compensation
  // section says: whether the tick compensates the whole target with them (off unless asked),
  // the lead bound and the R^2 a channel's fit needs.
  DynamicsFitOptions dynamics;
  LagCompensationChoice lag_compensation;
  // Progress: a line per channel fitted (phase "channel 2 of 3"; share: channels done), once
  // the fit has run 2 s.
  ProgressSink progress;
};

struct ChannelCalibration {
  int channel = 0;  // 1-based
  bool swept = false;
  std::size_t points = 0;
  std::optional<BranchFits> regulator;  // monitor against command (staircase)
  std::optional<RegulatorCheck> regulator_check;
  std::optional<BranchFits> response;  // sensor against command (staircase)
  std::optional<HysteresisFit> hysteresis;
  std::optional<HysteresisSelection> hysteresis_selection;  // when the class was chosen by held-out error
  HysteresisSource hysteresis_source = HysteresisSource::none;
  ActuatorModel actuator;
  std::optional<LineFit> stress_line;     // when fitted from stress pairs
  std::optional<DynamicsFit> dynamics;    // when the data has step or chirp rows
  bool dynamics_usable() const noexcept;  // identified with R^2 at or above the bound
  double min_r_squared = kDefaultMinDynamicsRSquared;
};

struct CalibrationResult {
  std::string rig_id, date, data_file, sensor_name;
  std::array<ChannelCalibration, kFingerCount> channels;
  std::optional<BranchFits> pooled_regulator, pooled_response;  // all swept channels together
  StressModel stress;
  std::optional<ForceWindowFit> force_window;
  std::string stress_file, force_file;
  LagCompensationChoice lag_compensation;
  std::vector<std::string> notes;
};

CalibrationResult fit_calibration(const SweepData& data, const CalibrationFitOptions& options);

}  // namespace palprig
