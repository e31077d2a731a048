// gui::EventClock: an input event's own timestamp placed on steady_clock. A local X server's
// stamps (CLOCK_MONOTONIC in ms, 32 bits), their wrap-around, a foreign clock at an unknown
// offset (estimated per session, used once its rate is confirmed), a clock that does not run at
// our rate (a test tool's counter) and no stamp at all.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>

#include "gui/event_clock.hpp"

namespace palprig::gui {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;
using time_point = EventClock::time_point;

time_point at_us(std::int64_t us) {
  return time_point(std::chrono::duration_cast<time_point::duration>(microseconds(us)));
}
double ms_between(time_point a, time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

TEST(gui_event_clock, a_monotonic_stamp_is_the_middle_of_its_millisecond_whatever_the_delivery_delay) {
  EventClock clock;
  // The key went down at 1,000,123.400 ms; delivered 37 ms later (a busy GUI thread).
  const time_point happened = at_us(1'000'123'400);
  const auto m = clock.map(1'000'123, happened + milliseconds(37));
  EXPECT_EQ(m.source, EventClock::Source::monotonic);
  EXPECT_NEAR(ms_between(happened, m.at), 0.1, 1e-6);  // 123.5 vs 123.4
  // The same stamp delivered 1.9 s late is still ours; the time does not move with the delay.
  EXPECT_EQ(clock.map(1'000'123, happened + milliseconds(1900)).at, m.at);
}

TEST(gui_event_clock, a_32_bit_stamp_that_wrapped_is_placed_in_our_clocks_turn) {
  EventClock clock;
  // 60 days of uptime: CLOCK_MONOTONIC is past 2^32 ms; the X stamp is the low 32 bits.
  const std::int64_t now_ms = 60LL * 24 * 3600 * 1000 + 5;
  const std::uint64_t stamp = static_cast<std::uint64_t>(now_ms - 3) % 4294967296ULL;
  const auto m = clock.map(stamp, at_us(now_ms * 1000));
  EXPECT_EQ(m.source, EventClock::Source::monotonic);
  EXPECT_NEAR(ms_between(m.at, at_us(now_ms * 1000)), 2.5, 1e-6);
  // Just after a wrap: the stamp is small, our clock just past a multiple of 2^32.
  const std::int64_t wrap_ms = 4294967296LL * 2 + 1;
  const auto w = clock.map(4294967295ULL, at_us(wrap_ms * 1000));  // stamped 2 ms before, before the wrap
  EXPECT_EQ(w.source, EventClock::Source::monotonic);
  EXPECT_NEAR(ms_between(w.at, at_us(wrap_ms * 1000)), 1.5, 1e-6);
}

TEST(gui_event_clock, the_mapped_time_is_never_after_the_delivery) {
  EventClock clock;
  // Stamped in the same millisecond as the delivery, 0.2 ms into it.
  const auto m = clock.map(5'000'000, at_us(5'000'000'200));
  EXPECT_EQ(m.source, EventClock::Source::monotonic);
  EXPECT_EQ(m.at, at_us(5'000'000'200));
}

TEST(gui_event_clock, no_stamp_is_the_delivery_time) {
  EventClock clock;
  const auto m = clock.map(0, at_us(123'456'789));
  EXPECT_EQ(m.source, EventClock::Source::delivery);
  EXPECT_EQ(m.at, at_us(123'456'789));
}

TEST(gui_event_clock, a_foreign_clock_is_used_at_its_estimated_offset_once_it_is_seen_to_run_at_our_rate) {
  // A remote X server whose milliseconds are ours minus 7,654,321 ms; network delays 3-9 ms.
  constexpr std::int64_t offset_ms = 7'654'321;
  const std::int64_t base_ms = 900'000'000;
  EventClock clock;
  const auto event = [&](std::int64_t true_ms, int delay_ms) {
    return clock.map(static_cast<std::uint64_t>(true_ms - offset_ms), at_us((true_ms + delay_ms) * 1000));
  };
  // Before its rate is known: the delivery time.
  EXPECT_EQ(event(base_ms, 9).source, EventClock::Source::delivery);
  EXPECT_EQ(event(base_ms + 400, 3).source, EventClock::Source::delivery);
  // 2 s later the stamps and the deliveries agree: the offset (smallest delay: 3 ms) is used.
  const auto m = event(base_ms + 2000, 8);
  EXPECT_EQ(m.source, EventClock::Source::offset);
  EXPECT_NEAR(ms_between(at_us((base_ms + 2000) * 1000), m.at), 3.0, 1e-6);
  // An event delayed far beyond the others (the offset no longer holds for it): delivery time.
  const auto late = event(base_ms + 3000, 200);
  EXPECT_EQ(late.source, EventClock::Source::delivery);
}

TEST(gui_event_clock, a_counter_that_does_not_run_at_our_rate_is_never_used) {
  // Qt Test's emulated mouse stamps: a few hundred ms per click whatever time passed.
  EventClock clock;
  std::uint64_t stamp = 1;
  for (int i = 0; i < 20; ++i) {
    const auto m = clock.map(stamp, at_us((800'000'000 + i * 3'000) * 1000LL));
    EXPECT_EQ(m.source, EventClock::Source::delivery) << i;
    EXPECT_EQ(m.at, at_us((800'000'000 + i * 3'000) * 1000LL)) << i;
    stamp += 401;
  }
}

}  // namespace
}  // namespace palprig::gui
