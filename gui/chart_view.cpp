#include "gui/chart_view.hpp"

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
    charts::Chart sized = chart_;
    sized.width_px = width();
    sized.height_px = height();
    try {
      charts::paint_chart(p, sized);
      return;
    } catch (const BadInput&) {
      // Too narrow for the legend, say: fall through to the text.
    }
    p.fillRect(rect(), Qt::white);
  }
  p.setPen(QColor(110, 110, 110));
  p.drawText(rect(), Qt::AlignCenter, has_data() ? tr("window too small for this chart") : empty_text_);
}

}  // namespace palprig::gui
