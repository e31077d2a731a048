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
      throw InputError(store.location(), "`resume`",
                       "an unfinished session of participant '" + request.participant_code + "' with protocol '" +
                           protocol.name + "' (there is none)");
    }
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
    const StoredSession stored = store.load_session(*unfinished);
    throw InputError(store.location(), "participant '" + request.participant_code + "'",
                     "no unfinished session with this protocol (session " + std::to_string(stored.id) + " stopped after " +
                         std::to_string(stored.completed_trials) + " of " + std::to_string(stored.plan.trials.size()) +
                         " trials: continue it with `resume`)");
  }
  opened.participant = store.enrol(request.participant_code, request.simulated);
  opened.protocol = protocol;
  const std::uint64_t seed = request.seed ? *request.seed : default_session_seed(request.participant_code, protocol.name);
  opened.plan = make_session_plan(protocol, opened.participant.number, seed);
  opened.session_id = store.create_session(opened.participant, protocol, opened.plan, request.setup);
  return opened;
}

}  // namespace palprig
