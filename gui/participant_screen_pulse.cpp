// ParticipantScreen's pulse-localisation part (the rest is participant_screen.cpp): the marking
// screen with one trial's scene at a time, arteries hidden, one mark.
#include <QLabel>
#include <QPushButton>
#include <QStackedWidget>

#include "formats/scene_file.hpp"
#include "study/pulse_scene.hpp"
#include "gui/localisation_marking.hpp"
#include "gui/participant_screen.hpp"

namespace palprig::gui {

void ParticipantScreen::start_pulse_session(const PulseProtocol&, std::shared_ptr<ParticipantChannel> channel) {
  marking_->detach_pen();  // before the last session's channel (and its pen) may go
  event_clock_.reset();
  pressed_.clear();
  channel_ = std::move(channel);
  localisation_ = false;
  pulse_ = true;
  pages_->setCurrentWidget(marking_);
  pages_->setVisible(true);
  marking_->set_single_mark(true);
  set_answering(false);
  show_wait(channel_ ? "Please wait" : "Simulated participant (pilot run)");
}

void ParticipantScreen::show_pulse_trial(const PulseTrialStart& start, const PulseCondition& condition) {
  ready_->setVisible(false);
  // The scene the session presents: the condition's file (validated with the protocol), or the
  // generated case of the trial's seed (the same seed gives the same scene).
  SceneFile scene = condition.generated && start.scene_seed
                        ? generated_pulse_scene(*start.scene_seed, *condition.generated)
                        : load_scene_file(condition.scene_file);
  marking_->show_scene(std::move(scene), channel_ ? &channel_->pen() : nullptr);
  if (!channel_) {
    prompt_->setText(QString("Simulated participant (pilot run): trial %1").arg(start.position + 1));
    return;
  }
  prompt_->setText(QString("Trial %1. Palpate with the pen and find where the pulse is strongest. Right-click (or "
                           "press M) there; marking again moves the mark. Done (Enter) when finished.")
                       .arg(start.position + 1));
  answering_ = start.position;
  set_answering(true);
  setFocus();
}

}  // namespace palprig::gui
