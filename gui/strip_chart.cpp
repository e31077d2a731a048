#include "gui/strip_chart.hpp"

#include <QPaintEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>

namespace palprig::gui {

namespace {
const QColor kTraceColour[kTraceKinds] = {QColor(20, 20, 20), QColor(40, 90, 220), QColor(235, 120, 0)};
const char* kTraceName[kTraceKinds] = {"target", "setpoint", "monitor"};
}  // namespace

StripChart::StripChart(const TraceHistory* history, QWidget* parent) : QWidget(parent), history_(history) {
  setMinimumSize(320, 180);
  setObjectName("strip_chart");
  setAttribute(Qt::WA_OpaquePaintEvent);
}

void StripChart::set_window_s(double s) {
  window_s_ = std::clamp(s, 2.0, 60.0);
  update();
}

void StripChart::set_paused(bool paused) {
  if (paused && !paused_ && history_->size()) paused_end_s_ = history_->newest().t_s;
  paused_ = paused;
  update();
}

void StripChart::paintEvent(QPaintEvent*) {
  QPainter p(this);
  render_to(p, rect());
}

namespace {

// The next of 5, 10, 20, 50, 100 ... kPa at or above v: lanes scale to what is being sent, so a
// 1 kPa soft-tissue trace is not a flat line under a 60 kPa p_max.
double nice_top(double v) {
  double top = 5;
  while (top < v) top = (std::lround(top / std::pow(10.0, std::floor(std::log10(top)))) == 2) ? top * 2.5 : top * 2;
  return top;
}

}  // namespace

void StripChart::render_to(QPainter& p, const QRect& area) {
  p.fillRect(area, Qt::white);
  const int left = area.left() + 44, right = area.right() - 8;
  const int columns = std::max(1, right - left);
  const double t1 = paused_ ? paused_end_s_ : (history_->size() ? history_->newest().t_s : 0.0);
  const double t0 = t1 - window_s_;
  // One pass per trace over the window (at most 60,000 samples), kept for the drawing below.
  double seen_max = 0;
  for (int f = 0; f < kFingerCount; ++f)
    for (int k = 0; k < kTraceKinds; ++k) {
      auto& cols = columns_[f][k];
      history_->columns_min_max(TraceKind(k), f, t0, t1, columns, cols);
      for (const ColumnExtent& e : cols)
        if (!e.empty) seen_max = std::max(seen_max, double(e.max));
    }
  const double top_kPa = std::min(nice_top(seen_max * 1.1), nice_top(p_max_kPa_ * 1.1));
  const int lane_gap = 6, legend_h = 16;
  const double lane_h = double(area.height() - legend_h - 2 * lane_gap) / kFingerCount;
  QFont small = p.font();
  small.setPointSizeF(std::max(6.0, small.pointSizeF() * 0.8));
  p.setFont(small);
  for (int f = 0; f < kFingerCount; ++f) {
    const double lane_top = area.top() + legend_h + f * (lane_h + lane_gap);
    const double lane_bottom = lane_top + lane_h;
    auto y_of = [&](float kPa) { return lane_bottom - std::clamp(double(kPa) / top_kPa, 0.0, 1.0) * lane_h; };
    p.setPen(QColor(200, 200, 200));
    p.drawRect(QRectF(left, lane_top, columns, lane_h));
    if (p_max_kPa_ <= top_kPa) {
      p.setPen(QPen(QColor(210, 0, 0), 1, Qt::DashLine));
      p.drawLine(QPointF(left, y_of(float(p_max_kPa_))), QPointF(left + columns, y_of(float(p_max_kPa_))));
      p.drawText(QPointF(left + 4, y_of(float(p_max_kPa_)) + 12), "p max");
    }
    p.setPen(Qt::black);
    p.drawText(QRectF(left + 4, lane_top + 2, 60, 14), Qt::AlignLeft, QString("finger %1").arg(f + 1));
    p.drawText(QRectF(area.left(), lane_top, 40, 14), Qt::AlignRight, QString::number(top_kPa, 'f', 0));
    p.drawText(QRectF(area.left(), lane_bottom - 14, 40, 14), Qt::AlignRight, "0");
    for (int k = 0; k < kTraceKinds; ++k) {
      const auto& cols = columns_[f][k];
      lines_.clear();
      bool have_prev = false;
      float prev_min = 0, prev_max = 0;
      for (int c = 0; c < columns; ++c) {
        const ColumnExtent& e = cols[std::size_t(c)];
        if (e.empty) {
          have_prev = false;
          continue;
        }
        const double x = left + c + 0.5;
        lines_.emplace_back(x, y_of(e.min), x, y_of(e.max) - 0.01);  // the column's span (at least a dot)
        if (have_prev) {  // join to the previous column so a slow trace is a line, not dots
          if (e.max < prev_min)
            lines_.emplace_back(x - 1, y_of(prev_min), x, y_of(e.max));
          else if (e.min > prev_max)
            lines_.emplace_back(x - 1, y_of(prev_max), x, y_of(e.min));
        }
        have_prev = true;
        prev_min = e.min;
        prev_max = e.max;
      }
      p.setPen(QPen(kTraceColour[k], k == 0 ? 1.0 : 1.4));
      p.drawLines(lines_.data(), int(lines_.size()));
    }
  }
  // Legend and time axis.
  int x = left;
  for (int k = 0; k < kTraceKinds; ++k) {
    p.setPen(QPen(kTraceColour[k], 3));
    p.drawLine(x, area.top() + 8, x + 16, area.top() + 8);
    p.setPen(Qt::black);
    p.drawText(x + 20, area.top() + 12, kTraceName[k]);
    x += 90;
  }
  p.drawText(QRect(x, area.top(), right - x, legend_h), Qt::AlignRight | Qt::AlignVCenter,
             QString("kPa, last %1 s%2").arg(window_s_, 0, 'f', 0).arg(paused_ ? " (paused)" : ""));
}

}  // namespace palprig::gui
