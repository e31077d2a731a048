// ExperimentPage's pulse-localisation part (the rest is experiment_page.cpp): a protocol with
// "task": "pulse" is planned with pulse_trial_order (the order run_pulse_study presents), its
// unfinished session is offered for resume from the store's pulse rows, the session runs
// run_pulse_study on SessionRun's thread with the window's participant (GuiPulseParticipant),
// and each committed trial fills its row: mark x/y mm, distance to the artery mm, hit, RT.
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QTableWidget>
#include <cmath>
#include <filesystem>

#include "formats/json_file.hpp"
#include "gui/experiment_page.hpp"
#include "gui/gui_pulse_participant.hpp"
#include "gui/participant_screen.hpp"
#include "gui/statistics_view.hpp"
#include "sessions/session_preview.hpp"
#include "sessions/session_setup.hpp"
#include "store/pulse_store.hpp"

#include <QPushButton>

namespace palprig::gui {

namespace {

enum PulseColumn {
  kPulsePosition,
  kPulseCondition,
  kMarkX,
  kMarkY,
  kDistance,
  kHit,
  kPulseRt,
  kPulseCommitted,
  kPulseColumns
};

QString mm(double v) { return std::isfinite(v) ? QString::number(v, 'f', 1) : QString(); }

}  // namespace

void ExperimentPage::set_table_columns(bool pulse) {
  if (pulse) {
    table_->setColumnCount(kPulseColumns);
    table_->setHorizontalHeaderLabels({"#", "Condition", "Mark x mm", "Mark y mm", "Distance mm", "Hit", "RT s", ""});
  } else {
    // experiment_page.cpp's Column enum, in order.
    const QStringList headers = {"#",     "Block",      "Condition",           "Stimulus kPa", "Tumor", "Answer",
                                 "Score", "RT onset s", "RT after stimulus s", "Rating",       ""};
    table_->setColumnCount(static_cast<int>(headers.size()));
    table_->setHorizontalHeaderLabels(headers);
  }
  if (show_key_) apply_answer_key();
}

std::vector<int> ExperimentPage::answer_key_columns() const {
  if (table_->columnCount() == kPulseColumns) return {kDistance, kHit};
  return {kStimulus, kTumor, kScore};
}

void ExperimentPage::apply_answer_key() {
  const bool one_display = screen_->in_console();
  show_key_->setVisible(person_session_ && one_display);
  answer_key_hidden_ = person_session_ && one_display && !show_key_->isChecked();
  for (int c = 0; c < table_->columnCount(); ++c) table_->setColumnHidden(c, false);
  if (answer_key_hidden_)
    for (int c : answer_key_columns()) table_->setColumnHidden(c, true);
}

bool ExperimentPage::update_pulse_plan(const ExperimentFields& f) {
  try {
    if (!is_pulse_protocol(read_json_file(f.protocol))) return false;
  } catch (const std::exception&) {
    return false;  // load_protocol names what is wrong with the file
  }
  set_table_columns(true);
  try {
    pulse_protocol_ = load_pulse_protocol(f.protocol);
  } catch (const std::exception& e) {
    refuse(e.what());
    set_buttons();
    return true;
  }
  if (f.participant.empty()) {
    plan_note_->setText("Enter the participant code to see the planned order.");
    set_buttons();
    return true;
  }
  PulseSessionPreview preview;
  try {
    if (!f.store.empty() && std::filesystem::exists(f.store) &&
        statistics_->store_location() != QString::fromStdString(f.store)) {
      statistics_->set_store(QString::fromStdString(f.store));
    }
    preview = preview_pulse_session(f.store, *pulse_protocol_, f.participant);
  } catch (const std::exception& e) {
    refuse(e.what());
    set_buttons();
    return true;
  }
  show_pulse_order(preview.protocol, preview.order);
  if (const auto id = preview.unfinished_session) {
    offered_session_ = *id;
    offered_start_ = preview.completed_trials;
    for (const PulseTrialRecord& t : preview.committed) tick_pulse_row(t);
    resume_note_->setText(QString("%1 has an unfinished session (%2) with this protocol: %3 of %4 trials committed. "
                                  "Resume session continues at trial %5.")
                              .arg(participant_edit_->text())
                              .arg(*id)
                              .arg(preview.completed_trials)
                              .arg(preview.order.size())
                              .arg(preview.completed_trials + 1));
    plan_note_->setText(QString("Stored order of session %1 (seed %2).").arg(*id).arg(preview.seed));
  } else {
    plan_note_->setText(QString("Planned order of the pulse-localisation session (seed %1), as `palprig experiment "
                                "run` presents it.")
                            .arg(preview.seed));
  }
  set_buttons();
  return true;
}

void ExperimentPage::show_pulse_order(const PulseProtocol& protocol, const std::vector<int>& order) {
  table_->setRowCount(static_cast<int>(order.size()));
  for (int row = 0; row < static_cast<int>(order.size()); ++row) {
    const PulseCondition& c = protocol.conditions.at(static_cast<std::size_t>(order[static_cast<std::size_t>(row)]));
    const QStringList cells = {QString::number(row + 1), QString::fromStdString(c.name), "", "", "", "", "", ""};
    for (int col = 0; col < kPulseColumns; ++col) table_->setItem(row, col, new QTableWidgetItem(cells[col]));
  }
}

void ExperimentPage::tick_pulse_row(const PulseTrialRecord& t) {
  const int row = t.position;
  if (row >= table_->rowCount()) return;
  table_->item(row, kMarkX)->setText(t.answered ? mm(t.mark_x_mm) : "no mark");
  table_->item(row, kMarkY)->setText(t.answered ? mm(t.mark_y_mm) : "");
  table_->item(row, kDistance)->setText(t.answered ? mm(t.distance_mm) : "");
  table_->item(row, kHit)->setText(t.hit ? "hit" : "miss");
  table_->item(row, kPulseRt)->setText(t.answered ? QString::number(t.response_time_s, 'f', 2) : "");
  table_->item(row, kPulseCommitted)->setText("\u2713");
  table_->scrollToItem(table_->item(row, 0));
}

void ExperimentPage::start_pulse_run(const StudySessionRequest& request) {
  PulsePersonFactory person;
  if (channel_) {
    person = [channel = channel_](const PulseProtocol&) { return std::make_unique<GuiPulseParticipant>(channel); };
  }
  run_.start_pulse(request, person);
}

void ExperimentPage::connect_pulse() {
  connect(&run_, &SessionRun::pulseTrialStarted, this,
          [this](const PulseTrialStart& start, const PulseCondition& condition) {
            try {
              screen_->show_pulse_trial(start, condition);
            } catch (const std::exception& e) {  // the scene was loaded by the session: should not happen
              status_->setText(QString("Cannot show the scene: %1").arg(e.what()));
              return;
            }
            status_->setText(QString("Trial %1 of %2: %3")
                                 .arg(start.position + 1)
                                 .arg(table_->rowCount())
                                 .arg(QString::fromStdString(condition.name)));
            if (start.position < table_->rowCount()) table_->scrollToItem(table_->item(start.position, 0));
          });
  connect(&run_, &SessionRun::pulseTrialCommitted, this, [this](const PulseTrialRecord& t, int) {
    tick_pulse_row(t);
    statistics_->refresh();  // coalesced with the view's own refresh on the file change
    emit trialCommitted(t.position);
  });
}

}  // namespace palprig::gui
