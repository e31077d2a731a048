#include "sessions/threshold_setup.hpp"

#include <stdexcept>

#include "core/input_error.hpp"
#include "sessions/session_setup.hpp"

namespace palprig {

OpenedThresholdSession open_threshold_session(SqliteTrialStore& store, const ThresholdProtocol& protocol,
                                              const ThresholdSessionRequest& request) {
  ThresholdStore threshold_store(store);
  OpenedThresholdSession opened;
  std::optional<StoredThresholdSession> stored;
  TaskSessionSteps steps;
  steps.progress = [&](std::int64_t id) {
    return "stopped after " + std::to_string(threshold_store.load_session(id).completed_trials) + " trials";
  };
  steps.load = [&](std::int64_t id) {
    stored = threshold_store.load_session(id);
    return StoredSessionHead{stored->id, stored->participant, stored->seed, stored->completed_trials,
                             stored->protocol_snapshot};
  };
  steps.create = [&](const ParticipantRecord& who, std::uint64_t seed) {
    return threshold_store.create_session(who, protocol, seed, request.setup);
  };
  const OpenedSessionHead head =
      open_task_session(store, protocol.name, protocol.snapshot, protocol.source, request, steps);
  if (head.resumed) {
    opened.protocol = parse_threshold_protocol(stored->protocol_snapshot, protocol.source);
    for (const TrackSpec& spec : opened.protocol.tracks) opened.tracks.emplace_back(spec);
    try {
      replay_tracks(opened.tracks, stored->trials);
    } catch (const BadInput& e) {  // the study's replay refused a stored trial
      throw InputError(store.location(), "threshold_trials of session " + std::to_string(stored->id),
                       std::string("trials the stored protocol's tracks can replay (") + e.what() + ")");
    }
  } else {
    opened.protocol = protocol;
    for (const TrackSpec& spec : protocol.tracks) opened.tracks.emplace_back(spec);
  }
  opened.session_id = head.session_id;
  opened.participant = head.participant;
  opened.seed = head.seed;
  opened.start_position = head.start_position;
  opened.ordinal = head.ordinal;
  opened.resumed = head.resumed;
  return opened;
}

}  // namespace palprig
