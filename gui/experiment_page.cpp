#include "gui/experiment_page.hpp"

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
#include "sessions/session_telemetry.hpp"
#include "gui/statistics_view.hpp"
#include "models/parse_error.hpp"
#include "sessions/session_setup.hpp"
#include "store/trial_store.hpp"

namespace palprig::gui {

namespace {

// kResponseTime: from onset (paper 002's measure, its t-test); kRtAfterStimulus: from the end of
// the stimulus (what the participant was asked to answer after). kCommitted stays last.
enum Column { kPosition, kBlock, kCondition, kStimulus, kTumor, kAnswer, kScore, kResponseTime, kRtAfterStimulus,
              kConfidence, kCommitted, kColumns };

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

bool is_simulated_code(const std::string& code) {
  std::uint64_t seed = 0;
  return parse_simulated_participant(code, seed);
}

QPushButton* button(const char* name, const QString& text) {
  auto* b = new QPushButton(text);
  b->setObjectName(name);
  return b;
}

}  // namespace

ExperimentPage::ExperimentPage(ExperimentHost host, QWidget* parent) : QWidget(parent), host_(std::move(host)) {
  setObjectName("experiment_page");
  // Top: the session (left) and the participant's screen (right); below, full width, the
  // live statistics, whose charts need the room.
  auto* outer = new QVBoxLayout(this);
  auto* rows = new QSplitter(Qt::Vertical);
  outer->addWidget(rows);
  auto* split = new QSplitter(Qt::Horizontal);
  rows->addWidget(split);

  // Left: the session's files, controls, and the trial list.
  auto* left = new QWidget;
  auto* left_layout = new QVBoxLayout(left);
  auto* form_box = new QGroupBox("Session");
  auto* form = new QFormLayout(form_box);
  auto file_row = [this](QLineEdit*& edit, const char* name, const QString& filter, bool save) {
    edit = new QLineEdit;
    edit->setObjectName(name);
    auto* row = new QHBoxLayout;
    row->addWidget(edit, 1);
    auto* browse = new QPushButton("...");
    browse->setMaximumWidth(32);
    connect(browse, &QPushButton::clicked, this, [this, edit, filter, save] {
      const QString path = save ? QFileDialog::getSaveFileName(this, "Trial database", edit->text(), filter,
                                                               nullptr, QFileDialog::DontConfirmOverwrite)
                                : QFileDialog::getOpenFileName(this, "Protocol", edit->text(), filter);
      if (path.isEmpty()) return;
      edit->setText(path);
      update_plan();
    });
    row->addWidget(browse);
    connect(edit, &QLineEdit::editingFinished, this, &ExperimentPage::update_plan);
    return row;
  };
  form->addRow("Protocol", file_row(protocol_edit_, "protocol_file", "Protocols (*.json)", false));
  participant_edit_ = new QLineEdit;
  participant_edit_->setObjectName("participant_code");
  participant_edit_->setPlaceholderText("P01, or sim:SEED for a pilot run with the simulated participant");
  connect(participant_edit_, &QLineEdit::editingFinished, this, &ExperimentPage::update_plan);
  form->addRow("Participant", participant_edit_);
  form->addRow("Trial database", file_row(store_edit_, "store_file", "SQLite trial databases (*.db *.sqlite)", true));
  speed_ = new QDoubleSpinBox;
  speed_->setObjectName("speed");
  speed_->setRange(0, 1000);
  speed_->setDecimals(1);
  speed_->setSpecialValueText("0 (as fast as the simulated rig allows)");
  speed_->setToolTip("Simulated participant on the simulated rig: 0 = as fast as possible, 1 = real time (to watch "
                     "it). People and hardware rigs always run in real time.");
  form->addRow("Pilot speed", speed_);
  {  // Optional: every rig tick of the session, as `experiment run --telemetry` records it.
    auto* row = new QHBoxLayout;
    telemetry_edit_ = new QLineEdit;
    telemetry_edit_->setObjectName("telemetry_file");
    telemetry_edit_->setPlaceholderText("none; or a new .bin / .csv file for every rig tick of the session");
    row->addWidget(telemetry_edit_, 1);
    auto* browse = new QPushButton("...");
    browse->setMaximumWidth(32);
    connect(browse, &QPushButton::clicked, this, [this] {
      const QString path = QFileDialog::getSaveFileName(this, "Session telemetry", telemetry_edit_->text(),
                                                        "Telemetry (*.bin *.csv)");
      if (!path.isEmpty()) telemetry_edit_->setText(path);
    });
    row->addWidget(browse);
    form->addRow("Telemetry", row);
  }
  left_layout->addWidget(form_box);

  plan_note_ = new QLabel;
  plan_note_->setObjectName("plan_note");
  plan_note_->setWordWrap(true);
  left_layout->addWidget(plan_note_);
  resume_note_ = new QLabel;
  resume_note_->setObjectName("resume_note");
  resume_note_->setWordWrap(true);
  resume_note_->setStyleSheet("color: #9a5b00; font-weight: bold");
  left_layout->addWidget(resume_note_);

  auto* buttons = new QHBoxLayout;
  begin_ = button("begin_session", "Begin");
  resume_session_ = button("resume_session", "Resume session");
  pause_ = button("pause_session", "Pause");
  continue_ = button("continue_session", "Continue");
  abort_ = button("abort_session", "Abort");
  pause_->setToolTip("Vents every channel and holds the trial in progress (it is presented again after Continue, once the participant says Ready)");
  abort_->setToolTip("Vents and ends the session; every committed trial is kept and the session can be resumed");
  for (QPushButton* b : {begin_, resume_session_, pause_, continue_, abort_}) buttons->addWidget(b);
  connect(begin_, &QPushButton::clicked, this, [this] { begin(false); });
  connect(resume_session_, &QPushButton::clicked, this, [this] { begin(true); });
  connect(pause_, &QPushButton::clicked, this, &ExperimentPage::pause);
  connect(continue_, &QPushButton::clicked, this, &ExperimentPage::resume);
  connect(abort_, &QPushButton::clicked, this, &ExperimentPage::abort);
  left_layout->addLayout(buttons);
  status_ = new QLabel("No session.");
  status_->setObjectName("session_status");
  status_->setWordWrap(true);
  left_layout->addWidget(status_);

  table_ = new QTableWidget(0, kColumns);
  table_->setObjectName("trial_table");
  set_table_columns(false);
  table_->verticalHeader()->setVisible(false);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionMode(QAbstractItemView::NoSelection);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(true);
  table_->verticalHeader()->setDefaultSectionSize(table_->fontMetrics().height() + 6);
  files_ = new QLabel;
  files_->setObjectName("files_written");
  files_->setWordWrap(true);
  files_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  auto* trials_page = new QWidget;
  auto* trials_layout = new QVBoxLayout(trials_page);
  trials_layout->addWidget(table_, 1);
  trials_layout->addWidget(files_);
  left_layout->addStretch(1);
  split->addWidget(left);

  // Right: the participant's screen.
  auto* right = new QWidget;
  auto* right_layout = new QVBoxLayout(right);
  right_layout->setContentsMargins(0, 0, 0, 0);
  auto* screen_box = new QGroupBox("Participant screen");
  auto* screen_layout = new QVBoxLayout(screen_box);
  screen_ = new ParticipantScreen;
  screen_layout->addWidget(screen_, 1);
  full_screen_ = button("participant_full_screen", "Participant screen on the second display");
  full_screen_->setCheckable(true);
  connect(full_screen_, &QPushButton::toggled, this, [this](bool on) {
    const auto screens = QGuiApplication::screens();
    if (on) screen_->show_full_screen_on(screens.size() > 1 ? screens.back() : nullptr);
    else screen_->back_to_console();
  });
  connect(screen_, &ParticipantScreen::backInConsole, this, [this] {
    const QSignalBlocker quiet(full_screen_);
    full_screen_->setChecked(false);
  });
  screen_layout->addWidget(full_screen_);
  right_layout->addWidget(screen_box, 1);
  statistics_area_ = new QWidget;
  statistics_area_->setObjectName("statistics_area");
  statistics_layout_ = new QVBoxLayout(statistics_area_);
  statistics_ = new StatisticsView;
  statistics_layout_->addWidget(statistics_);
  connect(statistics_, &StatisticsView::exported, this, [this](const QStringList& written) {
    files_written_ << written;
    show_files();
  });
  split->addWidget(right);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 2);
  // Below: the trial list ticking as trials commit, and the live statistics (their charts need
  // the window's width).
  results_ = new QTabWidget;
  results_->setObjectName("results_tabs");
  results_->addTab(trials_page, "Trials");
  results_->addTab(statistics_area_, "Statistics");
  rows->addWidget(results_);
  rows->setStretchFactor(0, 2);
  rows->setStretchFactor(1, 3);

