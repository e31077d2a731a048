#pragma once
// Starting or resuming a threshold session (issue 13) against the trial store: the same rules
// as sessions/session_setup.hpp (a participant is enrolled once; an unfinished session with the
// same protocol must be continued with resume; a changed protocol file is refused on resume),
// and on resume the tracks are rebuilt from the state stored with the last committed trial.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "experiments/adaptive_track.hpp"
#include "experiments/threshold_protocol.hpp"
#include "store/threshold_store.hpp"

namespace palprig {

struct ThresholdSessionRequest {
  std::string participant_code;
  bool simulated = false;
  bool resume = false;
  std::optional<std::uint64_t> seed;
  SessionSetup setup;
};

struct OpenedThresholdSession {
  ThresholdProtocol protocol;
  std::vector<AdaptiveTrack> tracks;  // restored on resume
  std::int64_t session_id = 0;
  ParticipantRecord participant;
  std::uint64_t seed = 0;
  int start_position = 0;
  bool resumed = false;
};

// Throws InputError for every refusal.
OpenedThresholdSession open_threshold_session(SqliteTrialStore& store, const ThresholdProtocol& protocol,
                                              const ThresholdSessionRequest& request);

}  // namespace palprig
