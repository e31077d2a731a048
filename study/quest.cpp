#include "study/quest.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"

namespace palprig {

Quest::Quest(const QuestSettings& s) : settings_(s) {
  if (!(s.gamma >= 0 && s.delta >= 0 && s.gamma + s.delta < 1)) throw BadInput("quest: gamma + delta < 1");
  if (!(s.p_threshold > s.gamma && s.p_threshold < 1 - s.delta)) {
    throw BadInput("quest: p_threshold between gamma and 1 - delta");
  }
  if (!(s.beta > 0) || !(s.prior_sd_log10 > 0) || !(s.grid_step_log10 > 0) || !(s.grid_half_width_log10 > 0)) {
    throw BadInput("quest: beta, prior sd, grid step and width must be > 0");
  }
  if (!(s.min_kPa > 0 && s.min_kPa < s.max_kPa && s.prior_threshold_kPa > 0)) {
    throw BadInput("quest: 0 < min_kPa < max_kPa and a positive prior threshold");
  }
  const double w = (s.p_threshold - s.gamma) / (1 - s.gamma - s.delta);
  epsilon_ = std::log10(-std::log1p(-w)) / s.beta;
  const double centre = std::log10(s.prior_threshold_kPa);
  const auto half = static_cast<std::size_t>(std::ceil(s.grid_half_width_log10 / s.grid_step_log10));
  first_log10_ = centre - static_cast<double>(half) * s.grid_step_log10;
  log_posterior_.resize(2 * half + 1);
  for (std::size_t i = 0; i < log_posterior_.size(); ++i) {
    const double z = (grid_log10(i) - centre) / s.prior_sd_log10;
    log_posterior_[i] = -0.5 * z * z;
  }
}

double Quest::probability_correct(double level_kPa, double threshold_kPa) const noexcept {
  const double x = std::log10(level_kPa), t = std::log10(threshold_kPa);
  const double weibull = -std::expm1(-std::pow(10.0, settings_.beta * (x - t + epsilon_)));
  return settings_.gamma + (1 - settings_.gamma - settings_.delta) * weibull;
}

void Quest::update(double level_kPa, bool correct) {
  const double x = std::log10(level_kPa);
  for (std::size_t i = 0; i < log_posterior_.size(); ++i) {
    const double weibull = -std::expm1(-std::pow(10.0, settings_.beta * (x - grid_log10(i) + epsilon_)));
    const double p = settings_.gamma + (1 - settings_.gamma - settings_.delta) * weibull;
    log_posterior_[i] += std::log(std::max(correct ? p : 1 - p, 1e-300));
  }
}

void Quest::record(double level_kPa, bool correct) {
  if (!(level_kPa > 0) || !std::isfinite(level_kPa)) throw BadInput("quest: levels must be > 0 kPa");
  update(level_kPa, correct);
  history_.emplace_back(level_kPa, correct);
}

bool Quest::finished() const noexcept {
  if (static_cast<int>(history_.size()) >= settings_.max_trials) return true;
  return settings_.stop_sd_log10 > 0 && !history_.empty() && estimate().sd_log10 < settings_.stop_sd_log10;
}

QuestEstimate Quest::estimate() const {
  const double peak = *std::max_element(log_posterior_.begin(), log_posterior_.end());
  std::vector<double> weight(log_posterior_.size());
  double total = 0, mean = 0;
  for (std::size_t i = 0; i < weight.size(); ++i) {
    weight[i] = std::exp(log_posterior_[i] - peak);
    total += weight[i];
    mean += weight[i] * grid_log10(i);
  }
  mean /= total;
  double var = 0;
  for (std::size_t i = 0; i < weight.size(); ++i) var += weight[i] * (grid_log10(i) - mean) * (grid_log10(i) - mean);
  var /= total;
  QuestEstimate e;
  e.mean_log10 = mean;
  e.sd_log10 = std::sqrt(var);
  e.threshold_kPa = std::pow(10.0, mean);
  e.trials = static_cast<int>(history_.size());
  double cumulative = 0;
  bool low_set = false;
  e.ci_high_kPa = std::pow(10.0, grid_log10(weight.size() - 1));
  for (std::size_t i = 0; i < weight.size(); ++i) {
    cumulative += weight[i] / total;
    if (!low_set && cumulative >= 0.025) {
      e.ci_low_kPa = std::pow(10.0, grid_log10(i));
      low_set = true;
    }
    if (cumulative >= 0.975) {
      e.ci_high_kPa = std::pow(10.0, grid_log10(i));
      break;
    }
  }
  return e;
}

double Quest::next_level_kPa() const {
  double at_log10 = 0;
  if (settings_.placement == QuestSettings::Placement::mode) {
    const auto best = std::max_element(log_posterior_.begin(), log_posterior_.end()) - log_posterior_.begin();
    at_log10 = grid_log10(static_cast<std::size_t>(best));
  } else {
    at_log10 = estimate().mean_log10;
  }
  return std::clamp(std::pow(10.0, at_log10), settings_.min_kPa, settings_.max_kPa);
}

nlohmann::json Quest::state_json() const {
  nlohmann::json h = nlohmann::json::array();
  for (const auto& [level, correct] : history_) h.push_back({level, correct ? 1 : 0});
  return {{"history", h}};
}

void Quest::restore(const nlohmann::json& state) {
  try {
    *this = Quest(settings_);
    for (const auto& entry : state.at("history")) record(entry.at(0).get<double>(), entry.at(1).get<int>() != 0);
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(std::string("quest state: ") + e.what());
  }
}

}  // namespace palprig
