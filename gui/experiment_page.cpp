#include "gui/experiment_page.hpp"
#include "gui/participant_keys.hpp"

#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QScreen>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>

#include "experiments/simulated_participant.hpp"
#include "gui/participant_screen.hpp"
#include "sessions/session_preview.hpp"
#include "sessions/session_telemetry.hpp"
#include "gui/statistics_view.hpp"
#include "core/input_error.hpp"
#include "sessions/session_setup.hpp"
#include "store/trial_store.hpp"

namespace palprig::gui {

namespace {

QString flags_text(const FingerFlags& f) {
  QString s;
  for (int i = 0; i < kFingerCount; ++i)
    if (f[static_cast<std::size_t>(i)]) s += QString::number(i + 1);
  return s.isEmpty() ? "none" : s;
}

// "010" as stored -> "2"
QString stored_flags_text(const std::string& bits) {
  QString s;
  for (std::size_t i = 0; i < bits.size(); ++i)
    if (bits[i] == '1') s += QString::number(i + 1);
  return s.isEmpty() ? "none" : s;
}

}  // namespace

ExperimentPage::ExperimentPage(ExperimentHost host, QWidget* parent)
    : QWidget(parent), host_(std::move(host)), run_(host_.control) {
  setObjectName("experiment_page");
  // Top: the session (left) and the participant's screen (right); below, full width, the trial
  // list and the live statistics, whose charts need the room. The parts are built in
  // experiment_page_layout.cpp.
  auto* outer = new QVBoxLayout(this);
  auto* rows = new QSplitter(Qt::Vertical);
  outer->addWidget(rows);
  auto* split = new QSplitter(Qt::Horizontal);
  rows->addWidget(split);

  auto* left = new QWidget;
  auto* left_layout = new QVBoxLayout(left);
  left_layout->addWidget(build_session_form());
  build_session_controls(left_layout);
  QWidget* trials_page = build_trial_list();
  left_layout->addStretch(1);
  split->addWidget(left);
  split->addWidget(build_participant_side());
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 2);
  // Below: the trial list ticking as trials commit, and the live statistics (their charts need
  // the window's width).
  results_ = new QTabWidget;
  results_->setObjectName("results_tabs");
  results_->addTab(trials_page, "Trials");
  results_->addTab(statistics_area_, "Statistics");
  // Below the session form the trial list and the charts take what height is left: their own
  // minimum (the statistics charts, 500 px) would push a 1280 x 800 screen's window off it.
  results_->setMinimumHeight(200);
  rows->addWidget(results_);
  rows->setStretchFactor(0, 2);
  rows->setStretchFactor(1, 3);
  connect_session();
  set_buttons();
}

void ExperimentPage::connect_session() {
  connect(&run_, &SessionRun::started, this, &ExperimentPage::on_started);
  connect(&run_, &SessionRun::trialStarted, this, [this](int, const PlannedTrial& trial, const Condition& condition) {
    screen_->show_trial(trial, condition);
    status_->setText(QString("Trial %1 of %2: %3")
                         .arg(trial.position + 1)
                         .arg(table_->rowCount())
                         .arg(QString::fromStdString(condition.name)));
    if (trial.position < table_->rowCount()) table_->scrollToItem(table_->item(trial.position, 0));
  });
  connect(&run_, &SessionRun::runnerState, this, [this](RunnerState s, int position) {
    if (s == RunnerState::ready && !run_.paused())
      screen_->show_ready();
    else if (s == RunnerState::ready) {
      screen_->show_wait("Paused. Please wait.");
      pause_held_ = true;  // the session loop has vented and holds: Continue may go on
      set_buttons();
    } else if (s == RunnerState::rest)
      screen_->show_wait("Break. Please rest.");
    else if (s == RunnerState::respond)
      screen_->stimulus_ended(position);
  });
  connect(&run_, &SessionRun::trialCommitted, this, [this](const TrialRecord& t, int) {
    tick_row(t);
    statistics_->refresh();  // coalesced with the view's own refresh on the file change
    emit trialCommitted(t.planned.position);
  });
  connect(&run_, &SessionRun::participantFeedback, screen_, &ParticipantScreen::show_feedback);
  connect(&run_, &SessionRun::ended, this, &ExperimentPage::on_ended);
  connect_pulse();
  connect(&run_, &SessionRun::refused, this, [this](const QString& line, int code) {
    refuse(line);
    screen_->show_wait("No session");  // not "Please wait": nothing is coming
    emit sessionRefused(line, code);
  });
  connect(&run_, &SessionRun::finished, this, [this] {
    participant_keys_->remove();  // the keyboard is the experimenter's again
    person_session_ = false;
    apply_answer_key();
    // A session that stopped or faulted is resumable: offer it at once (the list keeps its
    // ticks, read back from the store). A completed one stays on show as it ended.
    if (!last_completed_ && refusal_text().isEmpty() && !training_) {
      const QStringList files = files_written_;
      const QString status = status_->text();
      update_plan();
      files_written_ = files;
      show_files();
      status_->setText(status);
    }
    set_buttons();
    if (training_) {
      training_ = false;  // `train next` (or the Training view) continues a stopped one
      emit trainingFinished();
    }
  });
}

