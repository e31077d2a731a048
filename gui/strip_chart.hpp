#pragma once
// StripChart: per finger target, setpoint and monitor pressure against time, one lane per
// finger, at display rate from the 1 kHz stream.
//
// Why not QtCharts: drawing 9 traces of 10,000 points as QLineSeries took 59-71 ms per frame
// on the development machine (a 60 Hz frame has 16.7 ms). A chart a few hundred pixels wide can
// show at most one value range per pixel column anyway, so this one reduces each trace to the
// minimum and maximum in each column (TraceHistory::columns_min_max, one pass over the window)
// and draws one vertical span per column plus the joins: the cost follows the width in pixels,
// not the number of samples, and no peak is lost (a 1 ms spike still colours its column).
// Measured in bench/bench_gui_frames.cpp (docs/benchmarks.md, "The window's frame times").
#include <QWidget>
#include <array>
#include <vector>

#include "gui/trace_history.hpp"

namespace palprig::gui {

class StripChart final : public QWidget {
  Q_OBJECT
 public:
  explicit StripChart(const TraceHistory* history, QWidget* parent = nullptr);
  void set_window_s(double s);
  double window_s() const noexcept { return window_s_; }
  void set_paused(bool paused);
  bool paused() const noexcept { return paused_; }
  void set_p_max_kPa(double p) { p_max_kPa_ = p; }
  // Draw into any painter (the widget, a benchmark's QImage).
  void render_to(QPainter& p, const QRect& area);
  QSize sizeHint() const override { return {640, 300}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  const TraceHistory* history_;
  double window_s_ = 10.0;
  bool paused_ = false;
  double paused_end_s_ = 0;
  double p_max_kPa_ = 60.0;
  // Per finger, per trace kind: reused between frames.
  std::array<std::array<std::vector<ColumnExtent>, kTraceKinds>, kFingerCount> columns_;
  std::vector<QLineF> lines_;
};

}  // namespace palprig::gui
