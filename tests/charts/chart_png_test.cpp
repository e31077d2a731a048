// The PNG chart drawing the command line's --plot options use: a real file is written, of the
// asked size, with series drawn where their data says (pixels checked), and bad charts refused.
#include <gtest/gtest.h>

#include <QtGui/QImage>

#include "io/checked_output.hpp"
#include "core/error.hpp"
#include "charts/chart_png.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig::charts;
using palprig::test_support::TempDir;

namespace {
// Whether a pixel near (x, y) has the colour (within a few levels of antialiasing).
bool has_colour_near(const QImage& img, int x, int y, QColor want) {
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx) {
      const QColor c = img.pixelColor(x + dx, y + dy);
      if (std::abs(c.red() - want.red()) < 12 && std::abs(c.green() - want.green()) < 12 &&
          std::abs(c.blue() - want.blue()) < 12)
        return true;
    }
  return false;
}
}  // namespace

TEST(ChartPng, BarsWithErrorBarsOnCategories) {
  TempDir dir;
  Chart c;
  c.title = "Accuracy";
  c.y_label = "ACC";
  c.x_categories = {"single", "three"};
  c.width_px = 600;
  c.height_px = 400;
  c.y_min = 0;
  c.y_max = 1;
  ChartSeries bars;
  bars.style = ChartSeries::Style::bars;
  // No label: no legend column, so the plot spans the width the pixel positions below assume.
  bars.x = {0, 1};
  bars.y = {0.933, 0.968};
  bars.y_low = {0.908, 0.949};
  bars.y_high = {0.951, 0.980};
  bars.color_rgb = 0x00ff00;
  c.series.push_back(bars);
  const auto path = dir.path() / "bars.png";
  write_chart_png(c, path);
  QImage img;
  ASSERT_TRUE(img.load(QString::fromStdString(path.string())));
  EXPECT_EQ(img.width(), 600);
  EXPECT_EQ(img.height(), 400);
  // With a title the plot spans x 80..576 for categories -0.5..1.5 and y 46..336 for 0..1: the
  // first bar's middle (x = 0, y = 0.45) is green; beside it, at the top of the axis, it is not.
  const int x0 = 80 + int(0.5 / 2.0 * 496), y_mid = 336 - int(0.45 * 290), y_above = 336 - int(0.99 * 290);
  EXPECT_TRUE(has_colour_near(img, x0, y_mid, QColor(0, 255, 0)));
  EXPECT_FALSE(has_colour_near(img, x0 + 60, y_above, QColor(0, 255, 0)));
}

TEST(ChartPng, LinesAndPointsOnNumericAxes) {
  TempDir dir;
  Chart c;
  c.x_label = "command (kPa)";
  c.y_label = "monitor (kPa)";
  c.x_min = 0;
  c.x_max = 100;
  c.y_min = 0;
  c.y_max = 100;
  c.width_px = 500;
  c.height_px = 400;
  ChartSeries line;  // no label: no legend column beside the plot
  line.x = {0, 100};
  line.y = {0, 100};
  line.color_rgb = 0xff0000;
  line.width_px = 3;
  c.series.push_back(line);
  const auto path = dir.path() / "line.png";
  write_chart_png(c, path);
  QImage img;
  ASSERT_TRUE(img.load(QString::fromStdString(path.string())));
  // Plot area 80..476 x 20..336: the diagonal passes through the middle, red.
  EXPECT_TRUE(has_colour_near(img, 80 + 198, 20 + 158, QColor(255, 0, 0)));
  EXPECT_FALSE(has_colour_near(img, 80 + 100, 20 + 50, QColor(255, 0, 0)));  // above-left of it: background
}

TEST(ChartPng, RefusesChartsWithNothingToDrawAndUnwritablePaths) {
  TempDir dir;
  Chart empty;
  EXPECT_THROW(write_chart_png(empty, dir.path() / "e.png"), palprig::BadInput);
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
  EXPECT_THROW(write_chart_png(ok, dir.path() / "no-such-dir" / "x.png"), palprig::OutputError);
}

TEST(ChartPng, LegendSitsBesideThePlotNeverOverTheData) {
  TempDir dir;
  Chart c;
  c.title = "dense";
  c.x_min = 0;
  c.x_max = 10;
  c.y_min = 0;
  c.y_max = 10;
  c.width_px = 600;
  c.height_px = 400;
  ChartSeries dots;  // points so big and close that they paint the whole plot area red
  dots.style = ChartSeries::Style::points;
  dots.label = "a long legend entry that needs room";
  dots.color_rgb = 0xff0000;
  dots.width_px = 12;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      dots.x.push_back(i * 0.25);
      dots.y.push_back(j * 0.25);
    }
  c.series.push_back(dots);
  const auto path = dir.path() / "legend.png";
  write_chart_png(c, path);
  QImage img;
  ASSERT_TRUE(img.load(QString::fromStdString(path.string())));
  auto red = [&](int x, int y) {
    const QColor p = img.pixelColor(x, y);
    return p.red() > 240 && p.green() < 15 && p.blue() < 15;
  };
  // The red area's bounding box is the plot; inside it (away from the antialiased frame)
  // everything is red: no legend box, no legend text.
  // (Columns and rows with at least 100 red pixels: the legend's 10 px swatch is not counted.)
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
  // The legend is drawn, to the right of the plot: its swatch is red, its text dark.
  int legend_red = 0, legend_text = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x1 + 5; x < img.width(); ++x) {
      const QColor p = img.pixelColor(x, y);
      legend_red += red(x, y);
      legend_text += p.red() < 80 && p.green() < 80 && p.blue() < 80;
    }
  EXPECT_GT(legend_red, 20);
  EXPECT_GT(legend_text, 20);
}
