#include "gui/chart_view.hpp"

#include <QImage>
#include <QPainter>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"

namespace palprig::gui {

ChartView::ChartView(QWidget* parent) : QWidget(parent) {
  setMinimumSize(420, 260);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void ChartView::set_chart(charts::Chart chart, const QString& empty_text) {
  chart_ = std::move(chart);
  empty_text_ = empty_text;
  update();
}

bool ChartView::has_data() const {
  for (const auto& s : chart_.series)
    for (double y : s.y)
      if (std::isfinite(y)) return true;
  return false;
}

void ChartView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), Qt::white);
  if (has_data()) {
    // The export's drawing (QCustomPlot) at the widget's size and pixel ratio.
    charts::Chart sized = chart_;
    sized.width_px = width();
    sized.height_px = height();
    try {
      const QImage image = charts::render_chart(sized, devicePixelRatioF());
      p.drawImage(rect(), image);
      return;
    } catch (const BadInput&) {
      // Too small to draw: fall through to the text.
    }
  }
  p.setPen(QColor(110, 110, 110));
  p.drawText(rect(), Qt::AlignCenter, has_data() ? tr("window too small for this chart") : empty_text_);
}

}  // namespace palprig::gui
