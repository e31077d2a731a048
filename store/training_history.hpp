#pragma once
// A training programme's records read and written without a rig (for `palprig train enrol`,
// `train status`, `train benchmark`, `stats learning`, `export --plot` and the window's Training
// view): trainees enrolled in a curriculum, where each stands, their learning curves per measure
// and CUSUM charts over their cases, and a level's benchmark from experts' sessions. Running a
// session is sessions/training_session.hpp. Every reader opens the store read-only.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "statistics/learning_curve.hpp"
#include "statistics/learning_cusum.hpp"
#include "store/trial_store.hpp"
#include "study/curriculum.hpp"
#include "study/training.hpp"

namespace palprig {

// Enrols `trainee` in the curriculum (the store is created when missing). Enrolling again
// changes nothing. Throws InputError for a bad curriculum or an empty code.
void enrol_trainee(const std::string& store_location, const Curriculum& curriculum, const std::string& trainee);

// Where one trainee stands in a curriculum, with their history and each session's scores.
struct TraineeStanding {
  std::string trainee;
  TrainingStanding standing;
  std::vector<TrainingSessionRecord> sessions;  // this curriculum's, in order (a running one last)
  std::vector<SessionScores> scores;            // per entry of `sessions` (empty while running)
};
// Throws InputError naming the store for a trainee not enrolled in the curriculum.
TraineeStanding trainee_standing(const std::string& store_location, const Curriculum& curriculum,
                                 const std::string& trainee);
// Every trainee enrolled in the curriculum, by code.
std::vector<TraineeStanding> curriculum_standings(const std::string& store_location, const Curriculum& curriculum);

// A trainee's learning curves (one point per completed session, in order) and CUSUM charts
// (one point per case, in order), with the benchmark each session was held to.
struct TrainingCurves {
  std::vector<int> level;                           // per session: its level (0-based)
  std::vector<stats::LearningPoint> found;          // tumors (pulses) found / targets
  std::vector<stats::LearningPoint> false_marks;    // false marks per case
  std::vector<stats::LearningPoint> time_per_case;  // seconds per case
  std::vector<stats::LearningPoint> normal_called;  // normal cases left unmarked / normal cases
  // Per session, its level's benchmark for each measure (none: not required).
  std::vector<std::optional<double>> found_min, false_marks_max, time_max_s, normal_called_min;
  std::vector<bool> met;            // per session: met its benchmark
  std::vector<bool> case_failures;  // per case, every session's cases in order
  stats::CusumLimit cusum_limit, lc_cusum_limit;
  std::vector<stats::CusumPoint> cusum, lc_cusum;
};
TrainingCurves training_curves(const Curriculum& curriculum, const TraineeStanding& trainee);

// `palprig train benchmark`: a level's benchmark from experts' completed sessions at that level
// (the mean, or a percentile: found and normal-called at the percentile from the bottom, false
// marks and time from the top, so the benchmark is what that share of expert sessions reached).
struct ExpertBenchmark {
  int level = 0;
  std::vector<std::string> experts;
  int sessions = 0;
  LevelBenchmark benchmark;  // consecutive_sessions from the curriculum's level
};
// Throws InputError when no expert has a completed session at the level.
ExpertBenchmark expert_benchmark(const std::string& store_location, const Curriculum& curriculum, int level,
                                 const std::vector<std::string>& experts, std::optional<double> percentile);

// The store a training command opens: the lab server itself for a postgresql:// location
// (enrolments, history and the cases given live there, for every rig), else the SQLite file, which
// must exist (enrolment made it).
std::unique_ptr<TrialStore> open_training_store(const std::string& location, TrialStore::Access access);
// Throws InputError naming the store unless `trainee` is enrolled in the curriculum.
void require_enrolled(TrialStore& store, const Curriculum& curriculum, const std::string& trainee);
// The level of that name in the curriculum (none: it has no longer such a level).
const CurriculumLevel* level_named(const Curriculum& curriculum, const std::string& name);
// A session's cases as committed (localisation trials, or pulse trials of an SQLite store), those
// before `before` (all: -1).
std::vector<CaseResult> stored_cases(TrialStore& store, std::int64_t session_id, bool pulse, int before = -1);
// Training rows left running by a process that ended after their session completed: scored now
// from the stored trials (history updated in place).
void complete_left_behind(TrialStore& store, const Curriculum& curriculum, std::vector<TrainingSessionRecord>& history);
// The trainee's sessions of one curriculum, in order.
std::vector<TrainingSessionRecord> of_curriculum(const std::vector<TrainingSessionRecord>& history,
                                                 const std::string& curriculum);

}  // namespace palprig
