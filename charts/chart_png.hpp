#pragma once
// Charts (charts/chart.hpp) drawn by QCustomPlot (Debian's libqcustomplot2.1-qt6, the plotting
// widget many lab programs use for live plots): as PNG files at print size (kPrintScale times
// the chart's logical pixels, 300 dpi in the file), as images for the window, and on any paint
// device (an SVG generator: chart_svg.hpp). One drawing for every chart kind of palprig, so the
// command line's --plot, the window's chart views and its export buttons show the same picture.
//
// QCustomPlot is a QWidget: drawing needs a QApplication (one with the offscreen platform is
// made when none exists, so the command line needs no display) and must happen on the
// application's thread. A call from another thread is refused (std::logic_error): a worker
// makes the Chart (plain data) and hands it to the GUI thread to draw.
#include <filesystem>

#include "charts/chart.hpp"

class QImage;
class QPaintDevice;

namespace palprig::charts {

// Throws BadInput as validate_chart, OutputError (io/checked_output.hpp: the
// file and the system's reason; no file is left) when the file cannot be written whole.
void write_chart_png(const Chart& chart, const std::filesystem::path& path);

// The chart at chart.width_px x chart.height_px logical pixels, `scale` image pixels each.
QImage render_chart(const Chart& chart, double scale = 1.0);

// Draws the chart on `device` (chart.width_px x chart.height_px).
void paint_chart(QPaintDevice& device, const Chart& chart);

// Makes the offscreen application QCustomPlot needs when none exists (see above).
void ensure_chart_application();

}  // namespace palprig::charts
