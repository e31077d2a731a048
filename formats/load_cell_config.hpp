#pragma once
// The rig file's load cells: the pressing force measured under the fingertip (paper
// 003's FSR) instead of given by a pen. One cell shared by every finger, or one per finger, each
// read as a voltage on one of the rig's analog inputs and turned into newtons by its own
// calibration (tare, gain: models/load_cell.hpp).
//
//   "load_cells": {
//     "fingers": "each",                              ("each": 3 channels, finger 1..3 in order;
//                                                      "all": 1 channel whose force every finger gets)
//     "channels": [{"tare_V": 0.1, "N_per_V": 2.0,
//                   "input": {...}}, ...],            (the analog input; by backend:
//                                                      comedi: {"channel": 4, "volts_span": [0, 5]}
//                                                              on the card's AI subdevice;
//                                                      modbus: {"link": "io", "register": 4,
//                                                              "function": "input", "raw_full_scale":
//                                                              32767, "signed": false, "volts_span": [0, 10]};
//                                                      simulated: none)
//     "simulated": {"stiffness_N_per_mm": 0.5, "tare_V": 0.1, "N_per_V": 2.0,
//                   "noise_sd_V": 0.002, "seed": 11}  (the simulated rig's cells: their true
//                                                      tare and gain, which calibration finds)
//   }
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/modbus_register_map.hpp"
#include "models/load_cell.hpp"

namespace palprig {

struct RigConfig;

struct LoadCellChannel {
  LoadCellCalibration calibration;
  // Where it is read (the backend's field; the others unset).
  int comedi_channel = -1;
  double volts_lo = 0.0, volts_hi = 10.0;  // comedi: what the cell's amplifier sends
  std::optional<ModbusRegisterRef> modbus;
};

struct LoadCellConfig {
  bool per_finger = false;                // "each": channels[i] is finger i's
  std::vector<LoadCellChannel> channels;  // 1 ("all") or kFingerCount ("each")
  SimulatedLoadCellParams simulated;      // the simulated backend's cells (seed + channel index)
};

// Parses `load_cells` of a rig being loaded (its backend, and for Modbus its links, already
// parsed). Throws InputError naming the file and field.
LoadCellConfig parse_load_cell_config(const RigConfig& rig, const nlohmann::json& section);

}  // namespace palprig
