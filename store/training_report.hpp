#pragma once
// `palprig stats learning`: each trainee's learning curves (one row per session: level, tumors
// found with its Wilson interval, false marks and seconds per case, normal cases called normal,
// benchmark met) and CUSUM charts (the decision limits computed from the curriculum's error
// rates with the run lengths they give, the signal points), as an aligned table or JSON.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "store/training_history.hpp"

namespace palprig {

std::string learning_report_text(const Curriculum& curriculum, const std::vector<TraineeStanding>& trainees);
nlohmann::ordered_json learning_report_json(const Curriculum& curriculum, const std::vector<TraineeStanding>& trainees);
// The two limits of the curriculum (the same for every trainee) as text lines.
std::string cusum_limits_text(const stats::CusumLimit& cusum, const stats::CusumLimit& lc_cusum);

}  // namespace palprig
