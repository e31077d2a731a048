// palprig export --plot: a simulated study exported with paper 002's fig. 15 chart, read back
// as an image at print size, both conditions' points present.
#include <gtest/gtest.h>

#include <QtGui/QImage>

#include "tests/support/run_process.hpp"

using namespace palprig::test_support;

TEST(ExportPlot, MeasuresByConditionChartIsWritten) {
  TempDir dir;
  const std::string db = (dir.path() / "t.db").string();
  for (int seed : {1, 2}) {
    const ProcessResult r = run_process(
        palprig_bin() + " experiment run --quiet --protocol " + source_dir() +
        "/data/protocols/discrimination_002.json --participant sim:" + std::to_string(seed) + " --db " + db);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto plots = dir.path() / "plots";
  const ProcessResult r = run_process(palprig_bin() + " export " + db + " --format csv --out " +
                                      (dir.path() / "csv").string() + " --plot " + plots.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto png = plots / "measures_by_condition.png";
  EXPECT_NE(r.out.find(png.string()), std::string::npos) << r.out;
  QImage img(QString::fromStdString(png.string()));
  ASSERT_FALSE(img.isNull());
  // Print size: 7 x 4.4 in at 300 dpi.
  EXPECT_EQ(img.width(), 2100);
  EXPECT_EQ(img.height(), 1320);
  // Two conditions: the palette's first two colours (Okabe and Ito's blue and vermillion) mark
  // points and whiskers in the plot and their legend entries.
  int blue = 0, red = 0;
  for (int y = 0; y < img.height(); y += 2)
    for (int x = 0; x < img.width(); x += 2) {
      const QColor c = img.pixelColor(x, y);
      if (c == QColor(0x00, 0x72, 0xb2)) ++blue;
      if (c == QColor(0xd5, 0x5e, 0x00)) ++red;
    }
  EXPECT_GT(blue, 200);
  EXPECT_GT(red, 200);
}

TEST(ExportPlot, AFileThatIsNotATrialDatabaseIsRefusedBeforeAnyPlot) {
  TempDir dir;
  const std::string db = (dir.path() / "empty.db").string();
  dir.write("empty.db", "not a database");
  const ProcessResult r = run_process(palprig_bin() + " export " + db + " --out " + (dir.path() / "o").string() +
                                      " --plot " + (dir.path() / "p").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "p" / "measures_by_condition.png"));
}
