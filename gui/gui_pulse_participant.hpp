#pragma once
// GuiPulseParticipant: a person at the window doing pulse localisation, as experiments'
// PulseParticipant (the simulated pulse observer is the other). It shares the discrimination
// participant's ParticipantChannel (gui/gui_participant.hpp): Ready is its atomic flag, the pen
// is its WindowPenInput (as localisation palpates), and the answer is the one mark handed over
// in the wait-free slot tagged by the trial's position, so a mark given for one trial can never
// be taken for the next. Neither thread waits on the other.
#include <memory>
#include <optional>

#include "experiments/pulse_session.hpp"
#include "gui/gui_participant.hpp"

namespace palprig::gui {

class GuiPulseParticipant final : public PulseParticipant {
 public:
  explicit GuiPulseParticipant(std::shared_ptr<ParticipantChannel> channel) : channel_(std::move(channel)) {}

  bool ready(double) override { return channel_->take_ready(); }
  InputSource& trial_started(int position, const PulseCondition&, const Scene&, double) override {
    position_ = position;
    // A mark given for this position before a pause belongs to the interrupted presentation:
    // drop it, so the trial presented again waits for a new one.
    (void)channel_->take_answer(position_);
    return channel_->pen();
  }
  void feel(const FeltSample&) override {}
  std::optional<Mark> answer(double) override {
    std::optional<std::chrono::steady_clock::time_point> given_at;
    const std::optional<Response> given = channel_->take_answer(position_, &given_at);
    given_at_s_.reset();
    if (!given || given->marks.empty()) return std::nullopt;
    if (given_at && clock_) given_at_s_ = clock_->at_steady(*given_at);  // the click or key's own time
    return given->marks.front();                                         // the screen hands over exactly one mark
  }
  void session_clock(const SessionClock& clock) override { clock_ = &clock; }
  std::optional<double> answer_given_at_s() const override { return given_at_s_; }

 private:
  std::shared_ptr<ParticipantChannel> channel_;
  const SessionClock* clock_ = nullptr;
  std::optional<double> given_at_s_;
  int position_ = -1;
};

}  // namespace palprig::gui