  connect(&run_, &SessionRun::started, this, &ExperimentPage::on_started);
  connect(&run_, &SessionRun::trialStarted, this,
          [this](int, const PlannedTrial& trial, const Condition& condition) {
            screen_->show_trial(trial, condition);
            status_->setText(QString("Trial %1 of %2: %3").arg(trial.position + 1).arg(table_->rowCount())
                                 .arg(QString::fromStdString(condition.name)));
            if (trial.position < table_->rowCount()) table_->scrollToItem(table_->item(trial.position, 0));
          });
  connect(&run_, &SessionRun::runnerState, this, [this](RunnerState s, int position) {
    if (s == RunnerState::ready && !run_.paused()) screen_->show_ready();
    else if (s == RunnerState::ready) {
      screen_->show_wait("Paused. Please wait.");
      pause_held_ = true;  // the session loop has vented and holds: Continue may go on
      set_buttons();
    }
    else if (s == RunnerState::rest) screen_->show_wait("Break. Please rest.");
    else if (s == RunnerState::respond) screen_->stimulus_ended(position);
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
    emit sessionRefused(line, code);
  });
  connect(&run_, &SessionRun::finished, this, [this] {
    if (rig_taken_ && host_.give_back_rig) host_.give_back_rig();
    rig_taken_ = false;
    // A session that stopped or faulted is resumable: offer it at once (the list keeps its
    // ticks, read back from the store). A completed one stays on show as it ended.
    if (!last_completed_ && refusal_text().isEmpty()) {
      const QStringList files = files_written_;
      const QString status = status_->text();
      update_plan();
      files_written_ = files;
      show_files();
      status_->setText(status);
    }
    set_buttons();
  });
  set_buttons();
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
          store_edit_->text().trimmed().toStdString(), speed_->value(), telemetry_edit_->text().trimmed().toStdString()};
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
  status_->setStyleSheet("");
  status_->setProperty("refusal", QString());
  speed_->setEnabled(is_simulated_code(f.participant));
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
  // one `palprig experiment plan` prints for the next enrolment number.
  int number = 1;
  try {
    if (!f.store.empty() && std::filesystem::exists(f.store)) {
      if (statistics_->store_location() != QString::fromStdString(f.store)) statistics_->set_store(QString::fromStdString(f.store));
      const auto store = open_trial_store(f.store, TrialStore::Access::read_only);
      if (const auto who = store->find_participant(f.participant)) {
        number = who->number;
        if (const auto id = store->find_unfinished_session(*who, protocol_->name)) {
          const StoredSession stored = store->load_session(*id);
          offered_session_ = *id;
          offered_start_ = stored.completed_trials;
          show_plan(*protocol_, stored.plan);
          for (const StoredTrial& t : store->read_trials(true)) {
            if (t.session != *id || t.position >= table_->rowCount()) continue;
            table_->item(t.position, kAnswer)->setText(t.answered ? stored_flags_text(t.answer) : "no answer");
            table_->item(t.position, kScore)->setText(QString::fromStdString(t.outcome[0] + " " + t.outcome[1] + " " + t.outcome[2]).trimmed());
            table_->item(t.position, kResponseTime)->setText(t.response_time_s ? QString::number(*t.response_time_s, 'f', 2) : "");
            table_->item(t.position, kRtAfterStimulus)
                ->setText(t.rt_after_stimulus_s ? QString::number(*t.rt_after_stimulus_s, 'f', 2) : "");
            table_->item(t.position, kConfidence)->setText(t.confidence ? QString::number(*t.confidence) : "");
            table_->item(t.position, kCommitted)->setText("\u2713");
          }
          resume_note_->setText(QString("%1 has an unfinished session (%2) with this protocol: %3 of %4 trials committed. "
                                        "Resume session continues at trial %5.")
                                    .arg(participant_edit_->text()).arg(*id).arg(stored.completed_trials)
                                    .arg(stored.plan.trials.size()).arg(stored.completed_trials + 1));
          plan_note_->setText(QString("Stored order of session %1 (seed %2).").arg(*id).arg(stored.plan.seed));
          set_buttons();
          return;
        }
      } else {
        int highest = 0;
        for (const SessionOverview& s : store->list_sessions()) highest = std::max(highest, s.participant.number);
        number = highest + 1;
      }
    }
  } catch (const std::exception& e) {
    refuse(e.what());
    set_buttons();
    return;
  }
  const std::uint64_t seed = default_session_seed(f.participant, protocol_->name);
  show_plan(*protocol_, make_session_plan(*protocol_, number, seed));
  plan_note_->setText(QString("Planned order for participant number %1 (seed %2), as `palprig experiment plan` "
                              "prints it.").arg(number).arg(seed));
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
    const QStringList cells = {QString::number(t.position + 1), QString::number(t.block + 1),
                               QString::fromStdString(c.name) + (t.practice ? " (practice)" : ""), stimulus, tumor,
                               "", "", "", "", "", ""};
    for (int col = 0; col < kColumns; ++col) table_->setItem(t.position, col, new QTableWidgetItem(cells[col]));
  }
}

