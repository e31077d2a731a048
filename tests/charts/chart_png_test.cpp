// The charts every --plot and the window draw (QCustomPlot): print size (PNG at 3x the logical
// pixels, 300 dpi; SVG in vector form with its text), nothing clipped at the axis' ends (a point
// or a label at a proportion of 1, a psychometric point at 0 or 1, shows as whole as one in
// the middle), the legend under the plot and never over the data, series side by side within a
// category, and bad charts refused.
#include <gtest/gtest.h>

#include <QtGui/QImage>

#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "charts/chart_png.hpp"
#include "charts/chart_svg.hpp"
#include "core/error.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig::charts;
using palprig::test_support::TempDir;

namespace {

bool near_colour(const QColor& c, QColor want, int tolerance = 12) {
  return std::abs(c.red() - want.red()) < tolerance && std::abs(c.green() - want.green()) < tolerance &&
         std::abs(c.blue() - want.blue()) < tolerance;
}

int count_colour(const QImage& img, QColor want) {
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) n += near_colour(img.pixelColor(x, y), want);
  return n;
}

// The mean x of the pixels of a colour (-1 when there are none).
double mean_x(const QImage& img, QColor want) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (near_colour(img.pixelColor(x, y), want)) sum += x, ++n;
  return n ? sum / n : -1;
}

// A square at (1, value) with a whisker from `low` to `high`, beside a labelled point at 0.6, on
// an axis whose data end at 1.
Chart proportion_points(double value, double low, double high) {
  Chart c;
  c.x_categories = {"Se", "Sp"};
  c.y_label = "proportion";
  c.y_min = 0.0;
  c.y_max = 1.0;
  ChartSeries s;
  s.style = ChartSeries::Style::points;
  s.marker = Marker::square;
  s.marker_px = 12;
  s.color_rgb = 0x00c000;
  s.x = {0, 1};
  s.y = {0.6, value};
  s.y_low = {0.5, low};
  s.y_high = {0.7, high};
  s.point_labels = {"0.600\nn=10", ""};
  c.series.push_back(s);
  return c;
}

}  // namespace

TEST(Charts, PngAndSvgAtPrintSize) {
  TempDir dir;
  Chart c;
  c.title = "A line";
  c.x_label = "command (kPa)";
  c.y_label = "monitor (kPa)";
  ChartSeries line;
  line.label = "monitor";
  line.x = {0, 100};
  line.y = {0, 100};
  c.series.push_back(line);
  const auto png = dir.path() / "line.png";
  write_chart_png(c, png);
  QImage img;
  ASSERT_TRUE(img.load(QString::fromStdString(png.string())));
  EXPECT_EQ(img.width(), 700 * kPrintScale);
  EXPECT_EQ(img.height(), 440 * kPrintScale);
  EXPECT_NEAR(img.dotsPerMeterX() * 0.0254, kPrintDotsPerInch, 1.0);
  const auto svg = dir.path() / "line.svg";
  write_chart_svg(c, svg);
  const std::string text = palprig::test_support::read_file(svg);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("command (kPa)"), std::string::npos) << "axis labels are text in the SVG";
  EXPECT_NE(text.find("monitor (kPa)"), std::string::npos);
  EXPECT_NE(text.find("viewBox=\"0 0 700 440\""), std::string::npos);
}

TEST(Charts, RefusesChartsWithNothingToDrawAndUnwritablePaths) {
  TempDir dir;
  Chart empty;
  EXPECT_THROW(write_chart_png(empty, dir.path() / "e.png"), palprig::BadInput);
  EXPECT_THROW(write_chart_svg(empty, dir.path() / "e.svg"), palprig::BadInput);
  Chart mismatched;
  ChartSeries s;
  s.x = {1, 2};
  s.y = {1};
  mismatched.series.push_back(s);
  EXPECT_THROW(write_chart_png(mismatched, dir.path() / "m.png"), palprig::BadInput);
  Chart ok;
  ChartSeries p;
  p.x = {1, 2};
  p.y = {1, 2};
  ok.series.push_back(p);
  EXPECT_THROW(write_chart_png(ok, dir.path() / "no-such-dir" / "x.png"), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "e.png"));
}

