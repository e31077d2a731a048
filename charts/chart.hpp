#pragma once
// A chart as data: what is drawn, with no Qt in sight, so any thread (a fit on a worker, a
// test) can make one. charts/chart_png.hpp and chart_svg.hpp draw it (QCustomPlot) at print
// size; the window's ChartView draws the same description at the widget's size.
//
// What every chart kind gets from this description: axes labelled with their units, ranges
// zoomed where the data are (padded so no point or whisker touches the frame), series told
// apart by colour (a colour-blind-safe palette) and by marker or dash (so a grey print still
// tells them apart), a legend under the plot (never over the data), and text annotations
// (values, n, thresholds) placed at data coordinates.
#include <optional>
#include <string>
#include <vector>

namespace palprig::charts {

enum class Marker { none, circle, square, diamond, triangle, inverted_triangle, cross, plus };
enum class Dash { solid, dashed, dotted };

struct ChartSeries {
  enum class Style { line, points, bars };
  std::string label;  // legend entry; empty: not in the legend
  Style style = Style::line;
  std::vector<double> x, y;  // non-finite points are skipped (a line breaks there)
  // Optional error bar ends (absolute values, same size as y): vertical (y_low/y_high, e.g.
  // Wilson intervals, which are not symmetric) and horizontal (x_low/x_high, e.g. a threshold's
  // bootstrap interval).
  std::vector<double> y_low, y_high, x_low, x_high;
  // Text beside each point or above each bar ("0.962", "n=42", "n/a" where y is missing), same
  // size as y, or empty.
  std::vector<std::string> point_labels;
  unsigned color_rgb = 0;               // 0xRRGGBB; 0 picks the next palette colour
  double width_px = 2.0;                // line width
  Marker marker = Marker::none;         // points: none picks the next marker shape
  double marker_px = 8;                 // marker size
  std::vector<double> marker_sizes_px;  // points: one size per point (area ~ n), or empty
  Dash dash = Dash::solid;
};

// Text at data coordinates: `align` is where the text sits from the point (right of it, left,
// above, below), `offset_px` its distance. Drawn inside the plot (clipped to it).
struct ChartText {
  enum class Align { right, left, above, below, center };
  double x = 0, y = 0;
  std::string text;
  Align align = Align::right;
  double offset_px = 6;
  unsigned color_rgb = 0x000000;
};

struct Chart {
  std::string title, x_label, y_label;  // axis labels say their unit: "pressure increment (kPa)"
  std::vector<ChartSeries> series;
  // When set, x = 0, 1, ... are these categories; the points and bars of several series sit side
  // by side (dodged) within a category.
  std::vector<std::string> x_categories;
  // x counts things (cases, sessions): ticks only at whole numbers, never at 2.5.
  bool x_whole_numbers = false;
  std::optional<double> x_min, x_max, y_min, y_max;  // default: the data's range, padded
  std::vector<ChartText> annotations;
  // Logical size in pixels: the SVG's size (at 100 px per inch: 7 x 4.4 in by default, a
  // double-column figure) and the PNG's at three times the pixels (300 dpi).
  int width_px = 700, height_px = 440;
};

// The PNG's pixels per logical pixel (300 dpi for a chart of width_px / 100 inches).
inline constexpr int kPrintScale = 3;
inline constexpr int kPrintDotsPerInch = 300;

// Throws BadInput for a chart with nothing to draw or series of mismatched sizes.
void validate_chart(const Chart& chart);

}  // namespace palprig::charts
