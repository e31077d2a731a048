#pragma once
// "1 trial", "2 trials": a count with its noun for the window's lines (Qt's %n plurals need a
// translation file the window does not ship).
#include <QString>

namespace palprig::gui {

inline QString counted(long long n, const QString& one, const QString& many) {
  return QString::number(n) + ' ' + (n == 1 ? one : many);
}

}  // namespace palprig::gui
