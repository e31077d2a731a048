#include "study/threshold_record.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.hpp"

namespace palprig {

nlohmann::json tracks_state(const std::vector<AdaptiveTrack>& tracks) {
  nlohmann::json all = nlohmann::json::array();
  for (const AdaptiveTrack& t : tracks) all.push_back(t.state_json());
  return all;
}

void restore_tracks(std::vector<AdaptiveTrack>& tracks, const nlohmann::json& state) {
  if (!state.is_array() || state.size() != tracks.size()) {
    throw BadInput("stored track state: one entry per track of the protocol");
  }
  for (std::size_t i = 0; i < tracks.size(); ++i) tracks[i].restore(state[i]);
}

void replay_tracks(
    std::vector<AdaptiveTrack>& tracks, const std::vector<ThresholdTrialRecord>& trials,
    const std::function<void(const ThresholdTrialRecord&, const std::vector<AdaptiveTrack>&)>& after_each) {
  for (const ThresholdTrialRecord& r : trials) {
    const std::string at = "trial at position " + std::to_string(r.position) + ": ";
    if (r.track < 0 || static_cast<std::size_t>(r.track) >= tracks.size()) {
      throw BadInput(at + "track " + std::to_string(r.track) + " is not a track of the protocol (" +
                     std::to_string(tracks.size()) + " tracks)");
    }
    AdaptiveTrack& track = tracks[static_cast<std::size_t>(r.track)];
    // The level was the track's next level when the trial ran; the same answers in the same
    // order give the same doubles, so any difference beyond rounding means other answers.
    const double expected = track.next_level_kPa();
    if (!(std::abs(r.level_kPa - expected) <= 1e-9 * std::max(1.0, std::abs(expected)))) {
      throw BadInput(at + "level " + std::to_string(r.level_kPa) + " kPa, but the track's answers before it give " +
                     std::to_string(expected) + " kPa");
    }
    if (r.answered) {
      const bool reversal = track.record(r.level_kPa, r.correct);
      if (reversal != r.reversal) throw BadInput(at + "its reversal flag disagrees with the track's answers");
    }
    if (after_each) after_each(r, tracks);
  }
}

}  // namespace palprig