ExperimentPage::~ExperimentPage() { run_.abort_and_wait(); }

void ExperimentPage::set_fields(const ExperimentFields& f) {
  protocol_edit_->setText(QString::fromStdString(f.protocol));
  participant_edit_->setText(QString::fromStdString(f.participant));
  store_edit_->setText(QString::fromStdString(f.store));
  speed_->setValue(f.speed);
  telemetry_edit_->setText(QString::fromStdString(f.telemetry));
  update_plan();
}

ExperimentFields ExperimentPage::fields() const {
  return {protocol_edit_->text().trimmed().toStdString(), participant_edit_->text().trimmed().toStdString(),
          store_edit_->text().trimmed().toStdString(), speed_->value(),
          telemetry_edit_->text().trimmed().toStdString()};
}

QString ExperimentPage::refusal_text() const { return status_->property("refusal").toString(); }

void ExperimentPage::refuse(const QString& line) {
  status_->setProperty("refusal", line);
  status_->setStyleSheet("color: #b00020");
  status_->setText("palprig: " + line);
}

void ExperimentPage::update_plan() {
  if (run_.running()) return;
  const ExperimentFields f = fields();
  protocol_.reset();
  pulse_protocol_.reset();
  offered_session_.reset();
  resume_note_->clear();
  plan_note_->clear();
  // A refusal is cleared with its cause: the fields are read again below and refused anew if
  // still wrong.
  if (!refusal_text().isEmpty()) status_->setText("No session.");
  status_->setStyleSheet("");
  status_->setProperty("refusal", QString());
  speed_->setEnabled(is_simulated_participant(f.participant));
  table_->setRowCount(0);
  set_table_columns(false);
  if (f.protocol.empty()) {
    set_buttons();
    return;
  }
  if (update_pulse_plan(f)) return;
  try {
    protocol_ = load_protocol(f.protocol);
  } catch (const std::exception& e) {
    refuse(e.what());
    set_buttons();
    return;
  }
  if (f.participant.empty()) {
    plan_note_->setText("Enter the participant code to see the planned order.");
    set_buttons();
    return;
  }
  // The order a resumed session continues with is the stored one; a new participant's is the
  // one `palprig experiment plan` prints for the next enrolment number (sessions/ decides both).
  SessionPreview preview;
  try {
    if (!f.store.empty() && std::filesystem::exists(f.store) &&
        statistics_->store_location() != QString::fromStdString(f.store)) {
      statistics_->set_store(QString::fromStdString(f.store));
    }
    preview = preview_session(f.store, *protocol_, f.participant);
  } catch (const std::exception& e) {
    refuse(e.what());
    set_buttons();
    return;
  }
  show_plan(*protocol_, preview.plan);
  if (const auto id = preview.unfinished_session) {
    offered_session_ = *id;
    offered_start_ = preview.completed_trials;
    for (const StoredTrial& t : preview.committed) {
      if (t.position >= table_->rowCount()) continue;
      table_->item(t.position, kAnswer)->setText(t.answered ? stored_flags_text(t.answer) : "no answer");
      table_->item(t.position, kScore)
          ->setText(QString::fromStdString(t.outcome[0] + " " + t.outcome[1] + " " + t.outcome[2]).trimmed());
      table_->item(t.position, kResponseTime)
          ->setText(t.response_time_s ? QString::number(*t.response_time_s, 'f', 2) : "");
      table_->item(t.position, kRtAfterStimulus)
          ->setText(t.rt_after_stimulus_s ? QString::number(*t.rt_after_stimulus_s, 'f', 2) : "");
      table_->item(t.position, kConfidence)->setText(t.confidence ? QString::number(*t.confidence) : "");
      table_->item(t.position, kCommitted)->setText("\u2713");
    }
    resume_note_->setText(QString("%1 has an unfinished session (%2) with this protocol: %3 of %4 trials committed. "
                                  "Resume session continues at trial %5.")
                              .arg(participant_edit_->text())
                              .arg(*id)
                              .arg(preview.completed_trials)
                              .arg(preview.plan.trials.size())
                              .arg(preview.completed_trials + 1));
    plan_note_->setText(QString("Stored order of session %1 (seed %2).").arg(*id).arg(preview.seed));
  } else if (f.store.empty()) {
    plan_note_->setText(QString("Choose the trial database: the order depends on the participant's number in it "
                                "(shown: a first participant's, seed %1).")
                            .arg(preview.seed));
  } else {
    plan_note_->setText(QString("Planned order for participant number %1 (seed %2), as `palprig experiment plan` "
                                "prints it.")
                            .arg(preview.participant_number)
                            .arg(preview.seed));
  }
  set_buttons();
}

