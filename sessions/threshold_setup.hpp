#pragma once
// Starting or resuming a threshold session against the trial store: the same rules
// as sessions/session_setup.hpp (a participant is enrolled once; an unfinished session with the
// same protocol must be continued with resume; a changed protocol file is refused on resume),
// and on resume the tracks are rebuilt from the state stored with the last committed trial.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "study/adaptive_track.hpp"
#include "study/threshold_protocol.hpp"
#include "sessions/session_setup.hpp"
#include "store/threshold_store.hpp"

namespace palprig {

using ThresholdSessionRequest = SessionRequest;

struct OpenedThresholdSession {
  ThresholdProtocol protocol;
  std::vector<AdaptiveTrack> tracks;  // restored on resume
  std::int64_t session_id = 0;
  ParticipantRecord participant;
  std::uint64_t seed = 0;
  int start_position = 0;
  int ordinal = 1;  // the participant's n-th session with the protocol
  bool resumed = false;
};

// Throws InputError for every refusal.
OpenedThresholdSession open_threshold_session(SqliteTrialStore& store, const ThresholdProtocol& protocol,
                                              const ThresholdSessionRequest& request);

}  // namespace palprig
