#include "gui/event_clock.hpp"

#include <algorithm>
#include <cmath>

namespace palprig::gui {

namespace {

constexpr double kWrap_ms = 4294967296.0;  // X11 timestamps are 32-bit milliseconds

double ms_of(EventClock::time_point t) noexcept {
  return std::chrono::duration<double, std::milli>(t.time_since_epoch()).count();
}

EventClock::time_point at_ms(double ms) noexcept {
  return EventClock::time_point(
      std::chrono::duration_cast<EventClock::time_point::duration>(std::chrono::duration<double, std::milli>(ms)));
}

}  // namespace

EventClock::Mapped EventClock::map(std::uint64_t stamp, time_point delivered) noexcept {
  if (stamp == 0) return {delivered, Source::delivery};
  const double delivered_ms = ms_of(delivered);
  double stamp_ms = static_cast<double>(stamp);
  // A 32-bit stamp has wrapped as often as our clock's milliseconds have: the stamp's turn is
  // the one nearest the delivery.
  if (stamp_ms < kWrap_ms) stamp_ms += kWrap_ms * std::round((delivered_ms - stamp_ms) / kWrap_ms);
  const double delay_ms = delivered_ms - stamp_ms;
  if (delay_ms >= 0 && delay_ms <= kMaxDeliveryLag_ms) {
    // Our own clock in whole milliseconds: the event happened within the stamp's millisecond.
    return {std::min(delivered, at_ms(stamp_ms + 0.5)), Source::monotonic};
  }
  // Another clock: the least-delayed event of the session gives the offset.
  min_delay_ms_ = min_delay_ms_ ? std::min(*min_delay_ms_, delay_ms) : delay_ms;
  if (!first_) {
    first_ = Seen{stamp_ms, delivered_ms};
  } else if (!rate_confirmed_ && delivered_ms - first_->delivered_ms >= kRateCheckSpan_ms &&
             std::abs((delivered_ms - first_->delivered_ms) - (stamp_ms - first_->stamp_ms)) <= kForeignJitter_ms) {
    rate_confirmed_ = true;  // it runs at our rate: its offset means something
  }
  if (!rate_confirmed_ || delay_ms - *min_delay_ms_ > kForeignJitter_ms) return {delivered, Source::delivery};
  return {std::min(delivered, at_ms(stamp_ms + *min_delay_ms_)), Source::offset};
}

}  // namespace palprig::gui
