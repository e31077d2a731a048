#pragma once
// A training curriculum (a versioned JSON file, "kind": "curriculum"): the levels a trainee goes
// through in order, each with its cases, how many per session, feedback and time limit, and the
// proficiency benchmark to meet on N consecutive sessions before moving on (proficiency-based
// progression). A complete, commented example is data/curricula/palpation_basics.json; the
// trainer's guide is docs/training.md.
//
//   {"version": 1, "kind": "curriculum", "name": ..., "description": ...,
//    "tolerance_mm": 5,
//    "levels": [{"name": ..., "cases": CASES, "cases_per_session": 4, "feedback": "all",
//                "time_limit_s": 120,
//                "benchmark": {"found_min": 0.9, "false_marks_per_case_max": 1,
//                              "time_per_case_max_s": 90, "normal_called_min": 0.8,
//                              "consecutive_sessions": 2}}, ...],
//    "cusum": {"acceptable_failure_rate": 0.1, "unacceptable_failure_rate": 0.3,
//              "alpha": 0.05, "beta": 0.2, "horizon_cases": 100},
//    "pilot": {"initial_skill": 0.3, "learning_rate_per_case": 0.05}}
//
//   CASES: {"generate": "easy" | "medium" | "hard"}   generated tumor cases, new to the trainee
//          {"pulse": "easy" | "medium" | "hard"}      generated pulse cases (an artery to find)
//          {"scenes": ["file.json", ...]}             a fixed set of scene files with tumors
//                                                     (relative to the curriculum file)
// Every field is checked on load; a refusal names the file, the field and what was expected
// (InputError), before anything is stored or moved.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/case_generator.hpp"
#include "study/protocol.hpp"

namespace palprig {

inline constexpr int kCurriculumFileVersion = 1;

enum class LevelCases { generated_tumors, generated_pulse, scene_set };
const char* to_string(LevelCases kind) noexcept;

// What a level's sessions must show, each measure optional (absent: not required), to count as
// meeting the benchmark; a level is passed after `consecutive_sessions` such sessions in a row.
struct LevelBenchmark {
  std::optional<double> found_min;                 // tumors found of all tumors (pulse: pulses hit of all cases), 0..1
  std::optional<double> false_marks_per_case_max;  // marks near no tumor, per case
  std::optional<double> time_per_case_max_s;       // mean seconds from a case's presentation to the answer
  std::optional<double> normal_called_min;         // normal cases left unmarked of all normal cases, 0..1
  int consecutive_sessions = 2;
};

struct CurriculumLevel {
  std::string name;
  LevelCases cases = LevelCases::generated_tumors;
  CaseDifficulty difficulty = CaseDifficulty::easy;  // generated levels
  std::vector<std::filesystem::path> scenes;         // scene_set (resolved against the curriculum's folder)
  int cases_per_session = 4;
  Feedback feedback = Feedback::all;
  double time_limit_s = 120;  // a case is presented at most this long
  LevelBenchmark benchmark;
};

// The case outcomes the CUSUM charts read (statistics/learning_cusum.hpp) and the error rates
// their limits are computed from.
struct CurriculumCusum {
  double acceptable_failure_rate = 0.1;
  double unacceptable_failure_rate = 0.3;
  double alpha = 0.05, beta = 0.2;
  int horizon_cases = 100;
};

// The simulated trainee of a pilot (`palprig train next --participant sim:SEED`): its skill, the
// probability of reporting a bump it felt, rises with the cases practised n as
// 1 - (1 - initial_skill) exp(-learning_rate_per_case n). A rate of 0 never learns.
struct CurriculumPilot {
  double initial_skill = 0.3;
  double learning_rate_per_case = 0.05;
};

struct Curriculum {
  std::string source;  // the file, for messages
  std::string name, description;
  double tolerance_mm = 5.0;
  std::vector<CurriculumLevel> levels;
  CurriculumCusum cusum;
  CurriculumPilot pilot;
  nlohmann::json snapshot;  // the file as read
};

bool is_curriculum(const nlohmann::json& document);
// Throws InputError (file, field, what was expected).
Curriculum parse_curriculum(const nlohmann::json& document, const std::string& source,
                            const std::filesystem::path& base_dir);
Curriculum load_curriculum(const std::filesystem::path& path);

// The level's index by name (as a trainer types it), or InputError naming the levels.
int level_index(const Curriculum& curriculum, const std::string& name);

}  // namespace palprig
