// Constrained randomisation: every request that can be met is met, with the right multiset,
// reproducibly from the seed; impossible requests are recognised.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "study/random_source.hpp"
#include "study/trial_order.hpp"

namespace palprig {
namespace {

std::map<int, int> histogram(const std::vector<int>& order) {
  std::map<int, int> h;
  for (int i : order) ++h[i];
  return h;
}

TEST(experiments_random_source, same_seed_same_stream_and_unbiased_bounds) {
  RandomSource a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next();
    EXPECT_EQ(x, b.next());
    EXPECT_NE(x, c.next());
  }
  // below(6) over many draws: every face about 1/6 (loose 5-sigma bound).
  RandomSource r(7);
  std::array<int, 6> faces{};
  const int n = 60000;
  for (int i = 0; i < n; ++i) ++faces[r.below(6)];
  for (int f : faces) EXPECT_NEAR(f, n / 6.0, 5 * std::sqrt(n * (1.0 / 6) * (5.0 / 6)));
}

TEST(experiments_random_source, lognormal_has_the_requested_mean_and_sd) {
  RandomSource r(3);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.lognormal_with_mean_sd(4.6, 2.3);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 4.6, 0.03);
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), 2.3, 0.05);
}

TEST(experiments_trial_order, full_shuffle_respects_max_repeats_and_counts) {
  const std::vector<int> counts = {4, 4, 4};
  const OrderConstraints c{1, 0};
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    RandomSource r(seed);
    std::vector<int> order;
    ASSERT_TRUE(extend_constrained_order(order, counts, c, r));
    EXPECT_EQ(order.size(), 12u);
    EXPECT_TRUE(order_satisfies(order, c));
    EXPECT_EQ(histogram(order), (std::map<int, int>{{0, 4}, {1, 4}, {2, 4}}));
  }
}

TEST(experiments_trial_order, tight_min_distance_is_still_met) {
  // 5 items x 3: distance 5 forces every window of 5 to hold each item once.
  const std::vector<int> counts(5, 3);
  const OrderConstraints c{0, 5};
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    RandomSource r(seed);
    std::vector<int> order;
    ASSERT_TRUE(extend_constrained_order(order, counts, c, r)) << seed;
    EXPECT_TRUE(order_satisfies(order, c));
  }
  EXPECT_FALSE(order_infeasibility(counts, c, {}).has_value());
}

TEST(experiments_trial_order, uneven_counts_with_runs) {
  // 'a' 6 times among 9 with at most 2 in a row: aa b aa b aa b is the only shape.
  const std::vector<int> counts = {6, 3};
  const OrderConstraints c{2, 0};
  RandomSource r(11);
  std::vector<int> order;
  ASSERT_TRUE(extend_constrained_order(order, counts, c, r));
  EXPECT_TRUE(order_satisfies(order, c));
  EXPECT_FALSE(order_infeasibility(counts, c, {}).has_value());
  EXPECT_FALSE(order_infeasibility({8, 3}, c, {}).has_value());         // aa b aa b aa b aa
  EXPECT_TRUE(order_infeasibility({9, 3}, c, {"a", "b"}).has_value());  // five runs need four b
}

TEST(experiments_trial_order, impossible_requests_are_named) {
  const auto why = order_infeasibility({3, 1}, OrderConstraints{0, 3}, {"0/30/0", "0/0/0"});
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("0/30/0"), std::string::npos);
  EXPECT_NE(why->find("7 trials"), std::string::npos);  // (3 - 1) * 3 + 1
  RandomSource r(1);
  std::vector<int> order = {0};
  EXPECT_FALSE(extend_constrained_order(order, {3, 1}, OrderConstraints{0, 3}, r));
  EXPECT_EQ(order, std::vector<int>{0});  // unchanged on failure
}

TEST(experiments_trial_order, seeds_give_different_but_reproducible_orders) {
  const std::vector<int> counts(14, 2);
  const OrderConstraints c{1, 0};
  auto make = [&](std::uint64_t seed) {
    RandomSource r(seed);
    std::vector<int> o;
    EXPECT_TRUE(extend_constrained_order(o, counts, c, r));
    return o;
  };
  EXPECT_EQ(make(5), make(5));
  EXPECT_NE(make(5), make(6));
}

TEST(experiments_trial_order, history_constrains_the_start_of_the_next_block) {
  // Blocked scheme: the next block must not start with the item that ended the last one.
  const OrderConstraints c{1, 0};
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    RandomSource r(seed);
    std::vector<int> order = {2, 0, 1};
    ASSERT_TRUE(extend_constrained_order(order, {1, 1, 1}, c, r));
    EXPECT_NE(order[3], 1);
    EXPECT_TRUE(order_satisfies(order, c));
  }
}

}  // namespace
}  // namespace palprig
