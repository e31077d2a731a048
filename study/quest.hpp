#pragma once
// Quest: Watson and Pelli's (1983) Bayesian adaptive threshold procedure. The threshold T is
// unknown; its posterior is kept on a grid of log10(level in kPa), starting from a Gaussian
// prior. Each answer multiplies the posterior by the likelihood of the answer under
//   psi(x; T) = gamma + (1 - gamma - delta) * (1 - exp(-10^(beta * (x - T + epsilon))))
// (x = log10 level; a Weibull in the level, as QUEST, PsychoPy's QuestHandler and
// Psychtoolbox's QuestCreate), where epsilon places T at the level answered correctly with
// probability p_threshold. The next level is the posterior mean or mode (clamped to the
// allowed range); the final estimate is the posterior mean with its sd and 95 % credible
// interval (2.5 and 97.5 % posterior quantiles).
//
// The state is the answer history; the posterior is rebuilt from prior and history, so the
// stored history resumes exactly the same procedure.
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace palprig {

struct QuestSettings {
  double prior_threshold_kPa = 3.0;  // prior mean (its log10 is the grid's centre)
  double prior_sd_log10 = 0.5;       // prior sd in log10 units (0.5: a factor of ~3)
  double grid_step_log10 = 0.005;
  double grid_half_width_log10 = 1.5;  // the grid spans the prior mean +/- this
  double beta = 1.4;                   // Weibull slope in log10 units
  double delta = 0.01;                 // lapse rate
  double gamma = 0.5;                  // guess rate: 0.5 for 2AFC, the false-alarm rate for yes/no
  double p_threshold = 0.82;           // T is the level answered correctly this often
  enum class Placement { mean, mode } placement = Placement::mean;
  double min_kPa = 0.05, max_kPa = 20.0;  // levels presented stay in here (min > 0: log scale)
  int max_trials = 60;
  double stop_sd_log10 = 0.0;  // also stop when the posterior sd is below this (0: never)
};

struct QuestEstimate {
  double threshold_kPa = 0;  // 10^(posterior mean of log10 T)
  double mean_log10 = 0, sd_log10 = 0;
  double ci_low_kPa = 0, ci_high_kPa = 0;  // 95 % credible interval
  int trials = 0;
};

class Quest {
 public:
  explicit Quest(const QuestSettings& settings);  // throws BadInput

  double next_level_kPa() const;
  void record(double level_kPa, bool correct);
  bool finished() const noexcept;
  QuestEstimate estimate() const;
  // P(correct) at a level for a threshold (both kPa): the model's psychometric function.
  double probability_correct(double level_kPa, double threshold_kPa) const noexcept;

  const std::vector<std::pair<double, bool>>& history() const noexcept { return history_; }
  nlohmann::json state_json() const;
  // Replays a stored history (throws BadInput on a malformed state).
  void restore(const nlohmann::json& state);
  const QuestSettings& settings() const noexcept { return settings_; }

 private:
  void update(double level_kPa, bool correct);
  double grid_log10(std::size_t i) const noexcept {
    return first_log10_ + static_cast<double>(i) * settings_.grid_step_log10;
  }

  QuestSettings settings_;
  double epsilon_ = 0;
  double first_log10_ = 0;
  std::vector<double> log_posterior_;
  std::vector<std::pair<double, bool>> history_;
};

}  // namespace palprig
