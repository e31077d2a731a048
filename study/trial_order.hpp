#pragma once
// Constrained random orders: each item (a stimulus combination) appears a given number of
// times, no more than N identical items in a row, identical items at least D positions apart.
//
// The search keeps one invariant: the order built so far can still be completed by the
// deterministic "most remaining first" rule. Every step tries candidates in a random order
// weighted by their remaining count and keeps the first that preserves the invariant, so it
// never backtracks more than one step, and a feasible request always succeeds. The same rule run
// from an empty order decides feasibility (for the distance constraint it is the classic
// optimal greedy; for runs it places the most frequent item whenever allowed).
#include <optional>
#include <string>
#include <vector>

#include "study/random_source.hpp"

namespace palprig {

struct OrderConstraints {
  int max_repeats_in_a_row = 0;  // 0: unlimited
  int min_distance = 0;          // 0 or 1: none; d: identical items at least d positions apart
};

// Append to `order` every item i counts[i] times in a random order that satisfies the
// constraints, taking the items already in `order` as history (for blocked schemes the earlier
// blocks constrain the start of the next). Returns false, leaving `order` unchanged, when no
// completion exists.
bool extend_constrained_order(std::vector<int>& order, const std::vector<int>& counts,
                              const OrderConstraints& constraints, RandomSource& random);

// Why no order of these counts can satisfy the constraints (from scratch), or nothing when one
// exists. `names` label the items in the message.
std::optional<std::string> order_infeasibility(const std::vector<int>& counts, const OrderConstraints& constraints,
                                               const std::vector<std::string>& names);

// True when the order meets the constraints (used by tests and when a stored order is loaded).
bool order_satisfies(const std::vector<int>& order, const OrderConstraints& constraints);

namespace detail {
// For tests: whether `order` followed by `remaining` (counts per item, `items` items) can be
// completed, by simulating "most remaining first" and by the test the search uses.
bool greedy_completes_after(const std::vector<int>& order, std::size_t items, const std::vector<int>& remaining,
                            const OrderConstraints& constraints);
bool completes_after(const std::vector<int>& order, std::size_t items, const std::vector<int>& remaining,
                     const OrderConstraints& constraints);
}  // namespace detail

}  // namespace palprig
