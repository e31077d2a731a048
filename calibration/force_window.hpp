#pragma once
// Paper 003's force window for the pulse amplitude, A = (F - F_min) / (F_max - F_min) * mu
// while F_min <= F <= F_max: F_min and F_max are the pressing forces read at reference presses
// of diastolic 60 and systolic 120 mmHg (a sphygmomanometer cuff over the sensor).
//
// Presses file (CSV, header required):  reference_mmHg,force_N   (several presses per level)
#include <filesystem>

#include "formats/calibration_file.hpp"

namespace palprig {

struct ForceWindowFit {
  MeasuredForceWindow window;
  double f_min_sd_N = 0, f_max_sd_N = 0;  // spread between presses (0 with one press)
  std::size_t presses_min = 0, presses_max = 0;
};

// Throws InputError for other reference levels, non-finite or negative forces, a level without
// presses, or F_max not above F_min.
ForceWindowFit force_window_from_presses(const std::filesystem::path& path, double diastolic_mmHg = 60.0,
                                         double systolic_mmHg = 120.0);

}  // namespace palprig
