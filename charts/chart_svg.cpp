#include "charts/chart_svg.hpp"

#include <QtCore/QBuffer>
#include <QtCore/QByteArray>
#include <QtSvg/QSvgGenerator>

#include "io/checked_output.hpp"

namespace palprig::charts {

void write_chart_svg(const Chart& chart, const std::filesystem::path& path) {
  validate_chart(chart);
  ensure_chart_application();
  // Drawn into memory, then written through the checked writer: QSvgGenerator reports a file it
  // cannot open or write only as a warning.
  QByteArray svg_bytes;
  QBuffer buffer(&svg_bytes);
  buffer.open(QIODevice::WriteOnly);
  {
    QSvgGenerator svg;
    svg.setOutputDevice(&buffer);
    svg.setSize(QSize(chart.width_px, chart.height_px));
    svg.setViewBox(QRect(0, 0, chart.width_px, chart.height_px));
    // 100 logical pixels an inch: the default 700 x 440 chart is 7 x 4.4 in, a double-column
    // figure, with its text at 8-10 pt.
    svg.setResolution(100);
    svg.setTitle(QString::fromStdString(chart.title));
    svg.setDescription(QStringLiteral("palprig chart"));
    paint_chart(svg, chart);
  }
  write_file_checked(path, std::string_view(svg_bytes.constData(), static_cast<std::size_t>(svg_bytes.size())));
}

}  // namespace palprig::charts
