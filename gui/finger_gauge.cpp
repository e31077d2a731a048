#include "gui/finger_gauge.hpp"

#include <QPainter>
#include <cmath>

#include "gui/scene_image.hpp"

namespace palprig::gui {

FingerGauge::FingerGauge(int finger, QWidget* parent) : QWidget(parent), finger_(finger) {
  // Tall enough for the bar and its three lines of figures (at 160 px the last line was clipped
  // when the live page's column was squeezed).
  setMinimumSize(90, 216);
  setObjectName(QString("finger_gauge_%1").arg(finger + 1));
}

void FingerGauge::set_values(double target_kPa, double setpoint_kPa, double monitor_kPa, double p_max_kPa, double t_s) {
  if (std::isfinite(t_s)) error_.push(t_s, monitor_kPa - target_kPa);
  target_ = target_kPa;
  setpoint_ = setpoint_kPa;
  monitor_ = monitor_kPa;
  p_max_ = p_max_kPa;
  scale_max_ = p_max_kPa * 1.1;  // p_max sits below the top so a clamped target shows above it
  update();
}

void FingerGauge::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const int text_h = 74;
  const QRectF bar(width() * 0.30, 18, width() * 0.40, height() - 18 - text_h);
  auto y_of = [&](double kPa) {
    const double f = std::isfinite(kPa) ? std::clamp(kPa / scale_max_, 0.0, 1.0) : 0.0;
    return bar.bottom() - f * bar.height();
  };
  p.drawText(QRectF(0, 0, width(), 16), Qt::AlignCenter, QString("Finger %1").arg(finger_ + 1));
  p.fillRect(bar, QColor(235, 235, 235));
  p.fillRect(QRectF(bar.left(), y_of(setpoint_), bar.width(), bar.bottom() - y_of(setpoint_)),
             pressure_colour(setpoint_, p_max_));
  p.setPen(QPen(QColor(80, 80, 80), 1));
  p.drawRect(bar);
  // p_max
  p.setPen(QPen(QColor(200, 0, 0), 2));
  p.drawLine(QPointF(bar.left() - 8, y_of(p_max_)), QPointF(bar.right() + 8, y_of(p_max_)));
  p.drawText(QRectF(bar.right() + 2, y_of(p_max_) - 14, width() - bar.right(), 14), Qt::AlignLeft, "p max");
  // target (black, left) and monitor (orange, right)
  p.setPen(QPen(Qt::black, 3));
  p.drawLine(QPointF(bar.left() - 10, y_of(target_)), QPointF(bar.left() + bar.width() * 0.5, y_of(target_)));
  if (std::isfinite(monitor_)) {
    p.setPen(QPen(QColor(230, 120, 0), 3));
    p.drawLine(QPointF(bar.left() + bar.width() * 0.5, y_of(monitor_)), QPointF(bar.right() + 10, y_of(monitor_)));
  }
  p.setPen(Qt::black);
  const QString mon = std::isfinite(monitor_) ? QString::number(monitor_, 'f', 1) : QString("--");
  const double rms = error_.rms_kPa();
  const QString err = std::isfinite(rms) ? QString::number(rms, 'f', 2) : QString("--");
  p.drawText(QRectF(0, height() - text_h, width(), text_h), Qt::AlignCenter,
             QString("target %1\nsetpoint %2\nmonitor %3 kPa\nRMS err %4 kPa")
                 .arg(target_, 0, 'f', 1)
                 .arg(setpoint_, 0, 'f', 1)
                 .arg(mon)
                 .arg(err));
}

}  // namespace palprig::gui
