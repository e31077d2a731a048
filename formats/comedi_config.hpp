#pragma once
// The comedi section of a rig file: a DAQ card's analog outputs drive the regulators and its
// analog inputs read their monitor voltages.
//
//   "backend": "comedi",
//   "comedi": {"device": "/dev/comedi0", "calibration": "auto", "ai_reference": "ground",
//              "ao_subdevice": 1, "ai_subdevice": 0},            (subdevices: default the first
//                                                                 AO / AI subdevice of the card)
//   "channels": [{"output":  {"channel": 0, "volts_span": [0, 10], "kPa_per_volt": 10},
//                 "monitor": {"channel": 0, "volts_span": [0, 10], "kPa_per_volt": 10}}, ...]
//
// volts_span is what the regulator accepts (output) or sends (monitor); the card's range is the
// smallest one that holds it (comedi_find_range), and outputs are clamped to the span before
// conversion. calibration: "auto" (soft calibration where the board needs it, else the board's
// own), "soft" (a comedi_soft_calibrate file, optional calibration_file), "hard" (the board's
// hardware calibration, or the nominal range for boards without any).
#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "models/regulator_scale.hpp"
#include "models/finger_layout.hpp"

namespace palprig {

struct RigConfig;

enum class ComediCalibration { automatic, soft, hard };
enum class ComediReference { ground, common, differential, other };

struct ComediChannelSpec {
  int channel = 0;
  double volts_lo = 0.0, volts_hi = 10.0;
  RegulatorScale regulator;
};

struct ComediRigConfig {
  std::string source, rig_id;
  std::string device = "/dev/comedi0";
  int ao_subdevice = -1, ai_subdevice = -1;  // -1: the first of that type
  ComediCalibration calibration = ComediCalibration::automatic;
  std::string calibration_file;  // soft calibration; empty: comedi's default path
  ComediReference ai_reference = ComediReference::ground;
  std::array<ComediChannelSpec, kFingerCount> outputs{}, monitors{};
  double p_max_kPa = 60.0;
};

// Parse and validate the "comedi" section (with the rig file's "channels" array under
// "channels") of a rig being loaded; load_rig_file calls it once and keeps the result in
// RigConfig::comedi. Throws InputError naming the file and field.
ComediRigConfig parse_comedi_config(const RigConfig& rig, const nlohmann::json& backend_section);

}  // namespace palprig
