#pragma once
// Starting or resuming a pulse-localisation session (the rules of sessions/session_setup.hpp):
// on resume the stored protocol and seed give the same trial order, continued at the first
// trial not committed.
#include <cstdint>
#include <optional>
#include <string>

#include "experiments/pulse_session.hpp"
#include "sessions/session_setup.hpp"
#include "store/pulse_store.hpp"

namespace palprig {

using PulseSessionRequest = SessionRequest;

struct OpenedPulseSession {
  PulseProtocol protocol;
  std::int64_t session_id = 0;
  ParticipantRecord participant;
  std::uint64_t seed = 0;
  int start_position = 0;
  int ordinal = 1;  // the participant's n-th session with the protocol
  bool resumed = false;
};

OpenedPulseSession open_pulse_session(SqliteTrialStore& store, const PulseProtocol& protocol,
                                      const PulseSessionRequest& request);

}  // namespace palprig
