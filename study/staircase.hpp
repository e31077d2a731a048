#pragma once
// Staircase: Levitt's transformed up-down procedure on a stimulus level in kPa (the pressure
// increment over the reference). After `down` correct (or "yes") answers in a row the level
// goes down by the down step, after `up` wrong answers in a row it goes up by the up step.
// With equal steps the track converges on the level answered correctly with probability
// p = 0.5^(1/down) for up = 1 (1-up/2-down 70.7 %, 1-up/3-down 79.4 %); with weighted steps
// (Kaernbach 1991) p^down = step_up / (step_up + step_down). Steps are halved at the listed
// reversal counts (never below min_step_kPa); the track stops after `stop_reversals` reversals
// or `max_trials` trials; the threshold is the mean of the last `threshold_reversals` reversal
// levels (PsychoPy StairHandler and Palamedes PAL_AMUD conventions: a reversal is recorded at
// the level of the trial whose answer changed the direction).
//
// The state is plain data and round-trips through JSON, so a session killed mid-track resumes
// with exactly the same staircase.
#include <vector>

#include <nlohmann/json.hpp>

namespace palprig {

struct StaircaseSettings {
  int up = 1;    // wrong answers in a row before a step up
  int down = 3;  // correct answers in a row before a step down
  double start_kPa = 4.0;
  double step_up_kPa = 0.5;
  double step_down_kPa = 0.5;
  std::vector<int> halve_at_reversals{2, 4};  // after these reversal counts both steps halve
  double min_step_kPa = 0.05;
  double min_kPa = 0.0, max_kPa = 20.0;
  int stop_reversals = 12;
  int max_trials = 120;
  int threshold_reversals = 8;  // threshold = mean of the last N reversals (all when fewer)
};

// The proportion correct the track converges on.
double staircase_target_probability(const StaircaseSettings& s) noexcept;

struct StaircaseState {
  double level_kPa = 0;
  int correct_in_a_row = 0;
  int wrong_in_a_row = 0;
  int direction = 0;  // last step: +1 up, -1 down, 0 none yet
  int halvings = 0;   // how many times the steps were halved
  int trials = 0;
  std::vector<double> reversals_kPa;
  bool finished = false;
};

nlohmann::json to_json(const StaircaseState& s);
StaircaseState staircase_state_from_json(const nlohmann::json& j);  // throws BadInput

class Staircase {
 public:
  explicit Staircase(const StaircaseSettings& settings);
  Staircase(const StaircaseSettings& settings, StaircaseState state) : settings_(settings), state_(std::move(state)) {}

  double next_level_kPa() const noexcept { return state_.level_kPa; }
  // Records the answer at the current level; returns true when it caused a reversal.
  bool record(bool correct);
  bool finished() const noexcept { return state_.finished; }
  // Mean of the last threshold_reversals reversals (the current level before any reversal).
  double threshold_kPa() const noexcept;
  const StaircaseState& state() const noexcept { return state_; }
  const StaircaseSettings& settings() const noexcept { return settings_; }

 private:
  void step(int direction);
  double scale() const noexcept;

  StaircaseSettings settings_;
  StaircaseState state_;
};

}  // namespace palprig
