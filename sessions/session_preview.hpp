#pragma once
// What Begin would run, before anything is stored: for a participant code, a protocol and a
// store, either the unfinished session that Resume continues (its stored order and the trials
// already committed) or the order a new session gets (the next enrolment number and the seed
// open_session derives). Read-only: the store is opened for reading, nothing is enrolled.
// The window's experiment console shows it; `palprig experiment plan` prints the same order.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "store/pulse_store.hpp"
#include "store/trial_store.hpp"
#include "study/protocol.hpp"
#include "study/pulse_protocol.hpp"
#include "study/session_plan.hpp"

namespace palprig {

struct SessionPreview {
  int participant_number = 1;  // the participant's, or the one the next enrolment gets
  bool enrolled = false;       // the store has the participant (else: the number enrolment would give)
  bool store_found = false;    // the store exists (a new one numbers from 1)
  std::uint64_t seed = 0;
  SessionPlan plan;
  std::optional<std::int64_t> unfinished_session;  // Resume continues this one
  int completed_trials = 0;
  std::vector<StoredTrial> committed;  // the unfinished session's trials, by position
};

// `store_location` may name no file yet (a new store): participant number 1.
SessionPreview preview_session(const std::string& store_location, const Protocol& protocol,
                               const std::string& participant_code);

struct PulseSessionPreview {
  PulseProtocol protocol;  // the stored one of an unfinished session, else the file's
  std::uint64_t seed = 0;
  std::vector<int> order;  // condition indices, as run
  std::optional<std::int64_t> unfinished_session;
  int completed_trials = 0;
  std::vector<PulseTrialRecord> committed;
};

PulseSessionPreview preview_pulse_session(const std::string& store_location, const PulseProtocol& protocol,
                                          const std::string& participant_code);

}  // namespace palprig
