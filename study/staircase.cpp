#include "study/staircase.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"

namespace palprig {

double staircase_target_probability(const StaircaseSettings& s) noexcept {
  // Equilibrium of the track: P(step down) * step_down = P(step up) * step_up. For up = 1,
  // P(down) = p^down, so p^down = step_up / (step_up + step_down).
  const double per_down = s.step_up_kPa / (s.step_up_kPa + s.step_down_kPa);
  if (s.up == 1) return std::pow(per_down, 1.0 / s.down);
  // up > 1: the level where P(down run) * step_down = P(up run) * step_up, solved by bisection.
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double p = 0.5 * (lo + hi);
    const double f = std::pow(p, s.down) * s.step_down_kPa - std::pow(1 - p, s.up) * s.step_up_kPa;
    (f > 0 ? hi : lo) = p;
  }
  return 0.5 * (lo + hi);
}

nlohmann::json to_json(const StaircaseState& s) {
  return {{"level_kPa", s.level_kPa},
          {"correct_in_a_row", s.correct_in_a_row},
          {"wrong_in_a_row", s.wrong_in_a_row},
          {"direction", s.direction},
          {"halvings", s.halvings},
          {"trials", s.trials},
          {"reversals_kPa", s.reversals_kPa},
          {"finished", s.finished}};
}

StaircaseState staircase_state_from_json(const nlohmann::json& j) {
  try {
    StaircaseState s;
    s.level_kPa = j.at("level_kPa").get<double>();
    s.correct_in_a_row = j.at("correct_in_a_row").get<int>();
    s.wrong_in_a_row = j.at("wrong_in_a_row").get<int>();
    s.direction = j.at("direction").get<int>();
    s.halvings = j.at("halvings").get<int>();
    s.trials = j.at("trials").get<int>();
    s.reversals_kPa = j.at("reversals_kPa").get<std::vector<double>>();
    s.finished = j.at("finished").get<bool>();
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(std::string("staircase state: ") + e.what());
  }
}

Staircase::Staircase(const StaircaseSettings& settings) : settings_(settings) {
  if (settings.up < 1 || settings.down < 1) throw BadInput("staircase: up and down must be at least 1");
  if (!(settings.step_up_kPa > 0) || !(settings.step_down_kPa > 0)) throw BadInput("staircase: steps must be > 0");
  if (!(settings.min_kPa <= settings.start_kPa && settings.start_kPa <= settings.max_kPa)) {
    throw BadInput("staircase: start level outside [min, max]");
  }
  state_.level_kPa = settings.start_kPa;
}

double Staircase::scale() const noexcept {
  const double s = std::ldexp(1.0, -state_.halvings);
  return s;
}

void Staircase::step(int direction) {
  double size = (direction > 0 ? settings_.step_up_kPa : settings_.step_down_kPa) * scale();
  // Halving stops at the smallest step (the ratio of up to down steps is kept).
  const double smallest = std::min(settings_.step_up_kPa, settings_.step_down_kPa) * scale();
  if (smallest < settings_.min_step_kPa) size *= settings_.min_step_kPa / smallest;
  // Rounded to 1e-9 kPa so that repeated steps land on the levels they should (0.8 - 0.4 - 0.4
  // is 0, not 1e-16): a psychometric fit then counts the trials of one level together.
  const double next = std::round((state_.level_kPa + direction * size) * 1e9) / 1e9;
  state_.level_kPa = std::clamp(next, settings_.min_kPa, settings_.max_kPa);
}

bool Staircase::record(bool correct) {
  if (state_.finished) return false;
  ++state_.trials;
  int move = 0;
  if (correct) {
    state_.wrong_in_a_row = 0;
    if (++state_.correct_in_a_row >= settings_.down) {
      state_.correct_in_a_row = 0;
      move = -1;
    }
  } else {
    state_.correct_in_a_row = 0;
    if (++state_.wrong_in_a_row >= settings_.up) {
      state_.wrong_in_a_row = 0;
      move = +1;
    }
  }
  bool reversal = false;
  if (move != 0) {
    if (state_.direction != 0 && move != state_.direction) {
      reversal = true;
      state_.reversals_kPa.push_back(state_.level_kPa);
      const int n = static_cast<int>(state_.reversals_kPa.size());
      if (std::find(settings_.halve_at_reversals.begin(), settings_.halve_at_reversals.end(), n) !=
          settings_.halve_at_reversals.end()) {
        ++state_.halvings;
      }
    }
    state_.direction = move;
    step(move);
  }
  if (static_cast<int>(state_.reversals_kPa.size()) >= settings_.stop_reversals ||
      state_.trials >= settings_.max_trials) {
    state_.finished = true;
  }
  return reversal;
}

double Staircase::threshold_kPa() const noexcept {
  const auto& r = state_.reversals_kPa;
  if (r.empty()) return state_.level_kPa;
  const std::size_t n =
      std::min<std::size_t>(r.size(), static_cast<std::size_t>(std::max(1, settings_.threshold_reversals)));
  double sum = 0;
  for (std::size_t i = r.size() - n; i < r.size(); ++i) sum += r[i];
  return sum / static_cast<double>(n);
}

}  // namespace palprig
