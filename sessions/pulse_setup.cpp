#include "sessions/pulse_setup.hpp"

#include "models/parse_error.hpp"
#include "sessions/session_setup.hpp"

namespace palprig {

OpenedPulseSession open_pulse_session(SqliteTrialStore& store, const PulseProtocol& protocol, const PulseSessionRequest& request) {
  PulseStore pulse_store(store);
  OpenedPulseSession opened;
  const int total = static_cast<int>(protocol.conditions.size()) * protocol.repetitions;
  const auto resumed = session_to_resume(store, request.participant_code, protocol.name, request.resume, [&](std::int64_t id) {
    return "stopped after " + std::to_string(pulse_store.load_session(id).completed_trials) + " of " +
           std::to_string(total) + " trials";
  });
  if (resumed) {
    const StoredPulseSession stored = pulse_store.load_session(*resumed);
    refuse_changed_protocol(stored.id, stored.protocol_snapshot, protocol.snapshot, protocol.source);
    opened.protocol = parse_pulse_protocol(stored.protocol_snapshot, protocol.source, stored.protocol_dir);
    opened.session_id = stored.id;
    opened.participant = stored.participant;
    opened.seed = stored.seed;
    opened.start_position = stored.completed_trials;
    opened.resumed = true;
    return opened;
  }
  opened.participant = store.enrol(request.participant_code, request.simulated);
  opened.protocol = protocol;
  opened.seed = request.seed ? *request.seed : default_session_seed(request.participant_code, protocol.name);
  opened.session_id = pulse_store.create_session(opened.participant, protocol, opened.seed, request.setup);
  return opened;
}

}  // namespace palprig