void ExperimentPage::show_plan(const Protocol& p, const SessionPlan& plan) {
  table_->setRowCount(static_cast<int>(plan.trials.size()));
  for (const PlannedTrial& t : plan.trials) {
    const Condition& c = p.conditions.at(static_cast<std::size_t>(t.condition));
    QString stimulus = "scene", tumor;
    if (c.mode != PresentationMode::scene && t.combination >= 0 &&
        t.combination < static_cast<int>(p.combinations.size())) {
      const auto& combination = p.combinations.at(static_cast<std::size_t>(t.combination));
      stimulus = QString::fromStdString(combination.label);
      tumor = flags_text(combination.tumor);
    }
    const QStringList cells = {QString::number(t.position + 1),
                               QString::number(t.block + 1),
                               QString::fromStdString(c.name) + (t.practice ? " (practice)" : ""),
                               stimulus,
                               tumor,
                               "",
                               "",
                               "",
                               "",
                               "",
                               ""};
    for (int col = 0; col < kColumns; ++col) table_->setItem(t.position, col, new QTableWidgetItem(cells[col]));
  }
}

void ExperimentPage::tick_row(const TrialRecord& t) {
  const int row = t.planned.position;
  if (row >= table_->rowCount()) return;
  QString answer = "no answer", score;
  if (t.answered && t.mode != PresentationMode::scene) {
    answer = flags_text(t.answer);
    score = QString("%1 %2 %3")
                .arg(to_string(t.finger_outcomes[0]))
                .arg(to_string(t.finger_outcomes[1]))
                .arg(to_string(t.finger_outcomes[2]));
  } else if (t.answered) {
    answer = QString("%1 marks").arg(t.marks.size());
    QStringList found;
    for (const auto& s : t.localisation.tumors)
      found << QString("%1 %2").arg(QString::fromStdString(s.tumor)).arg(s.hit ? "found" : "missed");
    score = found.join(", ") + QString("; %1 false").arg(t.localisation.false_marks);
  }
  table_->item(row, kAnswer)->setText(answer);
  table_->item(row, kScore)->setText(score);
  table_->item(row, kResponseTime)->setText(t.answered ? QString::number(t.response_time_s, 'f', 2) : "");
  const double after_s = response_time_after_stimulus_s(t);
  table_->item(row, kRtAfterStimulus)->setText(std::isfinite(after_s) ? QString::number(after_s, 'f', 2) : "");
  table_->item(row, kConfidence)->setText(t.confidence ? QString::number(*t.confidence) : "");
  table_->item(row, kCommitted)->setText("\u2713");
  table_->scrollToItem(table_->item(row, 0));
}

}  // namespace palprig::gui
