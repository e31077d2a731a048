#pragma once
// A chart (charts/chart_png.hpp) as an SVG file: the same drawing on a QSvgGenerator, so the PNG
// and the SVG of a figure never differ, and a journal gets vector lines and text.
#include <filesystem>

#include "charts/chart_png.hpp"

namespace palprig::charts {

// Throws BadInput as write_chart_png, OutputError as write_chart_png when the file
// cannot be written whole.
void write_chart_svg(const Chart& chart, const std::filesystem::path& path);

}  // namespace palprig::charts
