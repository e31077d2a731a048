#pragma once
// The tick's configuration from a rig file and its calibration: the one place that decides
// which rig and calibration fields the hot path uses.
#include "controller/tick.hpp"
#include "formats/rig_file.hpp"
#include "models/calibration_models.hpp"

namespace palprig {

TickConfig make_tick_config(const RigConfig& rig, const CalibrationModels& cal);

}  // namespace palprig
