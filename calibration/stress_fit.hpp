#pragma once
// The stress model's actuator line (paper 002 fig. 12): fingertip stress at the interaction
// centre regressed on air pressure, stress = slope * p + intercept, from (pressure, stress)
// pairs measured on the rig or computed by FE. Its inverse (ActuatorModel::pressure_for_stress_kPa)
// gives the pressure for a target stress: with the paper's line, 7.967 kPa needs 11.75 kPa.
//
// Pairs file (CSV, header required):  pressure_kPa,stress_kPa[,channel]
// A row without a channel (column absent or cell empty) applies to every channel.
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/line_fit.hpp"
#include "models/stress_model.hpp"

namespace palprig {

struct StressPair {
  int channel = 0;  // 0: every channel
  double pressure_kPa = 0, stress_kPa = 0;
};

std::vector<StressPair> read_stress_pairs_csv(const std::filesystem::path& path);

struct ActuatorFit {
  ActuatorModel model;
  LineFit line;
};

// The line for one channel (1-based) from its own pairs and the shared ones. Throws InputError
// for too few pairs, constant data or a stress that does not rise with pressure.
ActuatorFit fit_actuator_stress(const std::vector<StressPair>& pairs, int channel, const std::string& file);

}  // namespace palprig
