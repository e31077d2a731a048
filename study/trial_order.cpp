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

}  // namespace

bool extend_constrained_order(std::vector<int>& order, const std::vector<int>& counts,
                              const OrderConstraints& constraints, RandomSource& random) {
  const std::size_t items = counts.size();
  for (int item : order) {
    if (item < 0 || static_cast<std::size_t>(item) >= items) return false;
  }
  OrderState state = state_of(order, items);
  std::vector<int> remaining = counts;
  if (!greedy_completes(state, remaining, constraints)) return false;

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
      while (draw >= remaining[static_cast<std::size_t>(pool[pick])]) draw -= remaining[static_cast<std::size_t>(pool[pick++])];
      const int candidate = pool[pick];
      OrderState next = state;
      next.push(candidate);
      --remaining[static_cast<std::size_t>(candidate)];
      if (greedy_completes(next, remaining, constraints)) {
        state = next;
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
           " trials; keeping identical trials " + std::to_string(constraints.min_distance) +
           " apart needs at least " + std::to_string((m - 1) * constraints.min_distance + tied) + " trials";
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
