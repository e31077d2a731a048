#pragma once
// What a trainee's training leaves in the trial store (store/trial_store.hpp keeps it; the
// training rules of study/training.hpp read it): the enrolment in a curriculum, and per training
// session its level, the cases it gave (never given to the same trainee again) and, once
// completed, its scores and whether it met the level's benchmark.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace palprig {

// A trainee: a participant code enrolled in a curriculum (study/curriculum.hpp).
struct TraineeRecord {
  std::string code, curriculum, enrolled_utc;
};

struct TrainingSessionRecord {
  std::int64_t session_id = 0;  // the session in its store
  std::string trainee, curriculum;
  int level = 0;  // 0-based, in the curriculum's order when it ran
  std::string level_name;
  std::vector<std::string> cases;  // case keys (study/localisation_case.hpp: case_key), in order
  std::string status = "running";  // "running" or "completed"
  nlohmann::json scores;           // study/training.hpp: SessionScores as JSON; null while running
  std::optional<bool> met_benchmark;
  std::string started_utc, finished_utc;
  bool completed() const noexcept { return status == "completed"; }
};

}  // namespace palprig