TEST(Charts, APointAndItsWhiskerAtOneAreNotClipped) {
  // The same square drawn at 1.0, the axis' end (its whisker up to 1.0 too), and at 0.8 without a
  // whisker: as many of the square's pixels either way. The old chart cut points and error bars
  // at its frame at 1.0.
  const QColor green(0x00, 0xc0, 0x00);
  Chart top = proportion_points(1.0, 1.0, 1.0), mid = proportion_points(0.8, 0.8, 0.8);
  for (Chart* c : {&top, &mid}) c->series[0].y_low[1] = c->series[0].y_high[1] = std::nan("");
  const QImage at_top = render_chart(top, 2.0), at_mid = render_chart(mid, 2.0);
  const int on_top = count_colour(at_top, green), in_mid = count_colour(at_mid, green);
  EXPECT_GT(on_top, 400);
  EXPECT_NEAR(on_top, in_mid, 0.03 * in_mid) << "pixels of the point at 1.0 were cut";
  // The whisker's cap at 1.0 whole: its topmost green row is a bar of the cap's full width.
  const QImage whisker = render_chart(proportion_points(0.95, 0.87, 1.0), 2.0);
  int top_row = -1;
  for (int y = 0; y < whisker.height() && top_row < 0; ++y)
    for (int x = whisker.width() / 2; x < whisker.width(); ++x)
      if (near_colour(whisker.pixelColor(x, y), green)) {
        top_row = y;
        break;
      }
  ASSERT_GE(top_row, 0);
  int run = 0, longest = 0;
  for (int x = 0; x < whisker.width(); ++x) {
    run = near_colour(whisker.pixelColor(x, top_row + 1), green, 60) ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  EXPECT_GE(longest, 16) << "the cap of the whisker at 1.0 (10 px wide, at scale 2)";
}

TEST(Charts, SeriesSitSideBySideWithinACategoryAndTheLegendUnderThePlot) {
  Chart c;
  c.x_categories = {"Se"};
  c.y_min = 0;
  c.y_max = 1;
  for (unsigned rgb : {0xff0000u, 0x0000ffu}) {
    ChartSeries s;
    s.style = ChartSeries::Style::points;
    s.label = rgb == 0xff0000u ? "single-finger" : "three-finger";
    s.color_rgb = rgb;
    s.marker_px = 14;
    s.x = {0};
    s.y = {0.5};
    c.series.push_back(s);
  }
  const QImage img = render_chart(c, 1.0);
  const double red = mean_x(img, QColor(255, 0, 0)), blue = mean_x(img, QColor(0, 0, 255));
  ASSERT_GT(red, 0);
  ASSERT_GT(blue, 0);
  EXPECT_LT(red + 20, blue) << "the first series left of the second, not on top of it";
  // The legend's markers are under the plot: the lowest red pixels sit near the bottom edge.
  int lowest_red = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (near_colour(img.pixelColor(x, y), QColor(255, 0, 0))) lowest_red = y;
  EXPECT_GT(lowest_red, img.height() - 40);
}

TEST(Charts, ALegendNeverLiesOverTheData) {
  Chart c;
  c.title = "dense";
  c.x_min = 0;
  c.x_max = 10;
  c.y_min = 0;
  c.y_max = 10;
  ChartSeries dots;  // points so big and close that they paint the whole plot area red
  dots.style = ChartSeries::Style::points;
  dots.marker = Marker::square;
  dots.label = "a long legend entry that needs room";
  dots.color_rgb = 0xff0000;
  dots.marker_px = 24;
  for (int i = -2; i <= 42; ++i)
    for (int j = -2; j <= 42; ++j) {
      dots.x.push_back(i * 0.25);
      dots.y.push_back(j * 0.25);
    }
  c.series.push_back(dots);
  const QImage img = render_chart(c, 1.0);
  auto red = [&](int x, int y) { return near_colour(img.pixelColor(x, y), QColor(255, 0, 0), 20); };
  // The red area's bounding box (rows and columns with at least 100 red pixels) is the plot;
  // inside it everything is red: no legend box, no legend text.
  int x0 = img.width(), x1 = -1, y0 = img.height(), y1 = -1;
  for (int x = 0; x < img.width(); ++x) {
    int n = 0;
    for (int y = 0; y < img.height(); ++y) n += red(x, y);
    if (n >= 100) x0 = std::min(x0, x), x1 = std::max(x1, x);
  }
  for (int y = 0; y < img.height(); ++y) {
    int n = 0;
    for (int x = 0; x < img.width(); ++x) n += red(x, y);
    if (n >= 100) y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  ASSERT_GT(x1 - x0, 200);
  int covered = 0;
  for (int y = y0 + 4; y <= y1 - 4; ++y)
    for (int x = x0 + 4; x <= x1 - 4; ++x) covered += !red(x, y);
  EXPECT_EQ(covered, 0) << "pixels of the plot not showing the data (the legend lies over it)";
  int legend_text = 0;
  for (int y = y1 + 5; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const QColor p = img.pixelColor(x, y);
      legend_text += p.red() < 80 && p.green() < 80 && p.blue() < 80;
    }
  EXPECT_GT(legend_text, 100) << "the legend's text under the plot";
}

// A chart whose x counts cases (a CUSUM over 3 cases) has ticks at whole numbers only; left to
// itself QCustomPlot puts them at halves. Read off the SVG: one vertical grid line per x tick.
TEST(Charts, CountedAxesTickAtWholeNumbersOnly) {
  auto vertical_grid_lines = [](bool whole) {
    Chart c;
    c.x_label = "case";
    c.y_label = "S";
    c.x_min = 0.0;
    c.x_max = 3.0;
    c.x_whole_numbers = whole;
    ChartSeries s;
    for (int i = 0; i <= 3; ++i) {
      s.x.push_back(i);
      s.y.push_back(0.1 * i);
    }
    c.series.push_back(s);
    TempDir dir;
    write_chart_svg(c, dir.path() / "c.svg");
    std::ifstream in(dir.path() / "c.svg");
    const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The grid is drawn in its own light grey group; a vertical line has the same x at both ends.
    int lines = 0;
    std::size_t at = 0;
    while ((at = svg.find("stroke=\"#e1e1e1\"", at)) != std::string::npos) {
      const std::size_t end = svg.find("</g>", at);
      const std::regex line(R"re(points="([0-9.]+),[0-9.]+ ([0-9.]+),[0-9.]+ ")re");
      const std::string group = svg.substr(at, end - at);
      for (std::sregex_iterator m(group.begin(), group.end(), line), none; m != none; ++m) lines += (*m)[1] == (*m)[2];
      at = end;
    }
    return lines;
  };
  EXPECT_GT(vertical_grid_lines(false), 4) << "the default ticker's half-case ticks (the test's premise)";
  EXPECT_EQ(vertical_grid_lines(true), 4) << "ticks at 0, 1, 2 and 3 cases";
}
