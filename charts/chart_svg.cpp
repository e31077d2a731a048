#include "charts/chart_svg.hpp"

#include <QtCore/QFile>
#include <QtGui/QPainter>
#include <QtSvg/QSvgGenerator>

#include <stdexcept>

namespace palprig::charts {

void write_chart_svg(const Chart& chart, const std::filesystem::path& path) {
  ensure_chart_application();
  const QString file = QString::fromStdString(path.string());
  {
    // QSvgGenerator reports a file it cannot open only as a warning; check first.
    QFile probe(file);
    if (!probe.open(QIODevice::WriteOnly)) throw std::runtime_error("cannot write " + path.string());
  }
  QSvgGenerator svg;
  svg.setFileName(file);
  svg.setSize(QSize(chart.width_px, chart.height_px));
  svg.setViewBox(QRect(0, 0, chart.width_px, chart.height_px));
  svg.setTitle(QString::fromStdString(chart.title));
  svg.setDescription(QStringLiteral("palprig chart"));
  QPainter p;
  if (!p.begin(&svg)) throw std::runtime_error("cannot write " + path.string());
  try {
    paint_chart(p, chart);
  } catch (...) {
    p.end();
    QFile::remove(file);
    throw;
  }
  p.end();
}

}  // namespace palprig::charts
