#include "sessions/session_preview.hpp"

#include <filesystem>
#include <system_error>

#include "sessions/session_setup.hpp"

namespace palprig {

namespace {

bool store_exists(const std::string& location) {
  if (location.empty()) return false;
  if (is_server_store_location(location)) return true;
  std::error_code ec;
  return std::filesystem::exists(location, ec);
}

}  // namespace

SessionPreview preview_session(const std::string& store_location, const Protocol& protocol,
                               const std::string& participant_code) {
  SessionPreview preview;
  int ordinal = 1;
  if (store_exists(store_location)) {
    preview.store_found = true;
    const auto store = open_trial_store(store_location, TrialStore::Access::read_only);
    if (const auto who = store->find_participant(participant_code)) {
      preview.enrolled = true;
      preview.participant_number = who->number;
      if (const auto id = store->find_unfinished_session(*who, protocol.name)) {
        StoredSession stored = store->load_session(*id);
        preview.unfinished_session = *id;
        preview.completed_trials = stored.completed_trials;
        preview.seed = stored.plan.seed;
        preview.plan = std::move(stored.plan);
        preview.committed = store->read_session_trials(*id);
        return preview;
      }
      ordinal = sessions_with_protocol(*store, participant_code, protocol.name) + 1;
    } else {
      preview.participant_number = store->next_participant_number();
    }
  }
  preview.seed = default_session_seed(participant_code, protocol.name, ordinal);
  preview.plan = make_session_plan(protocol, preview.participant_number, preview.seed);
  return preview;
}

PulseSessionPreview preview_pulse_session(const std::string& store_location, const PulseProtocol& protocol,
                                          const std::string& participant_code) {
  PulseSessionPreview preview;
  int ordinal = 1;
  if (store_exists(store_location) && !is_server_store_location(store_location)) {
    SqliteTrialStore store(store_location, TrialStore::Access::read_only);
    const auto who = store.find_participant(participant_code);
    if (who) ordinal = sessions_with_protocol(store, participant_code, protocol.name) + 1;
    if (const auto id = who ? store.find_unfinished_session(*who, protocol.name) : std::nullopt) {
      // The order a resumed session continues with: the stored protocol and seed.
      PulseStore pulse(store, false);
      const StoredPulseSession stored = pulse.load_session(*id);
      preview.protocol = parse_pulse_protocol(stored.protocol_snapshot, protocol.source, stored.protocol_dir);
      preview.seed = stored.seed;
      preview.order = pulse_trial_order(preview.protocol, stored.seed);
      preview.unfinished_session = *id;
      preview.completed_trials = stored.completed_trials;
      preview.committed = pulse.read_trials(*id);
      return preview;
    }
  }
  preview.protocol = protocol;
  preview.seed = default_session_seed(participant_code, protocol.name, ordinal);
  preview.order = pulse_trial_order(protocol, preview.seed);
  return preview;
}

}  // namespace palprig
