#pragma once
// ParticipantKeys: while a person's session runs, the participant's keys (digits, Enter, Space;
// M and Backspace when marking)
// reach the participant screen whatever widget has the keyboard focus: an application-wide
// event filter takes them before any widget or shortcut does. So a click on the Live rig tab,
// a button the experimenter pressed, or the Abort button that got the focus after Pause never
// swallows an answer (the response time would then include the dead time) and Space (the
// participant's Ready) never presses an experimenter's control or the live page's pause.
// Esc and every other key go on as before (Esc vents from anywhere).
#include <QObject>

namespace palprig::gui {

class ParticipantScreen;

class ParticipantKeys final : public QObject {
  Q_OBJECT
 public:
  explicit ParticipantKeys(ParticipantScreen& screen, QObject* parent = nullptr);
  ~ParticipantKeys() override;
  // Installs the filter on the application (idempotent); remove() takes it off.
  void install();
  void remove();
  bool installed() const noexcept { return installed_; }
  static bool is_participant_key(int key) noexcept;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  ParticipantScreen& screen_;
  bool installed_ = false;
};

}  // namespace palprig::gui
