// The planner's completion test (study/trial_order.cpp) against the rule it replaced and an
// exhaustive search: for the runs constraint, every state of up to 4 items with up to 4 left
// each, after every possible history run, must get the same answer from the O(items) test, from
// simulating "most remaining first", and from trying every order. Then the plan is linear: a
// long plan keeps its constraints and counts.
#include <gtest/gtest.h>

#include <functional>
#include <numeric>
#include <vector>

#include "study/random_source.hpp"
#include "study/trial_order.hpp"

namespace palprig {
namespace {

// Whether some order of `remaining` after `history` meets the constraints (depth-first, tiny).
bool exists_completion(std::vector<int>& history, std::vector<int>& remaining, const OrderConstraints& c) {
  if (std::accumulate(remaining.begin(), remaining.end(), 0) == 0) return true;
  for (std::size_t i = 0; i < remaining.size(); ++i) {
    if (remaining[i] == 0) continue;
    history.push_back(static_cast<int>(i));
    --remaining[i];
    const bool ok = order_satisfies(history, c) && exists_completion(history, remaining, c);
    ++remaining[i];
    history.pop_back();
    if (ok) return true;
  }
  return false;
}

TEST(TrialOrderFeasibility, RunsTestAgreesWithTheGreedyRuleAndWithExhaustiveSearch) {
  int states = 0, feasible = 0;
  for (int k = 1; k <= 3; ++k) {
    const OrderConstraints c{k, 0};
    for (std::size_t items = 1; items <= 4; ++items) {
      // Every count vector 0..4 per item.
      std::vector<int> remaining(items, 0);
      const std::function<void(std::size_t)> each = [&](std::size_t at) {
        if (at < items) {
          for (int r = 0; r <= 4; ++r) {
            remaining[at] = r;
            each(at + 1);
          }
          return;
        }
        // Histories: nothing, or a run of L (1..k) of one item after another item.
        std::vector<std::vector<int>> histories{{}};
        for (std::size_t x = 0; x < items; ++x) {
          for (int run = 1; run <= k; ++run) {
            std::vector<int> h;
            if (items > 1) h.push_back(static_cast<int>((x + 1) % items));
            for (int i = 0; i < run; ++i) h.push_back(static_cast<int>(x));
            if (order_satisfies(h, c)) histories.push_back(h);
          }
        }
        for (std::vector<int> h : histories) {
          std::vector<int> r = remaining;
          const bool truth = exists_completion(h, r, c);
          EXPECT_EQ(detail::completes_after(h, items, remaining, c), truth) << "k " << k << " items " << items;
          EXPECT_EQ(detail::greedy_completes_after(h, items, remaining, c), truth) << "k " << k << " items " << items;
          ++states;
          feasible += truth;
        }
      };
      each(0);
    }
  }
  EXPECT_GT(states, 10000);
  EXPECT_GT(feasible, 1000);
  EXPECT_LT(feasible, states);
}

TEST(TrialOrderFeasibility, DistanceConstraintStillUsesTheGreedyRule) {
  const OrderConstraints c{0, 3};
  for (const auto& remaining : std::vector<std::vector<int>>{{2, 2, 2}, {3, 1, 1}, {3, 2, 2}, {1, 1}}) {
    std::vector<int> h;
    std::vector<int> r = remaining;
    EXPECT_EQ(detail::completes_after(h, remaining.size(), remaining, c), exists_completion(h, r, c));
  }
}

TEST(TrialOrderFeasibility, ALongPlanKeepsItsCountsAndConstraints) {
  // 8 combinations x 2,500 repetitions = 20,000 trials (the session bound), at most 1 in a row.
  const std::vector<int> counts(8, 2500);
  const OrderConstraints c{1, 0};
  RandomSource random(42);
  std::vector<int> order;
  ASSERT_TRUE(extend_constrained_order(order, counts, c, random));
  ASSERT_EQ(order.size(), 20000u);
  EXPECT_TRUE(order_satisfies(order, c));
  std::vector<int> seen(8, 0);
  for (int item : order) ++seen[static_cast<std::size_t>(item)];
  EXPECT_EQ(seen, counts);
}

}  // namespace
}  // namespace palprig
