// The experiment console's widgets, built once by the constructor (experiment_page.cpp holds
// what they do): the session form, the controls, the trial list and the participant's side.
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
#include <QScreen>
#include <QSignalBlocker>
#include <QTableWidget>
#include <QVBoxLayout>

#include "gui/experiment_page.hpp"
#include "gui/participant_keys.hpp"
#include "gui/participant_screen.hpp"
#include "gui/statistics_view.hpp"

namespace palprig::gui {

namespace {

QPushButton* button(const char* name, const QString& text) {
  auto* b = new QPushButton(text);
  b->setObjectName(name);
  return b;
}

// The participant's display: one apart from the console's (not overlapping it: a window system
// may also list the whole desktop as a screen), else any other, else none (one display).
QScreen* participant_display(const QWidget& console) {
  const QScreen* own = console.screen();
  const auto screens = QGuiApplication::screens();
  for (QScreen* s : screens)
    if (s != own && (own == nullptr || !s->geometry().intersects(own->geometry()))) return s;
  for (QScreen* s : screens)
    if (s != own) return s;
  return nullptr;
}

}  // namespace

QWidget* ExperimentPage::build_session_form() {
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
      const QString path = save ? QFileDialog::getSaveFileName(this, "Trial database", edit->text(), filter, nullptr,
                                                               QFileDialog::DontConfirmOverwrite)
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
  speed_->setToolTip(
      "Simulated participant on the simulated rig: 0 = as fast as possible, 1 = real time (to watch "
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
      const QString path =
          QFileDialog::getSaveFileName(this, "Session telemetry", telemetry_edit_->text(), "Telemetry (*.bin *.csv)");
      if (!path.isEmpty()) telemetry_edit_->setText(path);
    });
    row->addWidget(browse);
    form->addRow("Telemetry", row);
  }

  return form_box;
}

void ExperimentPage::build_session_controls(QVBoxLayout* left_layout) {
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
  // Not in the Tab chain: after Pause disables its own button the focus would land here, and
  // an Enter or Space meant for the participant would end the session (keys are routed to the
  // participant anyway; gui/participant_keys.hpp). A click still asks first (ask_abort).
  abort_->setFocusPolicy(Qt::ClickFocus);
  pause_->setToolTip(
      "Vents every channel and holds the trial in progress (it is presented again after Continue, once the participant "
      "says Ready)");
  abort_->setToolTip("Vents and ends the session; every committed trial is kept and the session can be resumed");
  for (QPushButton* b : {begin_, resume_session_, pause_, continue_, abort_}) buttons->addWidget(b);
  connect(begin_, &QPushButton::clicked, this, [this] { begin(false); });
  connect(resume_session_, &QPushButton::clicked, this, [this] { begin(true); });
  connect(pause_, &QPushButton::clicked, this, &ExperimentPage::pause);
  connect(continue_, &QPushButton::clicked, this, &ExperimentPage::resume);
  connect(abort_, &QPushButton::clicked, this, &ExperimentPage::ask_abort);
  left_layout->addLayout(buttons);
  status_ = new QLabel("No session.");
  status_->setObjectName("session_status");
  status_->setWordWrap(true);
  left_layout->addWidget(status_);
}

QWidget* ExperimentPage::build_trial_list() {
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
  show_key_ = button("show_answer_key", "Show the answer key (stimulus, tumor, score)");
  show_key_->setCheckable(true);
  show_key_->setFocusPolicy(Qt::ClickFocus);  // Space and Enter are the participant's
  show_key_->setToolTip(
      "The participant screen shares this window: the columns that give the answers away are hidden "
      "while a person's session runs. With two displays the participant screen goes to the second one "
      "and the columns stay.");
  show_key_->hide();
  connect(show_key_, &QPushButton::toggled, this, &ExperimentPage::apply_answer_key);
  auto* trials_page = new QWidget;
  auto* trials_layout = new QVBoxLayout(trials_page);
  trials_layout->addWidget(show_key_, 0, Qt::AlignLeft);
  trials_layout->addWidget(table_, 1);
  trials_layout->addWidget(files_);
  return trials_page;
}

QWidget* ExperimentPage::build_participant_side() {
  auto* right = new QWidget;
  auto* right_layout = new QVBoxLayout(right);
  right_layout->setContentsMargins(0, 0, 0, 0);
  auto* screen_box = new QGroupBox("Participant screen");
  auto* screen_layout = new QVBoxLayout(screen_box);
  screen_ = new ParticipantScreen;
  screen_layout->addWidget(screen_, 1);
  participant_keys_ = new ParticipantKeys(*screen_, this);
  full_screen_ = button("participant_full_screen", "Participant screen on the second display");
  full_screen_->setCheckable(true);
  connect(full_screen_, &QPushButton::toggled, this, [this](bool on) {
    if (on)
      screen_->show_full_screen_on(participant_display(*this));
    else
      screen_->back_to_console();
    apply_answer_key();
  });
  connect(screen_, &ParticipantScreen::backInConsole, this, [this] {
    const QSignalBlocker quiet(full_screen_);
    full_screen_->setChecked(false);
    apply_answer_key();
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
  return right;
}

}  // namespace palprig::gui
