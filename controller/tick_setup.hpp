#pragma once
// The tick's configuration from a rig file and its calibration: the one place that decides
// which rig and calibration fields the hot path uses.
#include <string>
#include <vector>

#include "controller/tick.hpp"
#include "formats/rig_file.hpp"
#include "models/calibration_models.hpp"

namespace palprig {

TickConfig make_tick_config(const RigConfig& rig, const CalibrationModels& cal);

// Whether channel i's identified dynamics may drive the lag compensation of its whole target:
// empty when it may, else why not ("no identified dynamics", "R^2 0.912 below 0.98").
std::string lag_compensation_refusal(const CalibrationModels& cal, std::size_t i);
// What a run with this calibration does about the regulators' lag, one line per point, for
// `palprig run` and `demo` to print: on or off, and per channel why a channel stays off.
std::vector<std::string> describe_lag_compensation(const CalibrationModels& cal);

}  // namespace palprig
