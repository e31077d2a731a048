#pragma once
// ParticipantScreen: what the participant sees and answers with. Discrimination: when the
// runner takes answers (answers_during_presentation: during a simultaneous stimulus unless the
// protocol fixes its length, after a sequence's last finger), which fingers felt a
// tumor: finger buttons and keys 1/2/3 toggle, "None" or 0 answers no tumor, Answer or Enter
// hands the answer over; when the protocol asks for a confidence rating, a row of rating
// buttons (keys 1..levels) follows first (gui/confidence_row.hpp) and the answer goes over with
// its rating in one piece. Space or "Ready" goes on
// at the start and after a break. No feedback on correctness (it would train the participant
// during the study; the scores are in the database and on the experimenter's console).
// Localisation: LocalisationMarking (gui/localisation_marking.hpp) is shown instead; pulse
// localisation shows it too, one trial's scene at a time with one mark (participant_screen_pulse.cpp).
// Answers go to the session thread through the ParticipantChannel (gui/gui_participant.hpp).
// The screen can leave the console and go full screen on another display (show_full_screen_on).
#include <QPointer>
#include <QWidget>
#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>

#include "study/protocol.hpp"
#include "experiments/pulse_session.hpp"
#include "study/session_plan.hpp"
#include "gui/event_clock.hpp"
#include "gui/gui_participant.hpp"

class QLabel;
class QPushButton;
class QScreen;
class QStackedWidget;

namespace palprig::gui {

class ConfidenceRow;
class LocalisationMarking;

class ParticipantScreen final : public QWidget {
  Q_OBJECT
 public:
  explicit ParticipantScreen(QWidget* parent = nullptr);

  // A new session: its protocol (finger names, task) and the channel answers go through; null
  // channel: a simulated participant answers (the screen only shows what happens).
  void start_session(const Protocol& protocol, std::shared_ptr<ParticipantChannel> channel);
  // The session's seed, once it is known (a localisation protocol that generates a case per
  // trial makes each trial's case from it).
  void set_session_seed(std::uint64_t seed) noexcept { session_seed_ = seed; }
  void show_ready();  // waiting for the participant's go-ahead
  void show_trial(const PlannedTrial& trial, const Condition& condition);
  // The runner left `present` for `respond` at this trial: discrimination answers are taken now.
  void stimulus_ended(int position);
  void show_wait(const QString& text);  // between trials, paused, done
  // After a committed trial, when the protocol asks for feedback (experiments/trial_feedback).
  void show_feedback(int position, const QString& text);
  // Pulse localisation: a session of `protocol` (conditions and their scenes), and one trial's
  // scene to palpate and mark (a generated condition's scene made from the trial's seed, as the
  // session made it). Null channel: the simulated participant palpates (the scene is shown).
  void start_pulse_session(const PulseProtocol& protocol, std::shared_ptr<ParticipantChannel> channel);
  void show_pulse_trial(const PulseTrialStart& start, const PulseCondition& condition);
  int answering_position() const noexcept { return answering_; }  // -1: no answer is taken now
  bool rating() const noexcept { return pending_.has_value(); }   // in the confidence step
  LocalisationMarking* marking() const noexcept { return marking_; }
  // A participant key (digits, Enter, Space) whatever widget had the focus (gui/participant_keys.hpp
  // routes them here during a person's session); false when the key means nothing now. `at`:
  // when the key went down (input_time of its event); none: now.
  bool participant_key(int key, std::optional<std::chrono::steady_clock::time_point> at = std::nullopt);
  // When an input event stamped `stamp_ms` (QInputEvent::timestamp()) delivered now happened, on
  // steady_clock (gui/event_clock.hpp; the clock is this session's).
  std::chrono::steady_clock::time_point input_time(std::uint64_t stamp_ms);
  EventClock::Source last_input_source() const noexcept { return last_source_; }
  // A mouse button went down on `widget` at `at` (ParticipantKeys sees every press): a click on
  // an answer button that follows is timed by its press, as a key by its going down.
  void note_press(QObject* widget, std::chrono::steady_clock::time_point at);

  // Leaves the console and fills `screen` (a second display); back_to_console() returns.
  void show_full_screen_on(QScreen* screen);
  void back_to_console();
  bool in_console() const noexcept { return console_parent_ == nullptr; }

 signals:
  void answerGiven(int position);  // handed to the session thread
  void backInConsole();            // its own window was closed: it is back in the console

 protected:
  void keyPressEvent(QKeyEvent*) override;
  // Its own window closed (by the window system or the participant): back into the console
  // rather than gone, so the experimenter still sees and can move it.
  void closeEvent(QCloseEvent*) override;

 private:
  void toggle_finger(int finger);
  void give(const FingerFlags& fingers, const QWidget* clicked);
  void hand_over(const Response& response, std::chrono::steady_clock::time_point given_at);
  void set_answering(bool on);
  bool marks_answer() const noexcept { return localisation_ || pulse_; }  // the marking screen answers
  void give_marks();
  void rate(int rating);
  // When the answer being handed over was given: the key being handled, else the press of the
  // button clicked (a press inside `clicked`), else now (a click made by program).
  std::chrono::steady_clock::time_point answer_time(const QWidget* clicked);

  std::shared_ptr<ParticipantChannel> channel_;
  std::optional<Protocol> protocol_;  // the discrimination/localisation session's (answer timing)
  std::uint64_t session_seed_ = 0;    // the running session's (generated localisation cases)
  std::array<std::string, kFingerCount> finger_names_{};
  bool localisation_ = false;
  bool pulse_ = false;
  int answering_ = -1;
  int presented_ = -1;                                  // the trial on show (answers wait for its stimulus to end)
  std::optional<Response> pending_;                     // the finger answer waiting for its rating
  std::chrono::steady_clock::time_point pending_at_{};  // when that finger answer was given
  EventClock event_clock_;
  EventClock::Source last_source_ = EventClock::Source::delivery;
  std::optional<std::chrono::steady_clock::time_point> key_at_;  // the key being handled
  QPointer<QObject> pressed_;                                    // the last mouse press: where and when
  std::chrono::steady_clock::time_point pressed_at_{};
  QLabel* prompt_ = nullptr;
  QPushButton* ready_ = nullptr;
  std::array<QPushButton*, kFingerCount> fingers_{};
  QPushButton* none_ = nullptr;
  QPushButton* answer_ = nullptr;
  QStackedWidget* pages_ = nullptr;
  QWidget* finger_page_ = nullptr;
  ConfidenceRow* confidence_ = nullptr;
  LocalisationMarking* marking_ = nullptr;
  QWidget* console_parent_ = nullptr;
};

}  // namespace palprig::gui
