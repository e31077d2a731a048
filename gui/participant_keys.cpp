#include "gui/participant_keys.hpp"

#include <QCoreApplication>
#include <QKeyEvent>

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
  return (key >= Qt::Key_0 && key <= Qt::Key_9) || key == Qt::Key_Return || key == Qt::Key_Enter || key == Qt::Key_Space ||
         key == Qt::Key_M || key == Qt::Key_Backspace;  // M and Backspace: mark and undo (localisation)
}

bool ParticipantKeys::eventFilter(QObject* watched, QEvent* event) {
  const QEvent::Type type = event->type();
  if (type != QEvent::KeyPress && type != QEvent::KeyRelease && type != QEvent::ShortcutOverride) {
    return QObject::eventFilter(watched, event);
  }
  auto* key = static_cast<QKeyEvent*>(event);
  if (!is_participant_key(key->key()) || (key->modifiers() & (Qt::ControlModifier | Qt::AltModifier | Qt::MetaModifier))) {
    return QObject::eventFilter(watched, event);
  }
  // The same key event reaches the filter once per widget it propagates through: only the first
  // (the focus widget, or the window when nothing has focus) is handled.
  if (type == QEvent::ShortcutOverride) {
    event->accept();  // "this key is taken": no shortcut (the live page's Space) fires for it
    return true;
  }
  if (type == QEvent::KeyPress && !key->isAutoRepeat()) screen_.participant_key(key->key());
  return true;  // consumed: no focused button clicks on Space, nothing else sees a digit
}

}  // namespace palprig::gui
