#pragma once
// SessionPlan: the whole order of one participant's session, generated once from the protocol,
// the participant's number (for counterbalancing) and a seed, then stored in the trial
// database so that a resumed session continues exactly where it stopped.
//
// Layout: conditions in the counterbalanced order; each condition starts with its practice
// trials, then its trials (every combination `repetitions` times, randomised by the
// protocol's scheme and constraints) cut into `blocks_per_condition` blocks. A break follows
// every block but the last, and every `break_every_trials` trials inside a block.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "study/protocol.hpp"
#include "study/random_source.hpp"

namespace palprig {

struct PlannedTrial {
  int position = 0;   // 0-based position in the session
  int block = 0;      // 0-based block number in presentation order
  int condition = 0;  // index into Protocol::conditions
  bool practice = false;
  int combination = -1;  // index into Protocol::combinations; -1 for localisation
  bool break_after = false;
};

struct SessionPlan {
  std::uint64_t seed = 0;
  int participant_number = 1;        // 1-based order of enrolment, drives counterbalancing
  std::vector<int> condition_order;  // indices into Protocol::conditions
  std::vector<PlannedTrial> trials;
};

// Throws InputError when the protocol's constraints cannot be met (load_protocol has already
// refused the impossible ones, so this only guards direct callers).
SessionPlan make_session_plan(const Protocol& protocol, int participant_number, std::uint64_t seed);

// The condition order for a participant under a counterbalancing scheme (random uses `random`).
std::vector<int> counterbalanced_order(Counterbalancing scheme, int conditions, int participant_number,
                                       RandomSource& random);

// Finger numbers with a flag set ("23"), or "none".
std::string finger_numbers_text(const FingerFlags& fingers);

// The order as `palprig experiment plan` prints it: a header, then one CSV row per trial
// (position, block, condition, mode, practice, stimulus_kPa, tumor_fingers, break_after).
void write_plan_csv(std::ostream& out, const Protocol& protocol, const SessionPlan& plan);

}  // namespace palprig
