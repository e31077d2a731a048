#include "gui/participant_keys.hpp"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QWidget>

#include "gui/participant_screen.hpp"

namespace palprig::gui {

ParticipantKeys::ParticipantKeys(ParticipantScreen& screen, QObject* parent) : QObject(parent), screen_(screen) {}

ParticipantKeys::~ParticipantKeys() { remove(); }

void ParticipantKeys::install() {
  if (installed_) return;
  QCoreApplication::instance()->installEventFilter(this);
  installed_ = true;
}

void ParticipantKeys::remove() {
  if (!installed_) return;
  QCoreApplication::instance()->removeEventFilter(this);
  installed_ = false;
}

bool ParticipantKeys::is_participant_key(int key) noexcept {
  return (key >= Qt::Key_0 && key <= Qt::Key_9) || key == Qt::Key_Return || key == Qt::Key_Enter ||
         key == Qt::Key_Space || key == Qt::Key_M ||
         key == Qt::Key_Backspace;  // M and Backspace: mark and undo (localisation)
}

bool ParticipantKeys::eventFilter(QObject* watched, QEvent* event) {
  const QEvent::Type type = event->type();
  if (type == QEvent::MouseButtonPress) {
    // A press on the participant screen (a button, the marking scene): noted with its own time,
    // so the click it becomes is timed by the press, whatever delayed the release or the click.
    auto* widget = qobject_cast<QWidget*>(watched);
    if (widget && (widget == &screen_ || screen_.isAncestorOf(widget))) {
      screen_.note_press(widget, screen_.input_time(static_cast<QMouseEvent*>(event)->timestamp()));
    }
    return QObject::eventFilter(watched, event);
  }
  if (type != QEvent::KeyPress && type != QEvent::KeyRelease && type != QEvent::ShortcutOverride) {
    return QObject::eventFilter(watched, event);
  }
  auto* key = static_cast<QKeyEvent*>(event);
  if (!is_participant_key(key->key()) ||
      (key->modifiers() & (Qt::ControlModifier | Qt::AltModifier | Qt::MetaModifier))) {
    return QObject::eventFilter(watched, event);
  }
  // The same key event reaches the filter once per widget it propagates through: only the first
  // (the focus widget, or the window when nothing has focus) is handled.
  if (type == QEvent::ShortcutOverride) {
    event->accept();  // "this key is taken": no shortcut (the live page's Space) fires for it
    return true;
  }
  // Timed by the event's own stamp (when the key went down), not by when this ran.
  if (type == QEvent::KeyPress && !key->isAutoRepeat())
    screen_.participant_key(key->key(), screen_.input_time(key->timestamp()));
  return true;  // consumed: no focused button clicks on Space, nothing else sees a digit
}

}  // namespace palprig::gui
