// The experiment console while a session runs: Begin/Resume, the session's start and end, pause,
// continue, abort and which buttons are live (experiment_page.cpp shows the plan before it).

#include "gui/experiment_page.hpp"

#include <QAbstractButton>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>
#include <QSignalBlocker>
#include <QScreen>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>

#include "experiments/simulated_participant.hpp"
#include "gui/counted_text.hpp"
#include "gui/localisation_marking.hpp"
#include "gui/participant_keys.hpp"
#include "gui/participant_screen.hpp"
#include "sessions/session_preview.hpp"
#include "sessions/session_telemetry.hpp"
#include "gui/statistics_view.hpp"
#include "core/input_error.hpp"
#include "sessions/session_setup.hpp"
#include "store/trial_store.hpp"

namespace palprig::gui {

bool ExperimentPage::begin(bool resume) {
  if (run_.running()) return false;
  training_ = false;
  update_plan();
  const ExperimentFields f = fields();
  if (!protocol_ && !pulse_protocol_) {
    if (refusal_text().isEmpty()) refuse("choose a protocol file");
    return false;
  }
  if (f.participant.empty() || f.store.empty()) {
    refuse(f.participant.empty() ? "enter the participant code" : "choose the trial database");
    return false;
  }
  StudySessionRequest request;
  request.protocol_file = f.protocol;
  request.participant_code = f.participant;
  request.store_location = f.store;
  request.rig_file = host_.rig_file ? host_.rig_file() : std::filesystem::path{};
  request.calibration_file = host_.calibration_file ? host_.calibration_file() : std::filesystem::path{};
  request.resume = resume;
  request.telemetry_file = f.telemetry;
  request.tick_observer = host_.tick_observer ? host_.tick_observer() : nullptr;
  request.rig = host_.opened_rig ? &host_.opened_rig() : nullptr;
  simulated_ = is_simulated_participant(f.participant);
  request.speed = simulated_ ? f.speed : 0;
  request.person_palpates = true;  // the window gives a person a pen
  channel_ = simulated_ ? nullptr : std::make_shared<ParticipantChannel>();
  PersonFactory person;
  if (!simulated_) {
    person = [channel = channel_](const Protocol& p) {
      return std::make_unique<GuiParticipant>(channel, p.task == TaskKind::localisation);
    };
  }
  try {
    if (pulse_protocol_)
      screen_->start_pulse_session(*pulse_protocol_, channel_);
    else
      screen_->start_session(*protocol_, channel_);
  } catch (const std::exception& e) {  // a localisation scene that does not load
    refuse(e.what());
    return false;
  }
  files_written_.clear();
  files_->clear();
  last_completed_ = false;
  status_->setStyleSheet("");
  status_->setProperty("refusal", QString());
  status_->setText(resume ? "Resuming..." : "Starting...");
  if (pulse_protocol_)
    start_pulse_run(request);
  else
    run_.start(request, person);
  session_started_for_participant();
  return true;
}

void ExperimentPage::session_started_for_participant() {
  if (!simulated_) participant_keys_->install();
  // The participant never sees the answer key: on its own display when there is a second one
  // (as PsychoPy opens its window there), else the key columns are hidden in this window.
  person_session_ = !simulated_;
  if (person_session_ && QGuiApplication::screens().size() > 1 && !full_screen_->isChecked())
    full_screen_->setChecked(true);
  {
    const QSignalBlocker quiet(show_key_);
    show_key_->setChecked(false);
  }
  apply_answer_key();
  set_buttons();
}

void ExperimentPage::on_started(const SessionStart& s) {
  screen_->set_session_seed(s.seed);
  resume_note_->clear();
  offered_session_.reset();
  // The order being run, as stored (a new participant's number is known only now).
  try {
    if (protocol_) {  // a pulse session's order is the one shown (same seed, same protocol)
      const auto store = open_trial_store(fields().store, TrialStore::Access::read_only);
      const StoredSession stored = store->load_session(s.session_id);
      if (table_->rowCount() != static_cast<int>(stored.plan.trials.size()) || !s.resumed)
        show_plan(*protocol_, stored.plan);
    }
  } catch (const std::exception&) {
    // Reading the order back is for display only; the session goes on.
  }
  plan_note_->setText(QString("%1, participant %2 (no. %3), session %4, seed %5%6%7")
                          .arg(QString::fromStdString(s.protocol_name))
                          .arg(QString::fromStdString(s.participant.code))
                          .arg(s.participant.number)
                          .arg(s.session_id)
                          .arg(s.seed)
                          .arg(s.simulated ? ", simulated participant (stored as simulated)" : "")
                          .arg(s.real_time_hardware ? ", hardware rig: real time" : ""));
  status_->setText(
      s.resumed ? QString("Resumed at trial %1 of %2.").arg(s.start_position + 1).arg(s.total_trials)
                : QString("Session %1 started: %2.").arg(s.session_id).arg(counted(s.total_trials, "trial", "trials")));
  // The runner starts in `ready` (no event says so): the participant's go-ahead is awaited.
  if (s.start_position < s.total_trials) screen_->show_ready();
  // The store exists now (created by the session): the statistics follow it.
  statistics_->set_export_directory(
      QString::fromStdString((std::filesystem::path(fields().store).parent_path() / "exports").string()));
  statistics_->set_store(QString::fromStdString(fields().store));
  emit sessionStarted();
}

void ExperimentPage::on_ended(const SessionEnd& e) {
  last_completed_ = e.completed;
  QString text;
  if (e.completed)
    text = QString("Session completed: %1 committed.").arg(counted(e.committed_trials, "trial", "trials"));
  else if (!e.fault.empty())
    text = QString("Rig fault: %1. Every channel vented; %2 of %3 kept; resume to go on.")
               .arg(QString::fromStdString(e.fault))
               .arg(e.committed_trials)
               .arg(counted(e.total_trials, "trial", "trials"));
  else
    text = QString("Session stopped (vented): %1 of %2 kept; it can be resumed.")
               .arg(e.committed_trials)
               .arg(counted(e.total_trials, "trial", "trials"));
  status_->setStyleSheet(e.fault.empty() ? "" : "color: #b00020");
  status_->setText(text);
  screen_->show_wait(e.completed ? "Thank you, the session is complete." : "The session has stopped.");
  screen_->marking()->clear_marks();  // the next participant starts on a clean scene
  files_written_ = {QString::fromStdString(fields().store)};
  store_note_ =
      QString(" (%1 of %2 committed)").arg(e.committed_trials).arg(counted(e.total_trials, "trial", "trials"));
  if (const std::string telemetry = telemetry_summary(e); !telemetry.empty())
    files_written_ << QString::fromStdString(telemetry);
  show_files();
  statistics_->refresh();
  emit sessionEnded(e);
}

void ExperimentPage::show_statistics() { results_->setCurrentWidget(statistics_area_); }

void ExperimentPage::show_files() {
  if (files_written_.isEmpty()) return;
  QString text = "Files written:\n  trial database " + files_written_.front() + store_note_;
  for (int i = 1; i < files_written_.size(); ++i) text += "\n  " + files_written_[i];
  files_->setText(text);
}

void ExperimentPage::pause() {
  if (!run_.running() || run_.paused()) return;  // Esc and VENT both pause: once
  run_.pause();
  if (channel_) channel_->withdraw_ready();
  pause_held_ = false;
  status_->setText(
      "Paused: every channel vented; the trial in progress is presented again after Continue and the participant's "
      "Ready.");
  screen_->show_wait("Paused. Please wait.");
  set_buttons();
}

void ExperimentPage::resume() {
  if (!run_.running()) return;
  if (!pause_held_) return;  // the loop has not taken the pause yet
  pause_held_ = false;
  run_.resume();
  // The held trial starts again when the participant says ready (fingers back on the actuators).
  if (!simulated_) screen_->show_ready();
  status_->setText(simulated_ ? "Continuing." : "Continuing: waiting for the participant's Ready.");
  set_buttons();
}

void ExperimentPage::abort() {
  if (!run_.running()) return;
  run_.abort();
  status_->setText("Aborting: venting; committed trials are kept.");
}

void ExperimentPage::ask_abort() {
  if (!run_.running()) return;
  auto* box = new QMessageBox(QMessageBox::Question, "palprig", "End the session now?",
                              QMessageBox::Yes | QMessageBox::No, this);
  box->setObjectName("abort_confirmation");
  box->setInformativeText("Every channel vents; the committed trials are kept and the session can be resumed.");
  box->setDefaultButton(QMessageBox::No);  // Enter keeps the session going
  box->setAttribute(Qt::WA_DeleteOnClose);
  connect(box, &QMessageBox::buttonClicked, this, [this, box](QAbstractButton* clicked) {
    if (box->standardButton(clicked) == QMessageBox::Yes) abort();
  });
  box->open();  // window-modal, not exec(): the session and the poll timer go on meanwhile
}

void ExperimentPage::abort_and_wait() {
  run_.abort_and_wait();
  participant_keys_->remove();
  set_buttons();
}

void ExperimentPage::set_buttons() {
  const bool running = run_.running();
  const bool ready = (protocol_.has_value() || pulse_protocol_.has_value()) &&
                     !participant_edit_->text().trimmed().isEmpty() && !store_edit_->text().trimmed().isEmpty();
  begin_->setEnabled(!running && ready && !offered_session_);
  resume_session_->setVisible(offered_session_.has_value());
  resume_session_->setEnabled(!running && offered_session_.has_value());
  pause_->setEnabled(running && !run_.paused());
  continue_->setEnabled(running && run_.paused() && pause_held_);
  abort_->setEnabled(running);
  for (QWidget* w : std::initializer_list<QWidget*>{protocol_edit_, participant_edit_, store_edit_, telemetry_edit_})
    w->setEnabled(!running);
  speed_->setEnabled(!running && is_simulated_participant(participant_edit_->text().trimmed().toStdString()));
  full_screen_->setEnabled(QGuiApplication::screens().size() > 1 || full_screen_->isChecked());
}

}  // namespace palprig::gui
