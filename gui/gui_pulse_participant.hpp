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
    const std::optional<Response> given = channel_->take_answer(position_);
    if (!given || given->marks.empty()) return std::nullopt;
    return given->marks.front();  // the screen hands over exactly one mark
  }

 private:
  std::shared_ptr<ParticipantChannel> channel_;
  int position_ = -1;
};

}  // namespace palprig::gui
