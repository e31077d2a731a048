#include "gui/gui_participant.hpp"

namespace palprig::gui {

bool ParticipantChannel::give_answer(int position, const Response& response,
                                     std::optional<std::chrono::steady_clock::time_point> given_at) noexcept {
  if (response.marks.size() > static_cast<std::size_t>(kMaxMarks)) return false;
  GivenAnswer a;
  a.position = position;
  a.serial = next_serial_++;
  a.tumor_under = response.tumor_under;
  a.confidence = response.confidence.value_or(0);
  a.mark_count = static_cast<int>(response.marks.size());
  for (std::size_t i = 0; i < response.marks.size(); ++i) a.marks[i] = response.marks[i];
  if (given_at)
    a.given_at_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(given_at->time_since_epoch()).count();
  answers_.publish(a);
  return true;
}

std::optional<Response> ParticipantChannel::take_answer(
    int position, std::optional<std::chrono::steady_clock::time_point>* given_at) {
  const GivenAnswer& a = answers_.latest();
  if (a.serial == 0 || a.serial == taken_serial_ || a.position != position) return std::nullopt;
  taken_serial_ = a.serial;
  Response r;
  r.tumor_under = a.tumor_under;
  if (a.confidence > 0) r.confidence = a.confidence;
  r.marks.assign(a.marks.begin(), a.marks.begin() + a.mark_count);
  if (given_at) {
    given_at->reset();
    if (a.given_at_ns != 0) {
      *given_at = std::chrono::steady_clock::time_point(
          std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::nanoseconds(a.given_at_ns)));
    }
  }
  return r;
}

}  // namespace palprig::gui
