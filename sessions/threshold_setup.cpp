#include "sessions/threshold_setup.hpp"

#include <stdexcept>

#include "models/parse_error.hpp"
#include "sessions/session_setup.hpp"

namespace palprig {

OpenedThresholdSession open_threshold_session(SqliteTrialStore& store, const ThresholdProtocol& protocol,
                                              const ThresholdSessionRequest& request) {
  ThresholdStore threshold_store(store);
  OpenedThresholdSession opened;
  const auto resumed = session_to_resume(store, request.participant_code, protocol.name, request.resume, [&](std::int64_t id) {
    return "stopped after " + std::to_string(threshold_store.load_session(id).completed_trials) + " trials";
  });
  if (resumed) {
    const StoredThresholdSession stored = threshold_store.load_session(*resumed);
    refuse_changed_protocol(stored.id, stored.protocol_snapshot, protocol.snapshot, protocol.source);
    opened.protocol = parse_threshold_protocol(stored.protocol_snapshot, protocol.source);
    for (const TrackSpec& spec : opened.protocol.tracks) opened.tracks.emplace_back(spec);
    if (!stored.last_state.is_null()) {
      try {
        restore_tracks(opened.tracks, stored.last_state);
      } catch (const std::invalid_argument& e) {
        throw InputError(store.location(), "threshold_trials.state of session " + std::to_string(stored.id), e.what());
      }
    }
    opened.session_id = stored.id;
    opened.participant = stored.participant;
    opened.seed = stored.seed;
    opened.start_position = stored.completed_trials;
    opened.resumed = true;
    return opened;
  }
  opened.participant = store.enrol(request.participant_code, request.simulated);
  opened.protocol = protocol;
  for (const TrackSpec& spec : protocol.tracks) opened.tracks.emplace_back(spec);
  opened.seed = request.seed ? *request.seed : default_session_seed(request.participant_code, protocol.name);
  opened.session_id = threshold_store.create_session(opened.participant, protocol, opened.seed, request.setup);
  return opened;
}

}  // namespace palprig
