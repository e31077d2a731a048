#include "gui/gui_participant.hpp"

namespace palprig::gui {

bool ParticipantChannel::give_answer(int position, const Response& response) noexcept {
  if (response.marks.size() > static_cast<std::size_t>(kMaxMarks)) return false;
  GivenAnswer a;
  a.position = position;
  a.serial = next_serial_++;
  a.tumor_under = response.tumor_under;
  a.confidence = response.confidence.value_or(0);
  a.mark_count = static_cast<int>(response.marks.size());
  for (std::size_t i = 0; i < response.marks.size(); ++i) a.marks[i] = response.marks[i];
  answers_.publish(a);
  return true;
}

std::optional<Response> ParticipantChannel::take_answer(int position) {
  const GivenAnswer& a = answers_.latest();
  if (a.serial == 0 || a.serial == taken_serial_ || a.position != position) return std::nullopt;
  taken_serial_ = a.serial;
  Response r;
  r.tumor_under = a.tumor_under;
  if (a.confidence > 0) r.confidence = a.confidence;
  r.marks.assign(a.marks.begin(), a.marks.begin() + a.mark_count);
  return r;
}

}  // namespace palprig::gui
