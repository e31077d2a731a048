#include "sessions/pulse_setup.hpp"

#include "core/input_error.hpp"
#include "sessions/session_setup.hpp"

namespace palprig {

OpenedPulseSession open_pulse_session(SqliteTrialStore& store, const PulseProtocol& protocol,
                                      const PulseSessionRequest& request) {
  PulseStore pulse_store(store);
  OpenedPulseSession opened;
  std::optional<StoredPulseSession> stored;
  const int total = static_cast<int>(protocol.conditions.size()) * protocol.repetitions;
  TaskSessionSteps steps;
  steps.progress = [&](std::int64_t id) {
    return "stopped after " + std::to_string(pulse_store.load_session(id).completed_trials) + " of " +
           std::to_string(total) + " trials";
  };
  steps.load = [&](std::int64_t id) {
    stored = pulse_store.load_session(id);
    return StoredSessionHead{stored->id, stored->participant, stored->seed, stored->completed_trials,
                             stored->protocol_snapshot};
  };
  steps.create = [&](const ParticipantRecord& who, std::uint64_t seed) {
    return pulse_store.create_session(who, protocol, seed, request.setup);
  };
  const OpenedSessionHead head =
      open_task_session(store, protocol.name, protocol.snapshot, protocol.source, request, steps);
  opened.protocol =
      head.resumed ? parse_pulse_protocol(stored->protocol_snapshot, protocol.source, stored->protocol_dir) : protocol;
  opened.session_id = head.session_id;
  opened.participant = head.participant;
  opened.seed = head.seed;
  opened.start_position = head.start_position;
  opened.ordinal = head.ordinal;
  opened.resumed = head.resumed;
  return opened;
}

}  // namespace palprig
