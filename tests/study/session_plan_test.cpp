// Session plans: counterbalancing, practice, blocks and breaks, reproducibility from the seed.
#include <gtest/gtest.h>

#include <filesystem>
#include <algorithm>
#include <map>

#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "study/trial_order.hpp"

namespace palprig {
namespace {

const std::filesystem::path kPlanProtocols = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "protocols";

TEST(experiments_session_plan, paper_002_session_layout) {
  const Protocol p = load_protocol(kPlanProtocols / "discrimination_002.json");
  const SessionPlan first = make_session_plan(p, 1, 99);
  const SessionPlan second = make_session_plan(p, 2, 99);
  // 2 conditions x (2 practice + 14 trials).
  ASSERT_EQ(first.trials.size(), 32u);
  // Alternate counterbalancing: participant 1 as listed, participant 2 reversed.
  EXPECT_EQ(first.condition_order, (std::vector<int>{0, 1}));
  EXPECT_EQ(second.condition_order, (std::vector<int>{1, 0}));
  EXPECT_EQ(first.trials.front().condition, 0);
  EXPECT_EQ(second.trials.front().condition, 1);

  std::map<int, std::map<int, int>> per_condition;  // condition -> combination -> count
  int practice = 0, breaks = 0;
  for (std::size_t i = 0; i < first.trials.size(); ++i) {
    const PlannedTrial& t = first.trials[i];
    EXPECT_EQ(t.position, static_cast<int>(i));
    if (t.practice)
      ++practice;
    else
      ++per_condition[t.condition][t.combination];
    if (t.break_after) ++breaks;
  }
  EXPECT_EQ(practice, 4);
  EXPECT_EQ(breaks, 1);  // between the two blocks only
  EXPECT_TRUE(first.trials[15].break_after);
  for (const auto& [condition, counts] : per_condition) {
    EXPECT_EQ(counts.size(), 14u);
    for (const auto& [combination, n] : counts) EXPECT_EQ(n, 1);
  }
  // Practice trials open each condition.
  EXPECT_TRUE(first.trials[0].practice && first.trials[1].practice && !first.trials[2].practice);
  EXPECT_TRUE(first.trials[16].practice && first.trials[17].practice);
}

TEST(experiments_session_plan, same_seed_same_plan_other_seed_other_order) {
  const Protocol p = load_protocol(kPlanProtocols / "discrimination_002.json");
  auto combos = [](const SessionPlan& s) {
    std::vector<int> v;
    for (const auto& t : s.trials) v.push_back(t.combination);
    return v;
  };
  EXPECT_EQ(combos(make_session_plan(p, 1, 7)), combos(make_session_plan(p, 1, 7)));
  EXPECT_NE(combos(make_session_plan(p, 1, 7)), combos(make_session_plan(p, 1, 8)));
}

TEST(experiments_session_plan, latin_square_is_balanced_for_four_conditions) {
  RandomSource unused(1);
  std::map<std::pair<int, int>, int> follows;
  std::map<std::pair<int, int>, int> position_counts;
  for (int participant = 1; participant <= 4; ++participant) {
    const auto order = counterbalanced_order(Counterbalancing::latin_square, 4, participant, unused);
    for (int i = 0; i < 4; ++i) ++position_counts[{order[static_cast<std::size_t>(i)], i}];
    for (std::size_t i = 0; i + 1 < 4; ++i) ++follows[{order[i], order[i + 1]}];
  }
  // Every condition once in every position, and every ordered pair exactly once (Williams).
  EXPECT_EQ(position_counts.size(), 16u);
  for (const auto& [key, n] : position_counts) EXPECT_EQ(n, 1);
  EXPECT_EQ(follows.size(), 12u);
  for (const auto& [key, n] : follows) EXPECT_EQ(n, 1);
}

TEST(experiments_session_plan, blocked_repetitions_and_breaks_inside_blocks) {
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "blocked", "task": "discrimination", "levels_kPa": [0, 30],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 0, 0], [30, 0, 0], [0, 30, 0], [0, 0, 30]]},
    "conditions": [{"name": "a", "mode": "simultaneous"}],
    "repetitions": 3, "blocks_per_condition": 3, "break_every_trials": 2,
    "randomisation": {"scheme": "blocked", "max_repeats_in_a_row": 1}
  })");
  const Protocol p = parse_protocol(doc, "blocked.json", ".");
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const SessionPlan s = make_session_plan(p, 1, seed);
    ASSERT_EQ(s.trials.size(), 12u);
    std::vector<int> order;
    for (const auto& t : s.trials) order.push_back(t.combination);
    EXPECT_TRUE(order_satisfies(order, {1, 0}));
    for (std::ptrdiff_t rep = 0; rep < 3; ++rep) {
      std::vector<int> run(order.begin() + rep * 4, order.begin() + rep * 4 + 4);
      std::sort(run.begin(), run.end());
      EXPECT_EQ(run, (std::vector<int>{0, 1, 2, 3})) << "each repetition holds every combination once";
      EXPECT_EQ(s.trials[static_cast<std::size_t>(rep * 4)].block, rep);
    }
    // Breaks after trials 2, 4 (block end), 6, 8 (block end), 10; none after the last.
    std::vector<int> breaks;
    for (const auto& t : s.trials)
      if (t.break_after) breaks.push_back(t.position);
    EXPECT_EQ(breaks, (std::vector<int>{1, 3, 5, 7, 9}));
  }
}

}  // namespace
}  // namespace palprig
