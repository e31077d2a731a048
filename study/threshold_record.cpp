#include "study/threshold_record.hpp"

#include <stdexcept>

namespace palprig {

nlohmann::json tracks_state(const std::vector<AdaptiveTrack>& tracks) {
  nlohmann::json all = nlohmann::json::array();
  for (const AdaptiveTrack& t : tracks) all.push_back(t.state_json());
  return all;
}

void restore_tracks(std::vector<AdaptiveTrack>& tracks, const nlohmann::json& state) {
  if (!state.is_array() || state.size() != tracks.size()) {
    throw std::invalid_argument("stored track state: one entry per track of the protocol");
  }
  for (std::size_t i = 0; i < tracks.size(); ++i) tracks[i].restore(state[i]);
}

}  // namespace palprig
