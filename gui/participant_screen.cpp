#include "gui/participant_screen.hpp"

#include <QCloseEvent>

#include <QGuiApplication>
#include <QBoxLayout>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QScreen>
#include <QStackedWidget>
#include <QVBoxLayout>

#include "gui/confidence_row.hpp"
#include "gui/localisation_marking.hpp"
#include "study/localisation_case.hpp"

namespace palprig::gui {

ParticipantScreen::ParticipantScreen(QWidget* parent) : QWidget(parent) {
  setObjectName("participant_screen");
  setFocusPolicy(Qt::StrongFocus);
  auto* layout = new QVBoxLayout(this);
  prompt_ = new QLabel("No session");
  prompt_->setObjectName("participant_prompt");
  prompt_->setAlignment(Qt::AlignCenter);
  prompt_->setWordWrap(true);
  QFont big = prompt_->font();
  big.setPointSizeF(big.pointSizeF() * 1.5);
  prompt_->setFont(big);
  // Room for three lines whatever the layout gives: a clipped question is worse than none.
  prompt_->setMinimumHeight(QFontMetrics(big).lineSpacing() * 3 + 8);
  layout->addWidget(prompt_);

  ready_ = new QPushButton("Ready (Space)");
  ready_->setObjectName("ready_button");
  ready_->setFont(big);
  connect(ready_, &QPushButton::clicked, this, [this] {
    if (!channel_) return;
    channel_->say_ready();
    ready_->setEnabled(false);
  });
  layout->addWidget(ready_);

  pages_ = new QStackedWidget;
  finger_page_ = new QWidget;
  auto* fingers = new QHBoxLayout(finger_page_);
  for (int f = 0; f < kFingerCount; ++f) {
    auto* b = new QPushButton;
    b->setObjectName(QString("finger_%1").arg(f + 1));
    b->setCheckable(true);
    b->setFont(big);
    b->setMinimumHeight(70);
    b->setFocusPolicy(Qt::NoFocus);  // keys go to the screen, not to one button
    fingers->addWidget(b);
    fingers_[static_cast<std::size_t>(f)] = b;
  }
  none_ = new QPushButton("None (0)");
  none_->setObjectName("none_button");
  none_->setFont(big);
  none_->setMinimumHeight(70);
  none_->setFocusPolicy(Qt::NoFocus);
  connect(none_, &QPushButton::clicked, this, [this] { give({}, none_); });
  fingers->addWidget(none_);
  answer_ = new QPushButton("Answer (Enter)");
  answer_->setObjectName("answer_button");
  answer_->setFont(big);
  answer_->setMinimumHeight(70);
  answer_->setFocusPolicy(Qt::NoFocus);
  connect(answer_, &QPushButton::clicked, this, [this] {
    FingerFlags chosen{};
    bool any = false;
    for (std::size_t f = 0; f < kFingerCount; ++f) any |= chosen[f] = fingers_[f]->isChecked();
    if (any) give(chosen, answer_);  // no finger chosen: "None" says so explicitly
  });
  fingers->addWidget(answer_);
  pages_->addWidget(finger_page_);
  confidence_ = new ConfidenceRow;
  connect(confidence_, &ConfidenceRow::rated, this, &ParticipantScreen::rate);
  pages_->addWidget(confidence_);

  marking_ = new LocalisationMarking;
  connect(marking_, &LocalisationMarking::done, this, &ParticipantScreen::give_marks);
  pages_->addWidget(marking_);
  layout->addWidget(pages_, 1);
  set_answering(false);
  ready_->setVisible(false);
}

void ParticipantScreen::start_session(const Protocol& protocol, std::shared_ptr<ParticipantChannel> channel) {
  marking_->detach_pen();  // before the last session's channel (and its pen) may go
  event_clock_.reset();    // a foreign clock's offset is estimated afresh for each session
  pressed_ = nullptr;
  channel_ = std::move(channel);
  finger_names_ = protocol.finger_names;
  localisation_ = protocol.task == TaskKind::localisation;
  protocol_ = protocol;
  pulse_ = false;
  confidence_->set_scale(protocol.confidence);
  pending_.reset();
  for (int f = 0; f < kFingerCount; ++f) {
    fingers_[static_cast<std::size_t>(f)]->setText(
        QString("%1  %2").arg(f + 1).arg(QString::fromStdString(finger_names_[static_cast<std::size_t>(f)])));
  }
  pages_->setCurrentWidget(localisation_ ? static_cast<QWidget*>(marking_) : finger_page_);
  pages_->setVisible(channel_ != nullptr || localisation_);  // a pilot run has nobody to answer
  if (localisation_) marking_->start_session(protocol, channel_ ? &channel_->pen() : nullptr);
  set_answering(false);
  show_wait(channel_ ? "Please wait" : "Simulated participant (pilot run)");
}

void ParticipantScreen::show_ready() {
  set_answering(false);
  if (!channel_) return;
  prompt_->setText("Ready? Press Space or the Ready button to start.");
  ready_->setVisible(true);
  ready_->setEnabled(true);
  setFocus();
}

void ParticipantScreen::show_trial(const PlannedTrial& trial, const Condition& condition) {
  ready_->setVisible(false);
  // Each trial palpates its own case: the participant's screen shows it (plain tissue).
  if (localisation_ && protocol_) marking_->show_case(trial_case(*protocol_, trial, session_seed_));
  if (!channel_) {
    prompt_->setText(QString("Simulated participant (pilot run): trial %1").arg(trial.position + 1));
    return;
  }
  QString text = QString("Trial %1%2. ").arg(trial.position + 1).arg(trial.practice ? " (practice)" : "");
  if (localisation_) {
    text += "Palpate the tissue with the pen. Right-click (or press M) where you feel a tumor; Done when finished.";
    marking_->clear_marks();
  } else {
    if (condition.mode == PresentationMode::sequential)
      text += "The fingers are presented one after another; you answer when the last one has ended.";
    else if (protocol_ && answers_during_presentation(*protocol_, condition.mode))
      text += "All fingers at once. Which fingers feel a tumor? 1/2/3 choose, Enter answers; 0 for none.";
    else
      text += "All fingers at once. Feel the stimulus; you answer when it has ended.";
    for (QPushButton* b : fingers_) b->setChecked(false);
    pending_.reset();
    pages_->setCurrentWidget(finger_page_);
  }
  prompt_->setText(text);
  presented_ = trial.position;
  // Marks are made while palpating; a stimulus that stays until the answer is answered while it
  // is on; a sequence after its last finger (stimulus_ended). The runner's rule, not a copy.
  if (localisation_ || (protocol_ && answers_during_presentation(*protocol_, condition.mode))) {
    answering_ = trial.position;
    set_answering(true);
  } else {
    set_answering(false);
  }
  setFocus();
}

void ParticipantScreen::stimulus_ended(int position) {
  if (!channel_ || marks_answer() || position != presented_ || answering_ == position) return;
  prompt_->setText(
      QString("Trial %1. Which fingers feel a tumor? 1/2/3 choose, Enter answers; 0 for none.").arg(position + 1));
  answering_ = position;
  set_answering(true);
  setFocus();
}

void ParticipantScreen::show_feedback(int position, const QString& text) {
  if (!channel_ || presented_ != position) return;  // a later trial is already on show
  prompt_->setText(text);
}

void ParticipantScreen::show_wait(const QString& text) {
  set_answering(false);
  for (QPushButton* b : fingers_) b->setChecked(false);  // no earlier choice left on show (a pause, the end)
  presented_ = -1;
  ready_->setVisible(false);
  prompt_->setText(text);
}

void ParticipantScreen::set_answering(bool on) {
  if (!on) {
    answering_ = -1;
    if (pending_ && channel_) channel_->say_rating(-1);
    pending_.reset();
    if (!marks_answer()) pages_->setCurrentWidget(finger_page_);
  }
  confidence_->setEnabled(on);
  for (QPushButton* b : fingers_) b->setEnabled(on);
  none_->setEnabled(on);
  answer_->setEnabled(on);
  marking_->setEnabled(on);
}

void ParticipantScreen::toggle_finger(int finger) {
  if (answering_ < 0 || marks_answer() || pending_) return;
  QPushButton* b = fingers_[static_cast<std::size_t>(finger)];
  b->setChecked(!b->isChecked());
}

void ParticipantScreen::give_marks() {
  if (!channel_ || answering_ < 0) return;
  const auto given_at = answer_time(marking_);
  Response r;
  r.marks = marking_->marks();
  if (pulse_ && r.marks.size() != 1) {
    prompt_->setText("Mark the point where the pulse is strongest first (right-click or M).");
    return;
  }
  if (!channel_->give_answer(answering_, r, given_at)) {
    prompt_->setText(QString("At most %1 marks, please undo some.").arg(kMaxMarks));
    return;
  }
  const int given = answering_;
  set_answering(false);
  if (pulse_) prompt_->setText("Mark recorded.");  // the same words for every mark: no feedback on correctness
  emit answerGiven(given);
}

void ParticipantScreen::give(const FingerFlags& fingers, const QWidget* clicked) {
  if (!channel_ || answering_ < 0 || pending_) return;
  const auto given_at = answer_time(clicked);
  Response r;
  r.tumor_under = fingers;
  if (confidence_->levels() > 0) {
    // The rating step: the answer waits here and goes over with its rating, timed by the finger
    // answer's input; the session holds the response timeout meanwhile.
    pending_ = r;
    pending_at_ = given_at;
    channel_->say_rating(answering_);
    pages_->setCurrentWidget(confidence_);
    prompt_->setText(
        QString("How confident are you? %1 (keys 1-%2).").arg(confidence_->legend()).arg(confidence_->levels()));
    return;
  }
  hand_over(r, given_at);
}

void ParticipantScreen::rate(int rating) {
  if (!pending_ || answering_ < 0 || rating < 1 || rating > confidence_->levels()) return;
  Response r = *pending_;
  r.confidence = rating;
  hand_over(r, pending_at_);  // the response time ends with the finger answer, not the rating
}

std::chrono::steady_clock::time_point ParticipantScreen::input_time(std::uint64_t stamp_ms) {
  const EventClock::Mapped m = event_clock_.map(stamp_ms, std::chrono::steady_clock::now());
  last_source_ = m.source;
  return m.at;
}

void ParticipantScreen::note_press(QObject* widget, std::chrono::steady_clock::time_point at) {
  pressed_ = widget;
  pressed_at_ = at;
}

std::chrono::steady_clock::time_point ParticipantScreen::answer_time(const QWidget* clicked) {
  if (key_at_) return *key_at_;
  const QObject* pressed = pressed_.data();
  pressed_.clear();  // one press times one click
  for (const QObject* o = pressed; o && clicked; o = o->parent()) {
    if (o == clicked) return pressed_at_;
  }
  return std::chrono::steady_clock::now();
}

void ParticipantScreen::hand_over(const Response& r, std::chrono::steady_clock::time_point given_at) {
  channel_->give_answer(answering_, r, given_at);
  channel_->say_rating(-1);
  const int given = answering_;
  set_answering(false);
  prompt_->setText("Answer recorded.");  // the same words for every answer: no feedback on correctness
  emit answerGiven(given);
}

void ParticipantScreen::keyPressEvent(QKeyEvent* e) {
  if (!participant_key(e->key(), input_time(e->timestamp()))) QWidget::keyPressEvent(e);
}

bool ParticipantScreen::participant_key(int key, std::optional<std::chrono::steady_clock::time_point> at) {
  // The key's time for whatever answer it hands over (Enter clicks Answer by program).
  key_at_ = at ? at : std::chrono::steady_clock::now();
  struct Clear {
    std::optional<std::chrono::steady_clock::time_point>& at;
    ~Clear() { at.reset(); }
  } clear{key_at_};
  if (pending_) {  // the rating step: digits 1..levels rate, nothing else answers
    const int digit = key - Qt::Key_0;
    if (digit >= 1 && digit <= confidence_->levels()) {
      rate(digit);
      return true;
    }
    return false;
  }
  switch (key) {
    case Qt::Key_1: toggle_finger(0); return true;
    case Qt::Key_2: toggle_finger(1); return true;
    case Qt::Key_3: toggle_finger(2); return true;
    case Qt::Key_0:
      if (!marks_answer()) give({}, nullptr);
      return true;
    case Qt::Key_Return:
    case Qt::Key_Enter:
      if (marks_answer())
        marking_->finish();
      else
        answer_->click();
      return true;
    case Qt::Key_Space:
      if (ready_->isVisible() && ready_->isEnabled()) ready_->click();
      return true;
    case Qt::Key_Backspace:
      if (!marks_answer()) return false;
      marking_->undo();
      return true;
    case Qt::Key_M:
      if (!marks_answer()) return false;
      marking_->mark_at_cursor();
      return true;
    default: return false;
  }
}

void ParticipantScreen::show_full_screen_on(QScreen* screen) {
  if (!console_parent_) console_parent_ = parentWidget();
  setParent(nullptr);
  setWindowTitle("palprig - participant");
  if (screen) {
    setScreen(screen);
    // The whole display even where no window manager honours the full-screen request (a bare X
    // server on a lab PC): the window system's full-screen state alone would leave it small.
    setGeometry(screen->geometry());
  }
  showFullScreen();
}

void ParticipantScreen::closeEvent(QCloseEvent* e) {
  if (in_console()) {
    QWidget::closeEvent(e);
    return;
  }
  e->ignore();
  back_to_console();
  emit backInConsole();
}

void ParticipantScreen::back_to_console() {
  if (!console_parent_) return;
  showNormal();
  setParent(console_parent_);
  if (auto* box = qobject_cast<QBoxLayout*>(console_parent_->layout())) box->insertWidget(0, this, 1);
  show();
  console_parent_ = nullptr;
}

}  // namespace palprig::gui
