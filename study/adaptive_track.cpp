#include "study/adaptive_track.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "study/random_source.hpp"

namespace palprig {

AdaptiveTrack::AdaptiveTrack(const TrackSpec& spec) : spec_(spec), staircase_(spec.staircase), quest_(spec.quest) {}

double AdaptiveTrack::next_level_kPa() const {
  return spec_.procedure == AdaptiveProcedure::staircase ? staircase_.next_level_kPa() : quest_.next_level_kPa();
}

bool AdaptiveTrack::record(double level_kPa, bool correct) {
  if (spec_.procedure == AdaptiveProcedure::staircase) return staircase_.record(correct);
  quest_.record(level_kPa, correct);
  return false;
}

bool AdaptiveTrack::finished() const {
  return spec_.procedure == AdaptiveProcedure::staircase ? staircase_.finished() : quest_.finished();
}

int AdaptiveTrack::trials() const {
  return spec_.procedure == AdaptiveProcedure::staircase ? staircase_.state().trials
                                                         : static_cast<int>(quest_.history().size());
}

TrackEstimate AdaptiveTrack::estimate() const {
  TrackEstimate e;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (spec_.procedure == AdaptiveProcedure::staircase) {
    const auto& r = staircase_.state().reversals_kPa;
    e.threshold_kPa = staircase_.threshold_kPa();
    e.trials = staircase_.state().trials;
    e.reversals = static_cast<int>(r.size());
    const std::size_t n =
        std::min<std::size_t>(r.size(), static_cast<std::size_t>(std::max(1, spec_.staircase.threshold_reversals)));
    double ss = 0;
    for (std::size_t i = r.size() - n; i < r.size(); ++i) ss += (r[i] - e.threshold_kPa) * (r[i] - e.threshold_kPa);
    e.sd = n > 1 ? std::sqrt(ss / static_cast<double>(n - 1)) : nan;
    e.ci_low_kPa = e.ci_high_kPa = nan;
    e.target_probability = staircase_target_probability(spec_.staircase);
  } else {
    const QuestEstimate q = quest_.estimate();
    e.threshold_kPa = q.threshold_kPa;
    e.sd = q.sd_log10;
    e.ci_low_kPa = q.ci_low_kPa;
    e.ci_high_kPa = q.ci_high_kPa;
    e.trials = q.trials;
    e.target_probability = spec_.quest.p_threshold;
  }
  return e;
}

nlohmann::json AdaptiveTrack::state_json() const {
  return spec_.procedure == AdaptiveProcedure::staircase ? to_json(staircase_.state()) : quest_.state_json();
}

void AdaptiveTrack::restore(const nlohmann::json& state) {
  if (spec_.procedure == AdaptiveProcedure::staircase)
    staircase_ = Staircase(spec_.staircase, staircase_state_from_json(state));
  else
    quest_.restore(state);
}

std::uint64_t trial_seed(std::uint64_t seed, int position, std::uint64_t purpose) noexcept {
  RandomSource r(seed ^ (static_cast<std::uint64_t>(position) * 0x9E3779B97F4A7C15ULL) ^
                 (purpose * 0xD1B54A32D192ED03ULL));
  return r.next();
}

int choose_track(const std::vector<AdaptiveTrack>& tracks, std::uint64_t seed, int position) {
  std::vector<int> open;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!tracks[i].finished()) open.push_back(static_cast<int>(i));
  }
  if (open.empty()) return -1;
  RandomSource r(trial_seed(seed, position, 1));
  return open[static_cast<std::size_t>(r.below(open.size()))];
}

}  // namespace palprig
