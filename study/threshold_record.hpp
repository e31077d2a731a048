#pragma once
// What one threshold trial leaves behind (the store commits it, stats and export read it back),
// and how the adaptive tracks are rebuilt from those trials. A track's state is a function of
// its answered trials in order (a staircase counts answers, QUEST keeps the history), so the
// trial rows are the tracks' history: a resumed session and an export replay them instead of
// reading a stored copy of every track's state (which grew with each trial: a QUEST track's
// 4,000th row held 91 KB). Pure data: no rig, no clock.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/adaptive_track.hpp"

namespace palprig {

struct ThresholdTrialRecord {
  int position = 0;
  int track = 0;
  std::string track_name;
  std::string fingers;  // "one" or "three"
  double level_kPa = 0, reference_kPa = 0;
  int signal_interval = 1;  // 0 or 1: the interval with reference + level
  bool answered = false;
  int response = -1;     // 2afc: chosen interval 0/1; yes-no: 1 yes, 0 no; -1 no answer
  bool correct = false;  // 2afc: chose the signal interval; yes-no: answered yes
  bool reversal = false;
  double onset_s = 0, response_time_s = 0;  // response time from the end of the second interval
  std::array<double, 2> felt_kPa{};         // mean pressure on the active fingers per interval
};

// Every track's state as one JSON array, and back (throws BadInput).
nlohmann::json tracks_state(const std::vector<AdaptiveTrack>& tracks);
void restore_tracks(std::vector<AdaptiveTrack>& tracks, const nlohmann::json& state);

// Rebuilds the tracks (fresh, from the protocol) from a session's committed trials in position
// order: each answered trial is one record() of its track at its level; an unanswered one
// leaves the tracks as they were (the trial is repeated). `after_each` sees every trial with
// the tracks as they stood after it (the export's estimate after each trial). Throws
// BadInput naming the position when a trial names no track of the protocol, or its
// level or reversal is not what the replayed track gives (a damaged or edited store, or one
// written under another protocol).
void replay_tracks(
    std::vector<AdaptiveTrack>& tracks, const std::vector<ThresholdTrialRecord>& trials,
    const std::function<void(const ThresholdTrialRecord&, const std::vector<AdaptiveTrack>&)>& after_each = {});

}  // namespace palprig
