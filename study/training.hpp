#pragma once
// The rules of a training programme, as pure functions of a curriculum (study/curriculum.hpp)
// and a trainee's history (study/training_record.hpp): where the trainee stands, which cases
// their next session gives (never one they had), the protocol that session runs, how it is
// scored against the level's benchmark, which cases count as failures for the CUSUM charts, and
// what a simulated trainee of the curriculum's pilot is predicted to need.
//
// Progression (proficiency-based): a trainee starts at the first level; a completed session at
// their level that meets its benchmark extends their run, one that does not ends it; after
// `consecutive_sessions` in a row they move to the next level. Sessions at another level (an
// expert running a level for a benchmark, `train next --level`) do not move them.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/curriculum.hpp"
#include "study/pulse_record.hpp"
#include "study/training_record.hpp"
#include "study/trial_record.hpp"

namespace palprig {

// One case of a training session as scored.
struct CaseResult {
  std::string name;  // the case's name (generated: case-<difficulty>-<seed>; pulse: the condition)
  bool pulse = false;
  bool answered = false;
  int tumors = 0;  // localisation: tumors in the case (0: a normal case); pulse: 1, the artery
  int found = 0;   // tumors found; pulse: 1 for a hit
  int false_marks = 0;
  double time_s = std::numeric_limits<double>::quiet_NaN();       // presentation to answer; NaN: none
  double distance_mm = std::numeric_limits<double>::quiet_NaN();  // pulse: mark to the artery
  bool normal() const noexcept { return !pulse && tumors == 0; }
};

CaseResult case_result(const TrialRecord& trial);
CaseResult case_result(const PulseTrialRecord& trial);

// A session's measures over its cases; each undefined (none) without cases to measure.
struct SessionScores {
  std::vector<CaseResult> cases;
  int targets() const;  // tumors (pulse: cases)
  int found() const;
  int normal_cases() const;
  int normal_called() const;  // normal cases answered without a mark
  int false_marks() const;
  std::optional<double> found_fraction() const;
  std::optional<double> false_marks_per_case() const;
  std::optional<double> time_per_case_s() const;  // mean over answered cases
  std::optional<double> normal_called_fraction() const;
};
nlohmann::json to_json(const SessionScores& scores);
SessionScores scores_from_json(const nlohmann::json& j);  // what to_json wrote; tolerant of nulls

struct BenchmarkResult {
  bool met = false;
  std::vector<std::string> shortfalls;  // "tumors found 0.50 (wanted >= 0.90)"
};
BenchmarkResult check_benchmark(const LevelBenchmark& benchmark, const SessionScores& scores);

// A case's outcome for the CUSUM charts: failed unless answered, every tumor found (a normal case:
// left unmarked; pulse: a hit) and no more false marks than the level's whole allowance per case.
bool case_failed(const CaseResult& c, const LevelBenchmark& benchmark);

struct TrainingStanding {
  int level = 0;          // the present level (levels.size() once every level is passed)
  bool finished = false;  // every level passed
  int sessions = 0;       // completed sessions in this curriculum
  int sessions_at_level = 0;
  int consecutive_met = 0;                      // the present run at the present level
  std::vector<int> passed_after;                // per level passed, the trainee's session number that passed it
  std::optional<std::int64_t> running_session;  // a started session not completed (to resume)
};
// `history`: the trainee's training sessions (any curriculum; others are ignored), in order.
TrainingStanding training_standing(const Curriculum& curriculum, const std::vector<TrainingSessionRecord>& history);

// The cases and protocol of the trainee's next session at `level`. `given` holds the case keys
// the trainee had before (generated cases are never given again; a scene set repeats its
// scenes only once all were given). `session_number` (1-based) varies the draw.
struct TrainingCase {
  std::string key, name;
  std::optional<std::uint64_t> seed;  // generated
  std::filesystem::path scene_file;   // scene set
};
struct PlannedTrainingSession {
  int level = 0;
  bool pulse = false;
  std::vector<TrainingCase> cases;
  std::string protocol_name;
  nlohmann::json protocol;  // a localisation or pulse protocol document (study/protocol.hpp, pulse_protocol.hpp)
};
PlannedTrainingSession plan_training_session(const Curriculum& curriculum, int level, const std::string& trainee,
                                             const std::set<std::string>& given, int session_number);
// The protocol name a level's sessions are stored under ("<curriculum> / <level>").
std::string training_protocol_name(const Curriculum& curriculum, int level);

// The simulated trainee's skill after `cases_practised` cases (CurriculumPilot).
double pilot_skill(const CurriculumPilot& pilot, int cases_practised);
// The sessions a pilot trainee of the curriculum is expected to need: the 1-based session at
// which it first trains at each level (none: not within `max_sessions`), from its expected
// tumors found per session: its skill averaged over the session's cases times what a fully
// skilled trainee finds at the level (`expert_found`, per level; 1 where not given: every
// tumor), against found_min; the other measures taken as met.
std::vector<std::optional<int>> predict_pilot_sessions(const Curriculum& curriculum, int max_sessions,
                                                       const std::vector<double>& expert_found = {});

}  // namespace palprig
