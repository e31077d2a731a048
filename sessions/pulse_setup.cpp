#include "sessions/pulse_setup.hpp"

#include "models/parse_error.hpp"
#include "sessions/session_setup.hpp"

namespace palprig {

OpenedPulseSession open_pulse_session(SqliteTrialStore& store, const PulseProtocol& protocol, const PulseSessionRequest& request) {
  if (request.participant_code.empty()) throw InputError("command line", "participant", "a participant code");
  PulseStore pulse_store(store);
  OpenedPulseSession opened;
  const auto existing = store.find_participant(request.participant_code);
  const auto unfinished = existing ? store.find_unfinished_session(*existing, protocol.name) : std::nullopt;
  if (request.resume) {
    if (!unfinished) {
      throw InputError(store.location(), "`resume`",
                       "an unfinished session of participant '" + request.participant_code + "' with protocol '" +
                           protocol.name + "' (there is none)");
    }
    const StoredPulseSession stored = pulse_store.load_session(*unfinished);
    if (stored.protocol_snapshot != protocol.snapshot) {
      throw InputError(protocol.source, "protocol",
                       "the protocol of the session being resumed (session " + std::to_string(stored.id) +
                           " started with a different version of this file)");
    }
    opened.protocol = parse_pulse_protocol(stored.protocol_snapshot, protocol.source, stored.protocol_dir);
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
  opened.seed = request.seed ? *request.seed : default_session_seed(request.participant_code, protocol.name);
  opened.session_id = pulse_store.create_session(opened.participant, protocol, opened.seed, request.setup);
  return opened;
}

}  // namespace palprig
