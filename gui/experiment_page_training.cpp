// The experiment console running a trainee's next session (the Training view's Start next
// session): the session's protocol is the one sessions/training_session planned for the trainee
// (prepared on this thread, so the participant screen is set up with its cases before the
// session thread starts), run on SessionRun's thread by run_training_session, which scores it
// against the level's benchmark at its end. The rest of the console (participant screen, keys,
// pause, abort, trial list with the answer key hidden from a person) is the one begin() uses.
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QTableWidget>

#include "gui/experiment_page.hpp"
#include "gui/gui_pulse_participant.hpp"
#include "gui/participant_keys.hpp"
#include "gui/participant_screen.hpp"
#include "gui/statistics_view.hpp"
#include "sessions/session_preview.hpp"
#include "study/pulse_protocol.hpp"

namespace palprig::gui {

bool ExperimentPage::begin_training(const TrainingRequest& r, const PreparedTraining& p) {
  if (run_.running()) return false;
  protocol_.reset();
  pulse_protocol_.reset();
  offered_session_.reset();
  resume_note_->clear();
  status_->setStyleSheet("");
  status_->setProperty("refusal", QString());
  const std::filesystem::path base = p.curriculum_file.parent_path();
  try {
    if (p.plan.pulse)
      pulse_protocol_ = parse_pulse_protocol(p.protocol, p.curriculum.source, base);
    else
      protocol_ = parse_protocol(p.protocol, p.curriculum.source, base);
  } catch (const std::exception& e) {
    refuse(e.what());
    set_buttons();
    return false;
  }
  // The fields show whose session it is; the protocol is the curriculum's level, not a file.
  protocol_edit_->clear();
  participant_edit_->setText(QString::fromStdString(r.trainee));
  store_edit_->setText(QString::fromStdString(r.store_location));
  telemetry_edit_->clear();
  set_table_columns(p.plan.pulse);
  table_->setRowCount(0);
  if (pulse_protocol_) {
    // The order run_pulse_study presents (a localisation session's is read back from the store
    // when it starts: on_started).
    try {
      const PulseSessionPreview preview = preview_pulse_session(r.store_location, *pulse_protocol_, r.trainee);
      show_pulse_order(preview.protocol, preview.order);
      for (const PulseTrialRecord& t : preview.committed) tick_pulse_row(t);
    } catch (const std::exception&) {
      // For display only: the rows are filled as the trials commit.
    }
  }
  QString cases;
  for (const auto& c : p.plan.cases) cases += (cases.isEmpty() ? "" : ", ") + QString::fromStdString(c);
  plan_note_->setText(QString("Training: %1, '%2' level %3 '%4', session %5%6: %7")
                          .arg(QString::fromStdString(r.trainee))
                          .arg(QString::fromStdString(p.plan.curriculum))
                          .arg(p.plan.level + 1)
                          .arg(QString::fromStdString(p.plan.level_name))
                          .arg(p.plan.session_number)
                          .arg(p.plan.resumed ? " (continued)" : "")
                          .arg(cases));

  TrainingRequest request = r;
  if (request.rig_file.empty() && host_.rig_file) request.rig_file = host_.rig_file();
  if (request.calibration_file.empty() && host_.calibration_file) request.calibration_file = host_.calibration_file();
  request.tick_observer = host_.tick_observer ? host_.tick_observer() : nullptr;
  request.rig = host_.opened_rig ? &host_.opened_rig() : nullptr;  // leased for the session
  request.person_palpates = true;                                  // the window gives a person a pen
  simulated_ = !request.participant.empty();
  if (!simulated_) request.speed = 0;
  channel_ = simulated_ ? nullptr : std::make_shared<ParticipantChannel>();
  PersonFactory person;
  PulsePersonFactory pulse_person;
  if (!simulated_) {
    person = [channel = channel_](const Protocol& protocol) {
      return std::make_unique<GuiParticipant>(channel, protocol.task == TaskKind::localisation);
    };
    pulse_person = [channel = channel_](const PulseProtocol&) {
      return std::make_unique<GuiPulseParticipant>(channel);
    };
  }
  try {
    if (pulse_protocol_)
      screen_->start_pulse_session(*pulse_protocol_, channel_);
    else
      screen_->start_session(*protocol_, channel_);
  } catch (const std::exception& e) {  // a scene of the set that does not load
    refuse(e.what());
    return false;
  }
  files_written_.clear();
  files_->clear();
  last_completed_ = false;
  training_ = true;
  status_->setText(p.plan.resumed ? "Continuing the trainee's unfinished session..." : "Starting...");
  run_.start_training(request, p, person, pulse_person);
  session_started_for_participant();  // as begin(): the participant never sees the answer key
  return true;
}

}  // namespace palprig::gui
