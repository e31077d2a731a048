#include "study/session_plan.hpp"

#include <algorithm>
#include <ostream>
#include <numeric>

#include "study/random_source.hpp"
#include "study/trial_order.hpp"
#include "core/input_error.hpp"

namespace palprig {

namespace {

// Williams' balanced Latin square: every condition follows every other equally often. For an
// odd number of conditions the square is doubled with its mirror rows.
std::vector<int> williams_row(int k, int row) {
  // First row 0, 1, k-1, 2, k-2, ...; row r adds r to every entry (mod k).
  std::vector<int> base(static_cast<std::size_t>(k));
  base[0] = 0;
  for (int j = 1, up = 1, down = k - 1; j < k; ++j) base[static_cast<std::size_t>(j)] = j % 2 == 1 ? up++ : down--;
  const int rows = k % 2 == 0 ? k : 2 * k;
  const int r = row % rows;
  std::vector<int> out(static_cast<std::size_t>(k));
  for (int j = 0; j < k; ++j) out[static_cast<std::size_t>(j)] = (base[static_cast<std::size_t>(j)] + r) % k;
  if (r >= k) std::reverse(out.begin(), out.end());
  return out;
}

std::vector<int> condition_sequence(const Protocol& p, RandomSource& random) {
  const int kinds = order_items(p);
  const OrderConstraints constraints{p.randomisation.max_repeats_in_a_row, p.randomisation.min_distance};
  std::vector<int> order;
  switch (p.randomisation.scheme) {
    case RandomScheme::fixed:
      for (int r = 0; r < p.repetitions; ++r) {
        for (int i = 0; i < kinds; ++i) order.push_back(i);
      }
      return order;
    case RandomScheme::full:
      if (!extend_constrained_order(order, std::vector<int>(static_cast<std::size_t>(kinds), p.repetitions),
                                    constraints, random)) {
        throw InputError(p.source, "randomisation", "constraints some order satisfies");
      }
      return order;
    case RandomScheme::blocked:
      for (int r = 0; r < p.repetitions; ++r) {
        if (!extend_constrained_order(order, std::vector<int>(static_cast<std::size_t>(kinds), 1), constraints,
                                      random)) {
          throw InputError(p.source, "randomisation", "constraints some blocked order satisfies");
        }
      }
      return order;
  }
  return order;
}

std::vector<int> practice_sequence(const Protocol& p, RandomSource& random) {
  const bool itemised = p.task == TaskKind::discrimination || p.localisation.listed;
  if (!itemised) return std::vector<int>(static_cast<std::size_t>(p.practice_trials), -1);
  // Practice draws the combinations (or listed cases) without replacement (reshuffled when more
  // are needed).
  std::vector<int> out;
  std::vector<int> deck;
  while (static_cast<int>(out.size()) < p.practice_trials) {
    if (deck.empty()) {
      deck.resize(static_cast<std::size_t>(order_items(p)));
      std::iota(deck.begin(), deck.end(), 0);
    }
    const auto pick = static_cast<std::ptrdiff_t>(random.below(deck.size()));
    out.push_back(deck[static_cast<std::size_t>(pick)]);
    deck.erase(deck.begin() + pick);
  }
  return out;
}

}  // namespace

std::vector<int> counterbalanced_order(Counterbalancing scheme, int conditions, int participant_number,
                                       RandomSource& random) {
  std::vector<int> order(static_cast<std::size_t>(conditions));
  std::iota(order.begin(), order.end(), 0);
  const int index = std::max(participant_number, 1) - 1;
  switch (scheme) {
    case Counterbalancing::none: break;
    case Counterbalancing::alternate:
      if (index % 2 == 1) std::reverse(order.begin(), order.end());
      break;
    case Counterbalancing::latin_square: order = williams_row(conditions, index); break;
    case Counterbalancing::random:
      for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random.below(i)]);
      break;
  }
  return order;
}

SessionPlan make_session_plan(const Protocol& protocol, int participant_number, std::uint64_t seed) {
  SessionPlan plan;
  plan.seed = seed;
  plan.participant_number = participant_number;
  RandomSource random(seed);
  const int conditions = static_cast<int>(protocol.conditions.size());
  plan.condition_order = counterbalanced_order(protocol.counterbalancing, conditions, participant_number, random);

  // Generate every condition's trials in the listed order so a condition's sequence does not
  // depend on where counterbalancing puts it.
  std::vector<std::vector<int>> sequences(static_cast<std::size_t>(conditions));
  std::vector<std::vector<int>> practice(static_cast<std::size_t>(conditions));
  for (int c = 0; c < conditions; ++c) {
    practice[static_cast<std::size_t>(c)] = practice_sequence(protocol, random);
    sequences[static_cast<std::size_t>(c)] = condition_sequence(protocol, random);
  }

  int block = 0;
  for (std::size_t slot = 0; slot < plan.condition_order.size(); ++slot) {
    const int c = plan.condition_order[slot];
    const auto& sequence = sequences[static_cast<std::size_t>(c)];
    for (int combination : practice[static_cast<std::size_t>(c)]) {
      plan.trials.push_back({0, block, c, true, combination, false});
    }
    const std::size_t per_block = sequence.size() / static_cast<std::size_t>(protocol.blocks_per_condition);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const std::size_t in_block = i % per_block;
      if (i > 0 && in_block == 0) ++block;
      PlannedTrial t{0, block, c, false, sequence[i], false};
      const bool block_end = in_block + 1 == per_block;
      t.break_after = block_end || (protocol.break_every_trials > 0 &&
                                    (in_block + 1) % static_cast<std::size_t>(protocol.break_every_trials) == 0);
      plan.trials.push_back(t);
    }
    ++block;
  }
  for (std::size_t i = 0; i < plan.trials.size(); ++i) plan.trials[i].position = static_cast<int>(i);
  if (!plan.trials.empty()) plan.trials.back().break_after = false;  // the session simply ends
  return plan;
}

std::string finger_numbers_text(const FingerFlags& f) {
  std::string s;
  for (int i = 0; i < kFingerCount; ++i) {
    if (f[static_cast<std::size_t>(i)]) s += std::to_string(i + 1);
  }
  return s.empty() ? "none" : s;
}

void write_plan_csv(std::ostream& out, const Protocol& p, const SessionPlan& plan) {
  out << "position,block,condition,mode,practice,stimulus_kPa,tumor_fingers,break_after\n";
  for (const PlannedTrial& t : plan.trials) {
    const Condition& c = p.conditions[static_cast<std::size_t>(t.condition)];
    std::string stimulus = "scene", tumor = "";
    if (p.task == TaskKind::localisation) {
      if (p.localisation.listed && t.combination >= 0)
        stimulus = p.localisation.cases.at(static_cast<std::size_t>(t.combination)).name;
      else if (p.localisation.generate)
        stimulus = std::string("generated ") + to_string(*p.localisation.generate);
    } else if (t.combination >= 0) {
      const auto& combination = p.combinations[static_cast<std::size_t>(t.combination)];
      stimulus = combination.label;
      tumor = finger_numbers_text(combination.tumor);
    }
    out << t.position + 1 << "," << t.block + 1 << "," << c.name << "," << to_string(c.mode) << ","
        << (t.practice ? 1 : 0) << "," << stimulus << "," << tumor << "," << (t.break_after ? 1 : 0) << "\n";
  }
}

}  // namespace palprig
