#include "study/trial_order.hpp"

#include <algorithm>
#include <numeric>

namespace palprig {

namespace {

// What the constraints need to know about an order: its length, where each item last
// appeared and the current run at its end.
struct OrderState {
  int length = 0;
  std::vector<int> last_position;  // -1: never
  int run_item = -1;
  int run_length = 0;

  explicit OrderState(std::size_t items) : last_position(items, -1) {}

  bool allows(int item, const OrderConstraints& c) const {
    if (c.max_repeats_in_a_row > 0 && item == run_item && run_length >= c.max_repeats_in_a_row) return false;
    if (c.min_distance > 1 && last_position[static_cast<std::size_t>(item)] >= 0 &&
        length - last_position[static_cast<std::size_t>(item)] < c.min_distance) {
      return false;
    }
    return true;
  }

  void push(int item) {
    run_length = item == run_item ? run_length + 1 : 1;
    run_item = item;
    last_position[static_cast<std::size_t>(item)] = length;
    ++length;
  }
};

OrderState state_of(const std::vector<int>& order, std::size_t items) {
  OrderState s(items);
  for (int item : order) s.push(item);
  return s;
}

// Complete the order with "most remaining first" (ties: lowest item); true when it gets through.
bool greedy_completes(OrderState state, std::vector<int> remaining, const OrderConstraints& c) {
  int left = std::accumulate(remaining.begin(), remaining.end(), 0);
  while (left > 0) {
    int best = -1;
    for (std::size_t i = 0; i < remaining.size(); ++i) {
      if (remaining[i] > 0 && state.allows(static_cast<int>(i), c) &&
          (best < 0 || remaining[i] > remaining[static_cast<std::size_t>(best)])) {
        best = static_cast<int>(i);
      }
    }
    if (best < 0) return false;
    state.push(best);
    --remaining[static_cast<std::size_t>(best)];
    --left;
  }
  return true;
}

// The runs constraint alone (no distance constraint): the order can be completed exactly when
// every remaining item fits between the others: item i has at most ceil(r_i / k) runs of at most
// k, separated by at least one other item each, and when i is the run the order ends with (L
// long) its first run holds k - L at most: r_i <= k (n - r_i) + k - L. "Most remaining first"
// completes exactly then (the classic rule for k = 1, "reorganise a string"; for every k it is
// checked against an exhaustive search in tests/study/trial_order_feasibility_test.cpp), so the
// search below asks this O(items) test instead of simulating the rule over the whole rest of the
// order at every step, which made planning quadratic in the trials (1,000 repetitions of the
// shipped discrimination protocol took 7 s).
bool runs_completable(const OrderState& state, const std::vector<int>& remaining, int k) {
  if (k <= 0) return true;
  const long long n = std::accumulate(remaining.begin(), remaining.end(), 0LL);
  for (std::size_t i = 0; i < remaining.size(); ++i) {
    const long long r = remaining[i];
    if (r == 0) continue;
    const long long run = static_cast<int>(i) == state.run_item ? state.run_length : 0;
    if (r > static_cast<long long>(k) * (n - r) + k - run) return false;
  }
  return true;
}

bool completes(const OrderState& state, const std::vector<int>& remaining, const OrderConstraints& c) {
  if (c.min_distance > 1) return greedy_completes(state, remaining, c);
  return runs_completable(state, remaining, c.max_repeats_in_a_row);
}

}  // namespace

namespace detail {

bool greedy_completes_after(const std::vector<int>& order, std::size_t items, const std::vector<int>& remaining,
                            const OrderConstraints& constraints) {
  return greedy_completes(state_of(order, items), remaining, constraints);
}

bool completes_after(const std::vector<int>& order, std::size_t items, const std::vector<int>& remaining,
                     const OrderConstraints& constraints) {
  return completes(state_of(order, items), remaining, constraints);
}

}  // namespace detail

bool extend_constrained_order(std::vector<int>& order, const std::vector<int>& counts,
                              const OrderConstraints& constraints, RandomSource& random) {
  const std::size_t items = counts.size();
  for (int item : order) {
    if (item < 0 || static_cast<std::size_t>(item) >= items) return false;
  }
  OrderState state = state_of(order, items);
  std::vector<int> remaining = counts;
  if (!completes(state, remaining, constraints)) return false;

  std::vector<int> added;
  int left = std::accumulate(remaining.begin(), remaining.end(), 0);
  while (left > 0) {
    // Weighted draw without replacement over the allowed items: try them in that order.
    std::vector<int> pool;
    for (std::size_t i = 0; i < items; ++i) {
      if (remaining[i] > 0 && state.allows(static_cast<int>(i), constraints)) pool.push_back(static_cast<int>(i));
    }
    bool placed = false;
    while (!pool.empty() && !placed) {
      int weight_total = 0;
      for (int i : pool) weight_total += remaining[static_cast<std::size_t>(i)];
      auto draw = static_cast<int>(random.below(static_cast<std::uint64_t>(weight_total)));
      std::size_t pick = 0;
      while (draw >= remaining[static_cast<std::size_t>(pool[pick])])
        draw -= remaining[static_cast<std::size_t>(pool[pick++])];
      const int candidate = pool[pick];
      OrderState next = state;
      next.push(candidate);
      --remaining[static_cast<std::size_t>(candidate)];
      if (completes(next, remaining, constraints)) {
        state = std::move(next);
        added.push_back(candidate);
        placed = true;
      } else {
        ++remaining[static_cast<std::size_t>(candidate)];
        pool.erase(pool.begin() + static_cast<std::ptrdiff_t>(pick));
      }
    }
    // The greedy choice always keeps the invariant, so a candidate is always found.
    if (!placed) return false;
    --left;
  }
  order.insert(order.end(), added.begin(), added.end());
  return true;
}

std::optional<std::string> order_infeasibility(const std::vector<int>& counts, const OrderConstraints& constraints,
                                               const std::vector<std::string>& names) {
  if (greedy_completes(OrderState(counts.size()), counts, constraints)) return std::nullopt;
  const int n = std::accumulate(counts.begin(), counts.end(), 0);
  const auto most = static_cast<std::size_t>(std::max_element(counts.begin(), counts.end()) - counts.begin());
  const int m = counts[most];
  const auto tied = static_cast<int>(std::count(counts.begin(), counts.end(), m));
  const std::string name = most < names.size() ? names[most] : "item " + std::to_string(most);
  if (constraints.min_distance > 1) {
    return "'" + name + "' occurs " + std::to_string(m) + " times in " + std::to_string(n) +
           " trials; keeping identical trials " + std::to_string(constraints.min_distance) + " apart needs at least " +
           std::to_string((m - 1) * constraints.min_distance + tied) + " trials";
  }
  return "'" + name + "' occurs " + std::to_string(m) + " times in " + std::to_string(n) + " trials; with at most " +
         std::to_string(constraints.max_repeats_in_a_row) + " in a row it needs at least " +
         std::to_string((m + constraints.max_repeats_in_a_row - 1) / constraints.max_repeats_in_a_row - 1) +
         " other trials between its runs, there are " + std::to_string(n - m);
}

bool order_satisfies(const std::vector<int>& order, const OrderConstraints& constraints) {
  int max_item = -1;
  for (int item : order) max_item = std::max(max_item, item);
  OrderState state(static_cast<std::size_t>(max_item + 1));
  for (int item : order) {
    if (item < 0 || !state.allows(item, constraints)) return false;
    state.push(item);
  }
  return true;
}

}  // namespace palprig
