#pragma once
// What one threshold trial leaves behind (the store commits it, stats and export read it back),
// and every adaptive track's state as JSON: stored with each trial so a resumed session
// continues the same tracks. Pure data: no rig, no clock.
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/adaptive_track.hpp"

namespace palprig {

struct ThresholdTrialRecord {
  int position = 0;
  int track = 0;
  std::string track_name;
  std::string fingers;       // "one" or "three"
  double level_kPa = 0, reference_kPa = 0;
  int signal_interval = 1;   // 0 or 1: the interval with reference + level
  bool answered = false;
  int response = -1;         // 2afc: chosen interval 0/1; yes-no: 1 yes, 0 no; -1 no answer
  bool correct = false;      // 2afc: chose the signal interval; yes-no: answered yes
  bool reversal = false;
  double onset_s = 0, response_time_s = 0;  // response time from the end of the second interval
  std::array<double, 2> felt_kPa{};          // mean pressure on the active fingers per interval
  nlohmann::json state;      // every track's state after this trial (resume from here)
};

// Every track's state as one JSON array, and back (throws std::invalid_argument).
nlohmann::json tracks_state(const std::vector<AdaptiveTrack>& tracks);
void restore_tracks(std::vector<AdaptiveTrack>& tracks, const nlohmann::json& state);

}  // namespace palprig
