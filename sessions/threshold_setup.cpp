#include "sessions/threshold_setup.hpp"

#include <stdexcept>

#include "models/parse_error.hpp"
#include "sessions/session_setup.hpp"

namespace palprig {

OpenedThresholdSession open_threshold_session(SqliteTrialStore& store, const ThresholdProtocol& protocol,
                                              const ThresholdSessionRequest& request) {
  if (request.participant_code.empty()) throw InputError("command line", "participant", "a participant code");
  ThresholdStore threshold_store(store);
  OpenedThresholdSession opened;
  const auto existing = store.find_participant(request.participant_code);
  const auto unfinished = existing ? store.find_unfinished_session(*existing, protocol.name) : std::nullopt;

  if (request.resume) {
    if (!unfinished) {
      throw InputError(store.location(), "`resume`",
                       "an unfinished session of participant '" + request.participant_code + "' with protocol '" +
                           protocol.name + "' (there is none)");
    }
    const StoredThresholdSession stored = threshold_store.load_session(*unfinished);
    if (stored.protocol_snapshot != protocol.snapshot) {
      throw InputError(protocol.source, "protocol",
                       "the protocol of the session being resumed (session " + std::to_string(stored.id) +
                           " started with a different version of this file)");
    }
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
  if (unfinished) {
    throw InputError(store.location(), "participant '" + request.participant_code + "'",
                     "no unfinished session with this protocol (session " + std::to_string(*unfinished) +
                         " is unfinished: continue it with `resume`)");
  }
  opened.participant = store.enrol(request.participant_code, request.simulated);
  opened.protocol = protocol;
  for (const TrackSpec& spec : protocol.tracks) opened.tracks.emplace_back(spec);
  opened.seed = request.seed ? *request.seed : default_session_seed(request.participant_code, protocol.name);
  opened.session_id = threshold_store.create_session(opened.participant, protocol, opened.seed, request.setup);
  return opened;
}

}  // namespace palprig
