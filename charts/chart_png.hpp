#pragma once
// Charts as PNG files, for the command line's --plot options and anything else that needs a
// figure on disk: line, point and bar series on numeric axes (or named categories), optional
// error bars with separate low and high ends (Wilson intervals are not symmetric), a title,
// axis labels and a legend (right of the plot area, never over the data). Drawn with QPainter on a QImage; when no Qt
// application exists yet, an offscreen QGuiApplication is created for the fonts (no display needed).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

class QPainter;
class QImage;

namespace palprig::charts {

struct ChartSeries {
  enum class Style { line, points, bars };
  std::string label;  // legend entry; empty: not in the legend
  Style style = Style::line;
  std::vector<double> x, y;             // non-finite points are skipped (a line breaks there)
  std::vector<double> y_low, y_high;    // optional error bar ends (absolute values), same size as y
  std::vector<std::string> bar_labels;  // bars: optional text above each bar ("n=42", "n/a"), same size as y
  unsigned color_rgb = 0;               // 0xRRGGBB; 0 picks the next palette colour
  double width_px = 2.0;                // line width, point diameter / 3
};

struct Chart {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  // When set, x = 0, 1, ... are these categories (bar charts); bars of several series sit side
  // by side within a category.
  std::vector<std::string> x_categories;
  std::optional<double> x_min, x_max, y_min, y_max;  // default: the data's range, padded
  int width_px = 1000, height_px = 650;
};

// Throws BadInput for a chart with nothing to draw or series of mismatched sizes,
// OutputError (io/checked_output.hpp: the file and the system's reason; no file is left)
// when the file cannot be written whole.
void write_chart_png(const Chart& chart, const std::filesystem::path& path);

// The same drawing on any paint device (a widget, an SVG generator) of chart.width_px x
// chart.height_px. Throws BadInput as write_chart_png, before painting anything.
void paint_chart(QPainter& painter, const Chart& chart);
QImage render_chart(const Chart& chart);
// Makes the offscreen application the fonts need when none exists (see write_chart_png).
void ensure_chart_application();

}  // namespace palprig::charts