void ExperimentPage::tick_row(const TrialRecord& t) {
  const int row = t.planned.position;
  if (row >= table_->rowCount()) return;
  QString answer = "no answer", score;
  if (t.answered && t.mode != PresentationMode::scene) {
    answer = flags_text(t.answer);
    score = QString("%1 %2 %3").arg(to_string(t.finger_outcomes[0])).arg(to_string(t.finger_outcomes[1]))
                .arg(to_string(t.finger_outcomes[2]));
  } else if (t.answered) {
    answer = QString("%1 marks").arg(t.marks.size());
    QStringList found;
    for (const auto& s : t.localisation.tumors) found << QString("%1 %2").arg(QString::fromStdString(s.tumor)).arg(s.hit ? "found" : "missed");
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

bool ExperimentPage::begin(bool resume) {
  if (run_.running()) return false;
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
  simulated_ = is_simulated_code(f.participant);
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
    if (pulse_protocol_) screen_->start_pulse_session(*pulse_protocol_, channel_);
    else screen_->start_session(*protocol_, channel_);
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
  if (host_.take_rig) host_.take_rig();
  rig_taken_ = true;
  if (pulse_protocol_) start_pulse_run(request);
  else run_.start(request, person);
  set_buttons();
  return true;
}

void ExperimentPage::on_started(const SessionStart& s) {
  resume_note_->clear();
  offered_session_.reset();
  // The order being run, as stored (a new participant's number is known only now).
  try {
    if (protocol_) {  // a pulse session's order is the one shown (same seed, same protocol)
      const auto store = open_trial_store(fields().store, TrialStore::Access::read_only);
      const StoredSession stored = store->load_session(s.session_id);
      if (table_->rowCount() != static_cast<int>(stored.plan.trials.size()) || !s.resumed) show_plan(*protocol_, stored.plan);
    }
  } catch (const std::exception&) {
    // Reading the order back is for display only; the session goes on.
  }
  plan_note_->setText(QString("%1, participant %2 (no. %3), session %4, seed %5%6%7")
                          .arg(QString::fromStdString(s.protocol_name)).arg(QString::fromStdString(s.participant.code))
                          .arg(s.participant.number).arg(s.session_id).arg(s.seed)
                          .arg(s.simulated ? ", simulated participant (stored as simulated)" : "")
                          .arg(s.real_time_hardware ? ", hardware rig: real time" : ""));
  status_->setText(s.resumed ? QString("Resumed at trial %1 of %2.").arg(s.start_position + 1).arg(s.total_trials)
                             : QString("Session %1 started: %2 trials.").arg(s.session_id).arg(s.total_trials));
  // The runner starts in `ready` (no event says so): the participant's go-ahead is awaited.
  if (s.start_position < s.total_trials) screen_->show_ready();
  // The store exists now (created by the session): the statistics follow it.
  statistics_->set_export_directory(QString::fromStdString(
      (std::filesystem::path(fields().store).parent_path() / "exports").string()));
  statistics_->set_store(QString::fromStdString(fields().store));
  emit sessionStarted();
}

void ExperimentPage::on_ended(const SessionEnd& e) {
  last_completed_ = e.completed;
  QString text;
  if (e.completed) text = QString("Session completed: %1 trials committed.").arg(e.committed_trials);
  else if (!e.fault.empty()) text = QString("Rig fault: %1. Every channel vented; %2 of %3 trials kept; resume to go on.")
                                        .arg(QString::fromStdString(e.fault)).arg(e.committed_trials).arg(e.total_trials);
  else text = QString("Session stopped (vented): %1 of %2 trials kept; it can be resumed.").arg(e.committed_trials).arg(e.total_trials);
  status_->setStyleSheet(e.fault.empty() ? "" : "color: #b00020");
  status_->setText(text);
  screen_->show_wait(e.completed ? "Thank you, the session is complete." : "The session has stopped.");
  files_written_ = {QString::fromStdString(fields().store)};
  store_note_ = QString(" (%1 of %2 trials committed)").arg(e.committed_trials).arg(e.total_trials);
  if (const std::string telemetry = telemetry_summary(e); !telemetry.empty()) files_written_ << QString::fromStdString(telemetry);
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
  if (!run_.running()) return;
  run_.pause();
  if (channel_) channel_->withdraw_ready();
  pause_held_ = false;
  status_->setText("Paused: every channel vented; the trial in progress is presented again after Continue and the participant's Ready.");
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

void ExperimentPage::abort_and_wait(bool give_back_rig) {
  run_.abort_and_wait();
  if (give_back_rig && rig_taken_ && host_.give_back_rig) host_.give_back_rig();
  rig_taken_ = false;
  set_buttons();
}

void ExperimentPage::set_buttons() {
  const bool running = run_.running();
  const bool ready = (protocol_.has_value() || pulse_protocol_.has_value()) && !participant_edit_->text().trimmed().isEmpty() &&
                     !store_edit_->text().trimmed().isEmpty();
  begin_->setEnabled(!running && ready && !offered_session_);
  resume_session_->setVisible(offered_session_.has_value());
  resume_session_->setEnabled(!running && offered_session_.has_value());
  pause_->setEnabled(running && !run_.paused());
  continue_->setEnabled(running && run_.paused() && pause_held_);
  abort_->setEnabled(running);
  for (QWidget* w : std::initializer_list<QWidget*>{protocol_edit_, participant_edit_, store_edit_, telemetry_edit_}) w->setEnabled(!running);
  speed_->setEnabled(!running && is_simulated_code(participant_edit_->text().trimmed().toStdString()));
  full_screen_->setEnabled(QGuiApplication::screens().size() > 1 || full_screen_->isChecked());
}

}  // namespace palprig::gui

