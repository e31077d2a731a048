#include "sessions/session_setup.hpp"

#include "study/random_source.hpp"
#include "core/input_error.hpp"

namespace palprig {

std::uint64_t default_session_seed(const std::string& participant_code, const std::string& protocol_name, int ordinal) {
  const std::uint64_t first = stable_hash(participant_code + '\n' + protocol_name);
  if (ordinal <= 1) return first;
  return stable_hash(std::to_string(first) + '\n' + std::to_string(ordinal));
}

int sessions_with_protocol(TrialStore& store, const std::string& participant_code, const std::string& protocol_name,
                           std::optional<std::int64_t> up_to_session) {
  int n = 0;
  for (const SessionOverview& s : store.list_sessions()) {
    if (s.participant.code == participant_code && s.protocol_name == protocol_name &&
        (!up_to_session || s.id <= *up_to_session))
      ++n;
  }
  return n;
}

std::uint64_t session_simulation_seed(std::uint64_t sim_seed, int ordinal) noexcept {
  if (ordinal <= 1) return sim_seed;
  return sim_seed ^ (0xD1B54A32D192ED03ULL * static_cast<std::uint64_t>(ordinal));
}

void refuse_server_store_for_task_session(const std::string& store_location) {
  if (!is_server_store_location(store_location)) return;
  throw InputError(store_location, "`store`",
                   "an SQLite file: threshold and pulse protocols are not stored on the PostgreSQL lab server");
}

std::optional<std::int64_t> session_to_resume(TrialStore& store, const std::string& participant_code,
                                              const std::string& protocol_name, bool resume,
                                              const std::function<std::string(std::int64_t)>& progress) {
  if (participant_code.empty()) throw InputError("command line", "participant", "a participant code");
  const auto existing = store.find_participant(participant_code);
  const auto unfinished = existing ? store.find_unfinished_session(*existing, protocol_name) : std::nullopt;
  if (resume) {
    if (!unfinished) {
      throw InputError(store.location(), "resume",
                       "participant '" + participant_code + "' has no unfinished session with protocol '" +
                           protocol_name +
                           "' to continue (none was started, or it was completed); to start a new "
                           "session, run the same command without `resume`");
    }
    // Held from here on: a second --resume of the same session at the same time is refused.
    store.claim_session(*unfinished);
    return unfinished;
  }
  if (unfinished) {
    store.refuse_if_running_elsewhere(*unfinished);  // "another process runs it" says more than "--resume"
    throw InputError(store.location(), "participant '" + participant_code + "'",
                     "already has an unfinished session with protocol '" + protocol_name + "' (session " +
                         std::to_string(*unfinished) + ", " + progress(*unfinished) +
                         "); to continue it, run the same command again with `resume`");
  }
  return std::nullopt;
}

void refuse_changed_protocol(std::int64_t session_id, const nlohmann::json& stored_snapshot,
                             const nlohmann::json& file_snapshot, const std::string& protocol_file) {
  if (stored_snapshot == file_snapshot) return;
  throw InputError(protocol_file, "protocol",
                   "the protocol of the session being resumed (session " + std::to_string(session_id) +
                       " started with a different version of this file)");
}

OpenedSessionHead open_task_session(TrialStore& store, const std::string& protocol_name,
                                    const nlohmann::json& file_snapshot, const std::string& protocol_file,
                                    const SessionRequest& request, const TaskSessionSteps& steps) {
  OpenedSessionHead opened;
  const auto resumed =
      session_to_resume(store, request.participant_code, protocol_name, request.resume, steps.progress);
  if (resumed) {
    const StoredSessionHead stored = steps.load(*resumed);
    refuse_changed_protocol(stored.id, stored.protocol_snapshot, file_snapshot, protocol_file);
    opened.session_id = stored.id;
    opened.participant = stored.participant;
    opened.seed = stored.seed;
    opened.start_position = stored.completed_trials;
    opened.resumed = true;
    opened.ordinal = sessions_with_protocol(store, request.participant_code, protocol_name, stored.id);
    return opened;
  }
  opened.participant = store.enrol(request.participant_code, request.simulated);
  opened.ordinal = sessions_with_protocol(store, request.participant_code, protocol_name) + 1;
  opened.seed =
      request.seed ? *request.seed : default_session_seed(request.participant_code, protocol_name, opened.ordinal);
  opened.session_id = steps.create(opened.participant, opened.seed);
  return opened;
}

OpenedSession open_session(TrialStore& store, const Protocol& protocol, const SessionRequest& request) {
  OpenedSession opened;
  std::optional<StoredSession> stored;
  TaskSessionSteps steps;
  steps.progress = [&](std::int64_t id) {
    const StoredSession s = store.load_session(id);
    return "stopped after " + std::to_string(s.completed_trials) + " of " + std::to_string(s.plan.trials.size()) +
           " trials";
  };
  steps.load = [&](std::int64_t id) {
    stored = store.load_session(id);
    return StoredSessionHead{stored->id, stored->participant, 0, stored->completed_trials, stored->protocol_snapshot};
  };
  steps.create = [&](const ParticipantRecord& who, std::uint64_t seed) {
    opened.plan = make_session_plan(protocol, who.number, seed);
    return store.create_session(who, protocol, opened.plan, request.setup);
  };
  const OpenedSessionHead head =
      open_task_session(store, protocol.name, protocol.snapshot, protocol.source, request, steps);
  if (head.resumed) {
    opened.protocol = parse_protocol(stored->protocol_snapshot, protocol.source, stored->protocol_dir);
    opened.plan = std::move(stored->plan);
  } else {
    opened.protocol = protocol;
  }
  opened.session_id = head.session_id;
  opened.participant = head.participant;
  opened.start_position = head.start_position;
  opened.resumed = head.resumed;
  opened.ordinal = head.ordinal;
  return opened;
}

}  // namespace palprig
