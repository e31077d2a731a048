#pragma once
// The finite-element runs as text: the CSV tables `palprig fe indent|actuator` write (the
// command writes them through models/checked_output) and the lines it prints. Pure formatting.
#include <string>

#include "mechanics/contact_problems.hpp"

namespace palprig::mechanics {

// One row per step: load_column (depth_mm or pressure_kPa), peak_kPa (averaged over 1 mm),
// node_peak_kPa, peak_at_mm, force_N_per_m, contact_length_mm, newton_iterations.
std::string steps_csv(const ContactRun& run, const std::string& load_column);
// One row per step and surface node: load_column, s_mm (arc position on the undeformed
// fingertip from its lowest point), x_mm, y_mm (where the node is), stress_kPa (the node's
// smoothed Cauchy contact stress), stress_1mm_kPa (averaged over 1 mm around it).
std::string profiles_csv(const ContactRun& run, const std::string& load_column);

}  // namespace palprig::mechanics
