#include "sessions/session_setup.hpp"

#include "experiments/random_source.hpp"
#include "models/parse_error.hpp"

namespace palprig {

std::uint64_t default_session_seed(const std::string& participant_code, const std::string& protocol_name) {
  return stable_hash(participant_code + '\n' + protocol_name);
}

OpenedSession open_session(TrialStore& store, const Protocol& protocol, const SessionRequest& request) {
  if (request.participant_code.empty()) throw InputError("command line", "participant", "a participant code");
  OpenedSession opened;
  const auto existing = store.find_participant(request.participant_code);
  const auto unfinished = existing ? store.find_unfinished_session(*existing, protocol.name) : std::nullopt;

  if (request.resume) {
    if (!unfinished) {
      throw InputError(store.location(), "resume",
                       "participant '" + request.participant_code + "' has no unfinished session with protocol '" +
                           protocol.name + "' to continue (none was started, or it was completed); to start a new "
                           "session, run the same command without `resume`");
    }
    // Held from here on: a second --resume of the same session at the same time is refused.
    store.claim_session(*unfinished);
    StoredSession stored = store.load_session(*unfinished);
    if (stored.protocol_snapshot != protocol.snapshot) {
      throw InputError(protocol.source, "protocol",
                       "the protocol of the session being resumed (session " + std::to_string(stored.id) +
                           " started with a different version of this file)");
    }
    opened.protocol = parse_protocol(stored.protocol_snapshot, protocol.source, stored.protocol_dir);
    opened.plan = std::move(stored.plan);
    opened.session_id = stored.id;
    opened.participant = stored.participant;
    opened.start_position = stored.completed_trials;
    opened.resumed = true;
    return opened;
  }

  if (unfinished) {
    store.refuse_if_running_elsewhere(*unfinished);  // "another process runs it" says more than "--resume"
    const StoredSession stored = store.load_session(*unfinished);
    throw InputError(store.location(), "participant '" + request.participant_code + "'",
                     "already has an unfinished session with protocol '" + protocol.name + "' (session " +
                         std::to_string(stored.id) + ", stopped after " + std::to_string(stored.completed_trials) +
                         " of " + std::to_string(stored.plan.trials.size()) +
                         " trials); to continue it, run the same command again with `resume`");
  }
  opened.participant = store.enrol(request.participant_code, request.simulated);
  opened.protocol = protocol;
  const std::uint64_t seed = request.seed ? *request.seed : default_session_seed(request.participant_code, protocol.name);
  opened.plan = make_session_plan(protocol, opened.participant.number, seed);
  opened.session_id = store.create_session(opened.participant, protocol, opened.plan, request.setup);
  return opened;
}

}  // namespace palprig
