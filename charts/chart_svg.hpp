#pragma once
// A chart (charts/chart.hpp) as an SVG file: the same QCustomPlot drawing as the PNG on a
// QSvgGenerator, so the PNG and the SVG of a figure never differ, and a journal gets vector
// lines and text, at print size (100 logical pixels an inch).
#include <filesystem>

#include "charts/chart_png.hpp"

namespace palprig::charts {

// Throws BadInput as write_chart_png, OutputError as write_chart_png when the file
// cannot be written whole.
void write_chart_svg(const Chart& chart, const std::filesystem::path& path);

}  // namespace palprig::charts
