#pragma once
// "1 trial", "2 trials": a count with its noun for the window's lines (Qt's %n plurals need a
// translation file the window does not ship); and a figure, "n/a" when it has none.
#include <QString>
#include <cmath>

namespace palprig::gui {

inline QString counted(long long n, const QString& one, const QString& many) {
  return QString::number(n) + ' ' + (n == 1 ? one : many);
}

// A figure with its decimals, "n/a" where there is none (not finite), for tables and lines.
inline QString number_text(double v, int decimals = 3) {
  return std::isfinite(v) ? QString::number(v, 'f', decimals) : QStringLiteral("n/a");
}

}  // namespace palprig::gui
