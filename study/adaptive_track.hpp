#pragma once
// AdaptiveTrack: one adaptive procedure (a staircase or QUEST) measuring one threshold, e.g.
// "one finger" or "three fingers"; several tracks interleave in one session (PsychoPy's
// MultiStairHandler): each trial goes to one of the unfinished tracks chosen at random.
// The choice is drawn from a generator seeded by the session seed and the trial's position,
// so a resumed session draws exactly what the lost attempt would have drawn.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/quest.hpp"
#include "study/staircase.hpp"

namespace palprig {

enum class FingerSet { one, three };
enum class AdaptiveProcedure { staircase, quest };

struct TrackSpec {
  std::string name;
  FingerSet fingers = FingerSet::one;
  int finger = 0;  // 0-based; the finger used when fingers == one
  AdaptiveProcedure procedure = AdaptiveProcedure::staircase;
  StaircaseSettings staircase;
  QuestSettings quest;
};

struct TrackEstimate {
  double threshold_kPa = 0;
  double sd = 0;                           // staircase: sd of the reversals averaged (kPa); QUEST: posterior sd (log10)
  double ci_low_kPa = 0, ci_high_kPa = 0;  // QUEST: 95 % credible interval; staircase: NaN
  int trials = 0;
  int reversals = 0;              // staircase only
  double target_probability = 0;  // the proportion correct the estimate refers to
};

class AdaptiveTrack {
 public:
  explicit AdaptiveTrack(const TrackSpec& spec);

  double next_level_kPa() const;
  // Records an answer at `level_kPa` (the level presented); true when it was a reversal.
  bool record(double level_kPa, bool correct);
  bool finished() const;
  int trials() const;
  TrackEstimate estimate() const;
  nlohmann::json state_json() const;
  void restore(const nlohmann::json& state);  // throws BadInput
  const TrackSpec& spec() const noexcept { return spec_; }

 private:
  TrackSpec spec_;
  Staircase staircase_;
  Quest quest_;
};

// Index of the track for the trial at `position`: uniform over the unfinished tracks; -1 when
// every track has finished.
int choose_track(const std::vector<AdaptiveTrack>& tracks, std::uint64_t seed, int position);

// A 64-bit value for a (seed, position, purpose) triple: the interleaving choice and the 2AFC
// interval order each get their own.
std::uint64_t trial_seed(std::uint64_t seed, int position, std::uint64_t purpose) noexcept;

}  // namespace palprig
