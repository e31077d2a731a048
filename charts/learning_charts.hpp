#pragma once
// A trainee's learning figures (store/training_history.hpp: TrainingCurves): one learning curve
// per measure over their sessions, with its interval and the benchmark line of each session's
// level (a step where the level changes), and the CUSUM and LC-CUSUM charts over their cases
// with the decision limit and the signal points (statistics/learning_cusum.hpp). `palprig
// export --plot --curriculum`, `palprig stats learning --plot` and the window's Training view
// draw these same charts.
#include <filesystem>
#include <string>
#include <vector>

#include "charts/chart_png.hpp"
#include "store/training_history.hpp"

namespace palprig::charts {

enum class LearningMeasure { found, false_marks, time_per_case, normal_called };
const char* to_string(LearningMeasure m) noexcept;  // "found", "false_marks", ...

// The measure's curve with its benchmark; the chart has no series when no session defines it.
Chart learning_curve_chart(const TrainingCurves& curves, LearningMeasure measure, const std::string& trainee);
// The CUSUM (monitoring) or LC-CUSUM (learning) chart of the trainee's cases.
Chart cusum_chart(const TrainingCurves& curves, stats::CusumChart chart, const std::string& trainee);

// Every learning figure of each trainee (curves with data, both CUSUM charts) as
// learning_<trainee>_<measure>.png, cusum_<trainee>.png, lc_cusum_<trainee>.png (and .svg with
// `svg`); the trainee's code reduced to letters, digits, '-' and '_'. Returns the files written.
std::vector<std::filesystem::path> plot_learning(const Curriculum& curriculum,
                                                 const std::vector<TraineeStanding>& trainees,
                                                 const std::filesystem::path& dir, bool svg);

}  // namespace palprig::charts
