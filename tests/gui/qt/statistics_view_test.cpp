// Qt Test suite for the live statistics view (registered as gui.StatisticsView.*, offscreen).
// Every store is a real SQLite file filled by real `palprig experiment run` processes with the
// simulated participant; the view's numbers and exports are compared with what real
// `palprig stats trials --json` and `palprig export` processes print and write. Tests wait on
// the view's signals (QSignalSpy::wait), never on fixed sleeps.
#include <QApplication>
#include <QFile>
#include <QImage>
#include <QLabel>
#include <QProcess>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QtTest>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gui/chart_view.hpp"
#include "gui/statistics_tables.hpp"
#include "gui/statistics_view.hpp"
#include "store/trial_summary_report.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using namespace palprig::gui;
using palprig::test_support::TempDir;
namespace fs = std::filesystem;

namespace {

std::string protocol(const char* name) { return std::string(PALPRIG_SOURCE_DIR) + "/data/protocols/" + name; }

// Runs palprig with `args`; fails the test on a non-zero exit. Returns stdout.
QByteArray run_cli(const QStringList& args) {
  QProcess p;
  p.start(QStringLiteral(PALPRIG_BIN), args);
  if (!p.waitForFinished(120000)) qFatal("palprig %s did not finish", qPrintable(args.join(' ')));
  if (p.exitStatus() != QProcess::NormalExit || p.exitCode() != 0)
    qFatal("palprig %s failed: %s", qPrintable(args.join(' ')), p.readAllStandardError().constData());
  return p.readAllStandardOutput();
}

void run_participant(const fs::path& db, const char* protocol_name, const char* participant) {
  run_cli({"experiment", "run", "--protocol", QString::fromStdString(protocol(protocol_name)), "--participant",
           participant, "--db", QString::fromStdString(db.string()), "--quiet"});
}

// Waits until the view has finished every refresh it was asked for; returns the refreshes seen.
int wait_idle(StatisticsView& view, QSignalSpy& refreshed) {
  while (view.refreshing()) {
    if (!refreshed.wait(60000)) qFatal("no refresh within 60 s");
  }
  return int(refreshed.count());
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Relative path -> content of every file below `dir`.
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_bytes(e.path());
  return files;
}

QTableWidget* table(StatisticsView& view, const char* name) {
  auto* t = view.findChild<QTableWidget*>(name);
  if (!t) qFatal("no table %s", name);
  return t;
}

// The row of the measures table whose group cell is `group`; -1 when none.
int row_of(QTableWidget* t, const QString& group) {
  for (int r = 0; r < t->rowCount(); ++r)
    if (t->item(r, group_column)->text() == group) return r;
  return -1;
}

}  // namespace

class StatisticsViewTest : public QObject {
  Q_OBJECT
 private slots:
  void numbersEqualStatsTrialsJson();
  void measureWithNoCasesShowsNa();
  void ratingAndRtAfterStimulusEqualStatsTrialsJson();
  void exportsEqualPalprigExport();
  void refreshesAskedWhileOneRunsAreCoalesced();
  void refreshesByItselfWhenTrialsAreCommitted();
  void unreadableStoreIsNamedAndOldNumbersStay();
};

void StatisticsViewTest::numbersEqualStatsTrialsJson() {
  TempDir dir;
  const fs::path db = dir.path() / "trials.db";
  run_participant(db, "discrimination_002.json", "sim:7");
  run_participant(db, "discrimination_002.json", "sim:8");
  const auto cli =
      nlohmann::ordered_json::parse(run_cli({"stats", "trials", QString::fromStdString(db.string()), "--json"}));

  StatisticsView view;
  view.resize(1400, 900);
  view.show();
  QSignalSpy refreshed(&view, &StatisticsView::refreshed);
  view.set_store(QString::fromStdString(db.string()));
  QCOMPARE(refreshed.count(), 0);  // set_store returns before the numbers exist: the work is on a worker
  wait_idle(view, refreshed);

  TrialSummary shown{{SummaryKey::condition}, view.condition_rows()};
  QCOMPARE(QString::fromStdString(summary_json(shown, 0.95).dump(2)), QString::fromStdString(cli.dump(2)));
  QCOMPARE(view.condition_rows().size(), std::size_t(2));

  // The table shows those numbers: Se of each condition with its interval and n.
  auto* measures = table(view, "measuresTable");
  for (const auto& row : cli["rows"]) {
    const int r = row_of(measures, "condition " + QString::fromStdString(row["condition"].get<std::string>()));
    QVERIFY(r >= 0);
    const auto& se = row["Se"];
    const QString expected =
        QStringLiteral("%1 [%2, %3] n=%4")
            .arg(QString::number(se["value"].get<double>(), 'f', 3), QString::number(se["lower"].get<double>(), 'f', 3),
                 QString::number(se["upper"].get<double>(), 'f', 3))
            .arg(se["n"].get<long long>());
    QCOMPARE(measures->item(r, se_column)->text(), expected);
    QCOMPARE(measures->item(r, tp_column)->text(), QString::number(row["TP"].get<long long>()));
  }
  // Per finger value: three rows, one per finger, whose counts add up to the conditions'.
  std::int64_t finger_tp = 0;
  for (const auto& r : view.statistics()->by_finger.rows) finger_tp += r.counts.tp;
  QCOMPARE(view.statistics()->by_finger.rows.size(), std::size_t(3));
  QCOMPARE(finger_tp, std::int64_t(cli["rows"][0]["TP"].get<long long>() + cli["rows"][1]["TP"].get<long long>()));
  QVERIFY(row_of(measures, "finger 2") >= 0);

  // The comparisons: one t-test of response times and eq. 10 for each measure defined on both sides.
  const TrialStatistics& s = *view.statistics();
  QCOMPARE(s.response_times.size(), std::size_t(1));
  QVERIFY(s.response_times[0].test.has_value());
  QCOMPARE(s.response_times[0].test->kind, stats::TTestKind::student);
  QCOMPARE(double(s.response_times[0].test->mean_x), cli["rows"][0]["rt_mean_s"].get<double>());
  auto* comparisons = table(view, "comparisonsTable");
  QCOMPARE(comparisons->rowCount(), int(1 + s.measures.size()));
  QVERIFY(comparisons->item(0, 3)->text().startsWith("t("));
  QVERIFY(measures->isColumnHidden(confidence_column));  // the protocol asks no rating

  // For the README: the view with its numbers, when asked.
  if (const char* shot = std::getenv("PALPRIG_STATISTICS_SCREENSHOT")) QVERIFY(view.grab().save(shot));
}

void StatisticsViewTest::ratingAndRtAfterStimulusEqualStatsTrialsJson() {
  TempDir dir;
  const fs::path db = dir.path() / "rated.db";
  run_participant(db, "discrimination_002_confidence.json", "sim:7");
  run_participant(db, "discrimination_002_confidence.json", "sim:8");
  const auto cli =
      nlohmann::ordered_json::parse(run_cli({"stats", "trials", QString::fromStdString(db.string()), "--json"}));
  StatisticsView view;
  view.resize(1400, 900);
  view.show();
  QSignalSpy refreshed(&view, &StatisticsView::refreshed);
  view.set_store(QString::fromStdString(db.string()));
  wait_idle(view, refreshed);
  TrialSummary shown{{SummaryKey::condition}, view.condition_rows()};
  shown.any_rated = view.statistics()->by_condition.any_rated;
  QCOMPARE(QString::fromStdString(summary_json(shown, 0.95).dump(2)), QString::fromStdString(cli.dump(2)));
  auto* measures = table(view, "measuresTable");
  QVERIFY(!measures->isColumnHidden(confidence_column));
  for (const auto& row : cli["rows"]) {
    const int r = row_of(measures, "condition " + QString::fromStdString(row["condition"].get<std::string>()));
    QVERIFY(r >= 0);
    QCOMPARE(measures->item(r, rt_after_column)->text(),
             QString::number(row["rt_after_stimulus_mean_s"].get<double>(), 'f', 2) + QStringLiteral(" ± ") +
                 QString::number(row["rt_after_stimulus_sd_s"].get<double>(), 'f', 2));
    // From when the stimulus reached the fingers (the simulated rig's monitors at half the level).
    QCOMPARE(measures->item(r, rt_reached_column)->text(),
             QString::number(row["rt_from_reached_mean_s"].get<double>(), 'f', 2) + QStringLiteral(" ± ") +
                 QString::number(row["rt_from_reached_sd_s"].get<double>(), 'f', 2));
    QVERIFY(row["rated"].get<int>() > 0);
    QCOMPARE(measures->item(r, confidence_column)->text(),
             QString::number(row["confidence_mean"].get<double>(), 'f', 2) +
                 QStringLiteral(" (n=%1)").arg(row["rated"].get<int>()));
  }
}

void StatisticsViewTest::measureWithNoCasesShowsNa() {
  TempDir dir;
  const fs::path db = dir.path() / "localisation.db";
  run_participant(db, "localisation_002.json", "sim:3");
  run_participant(db, "localisation_002.json", "sim:4");
  const auto cli =
      nlohmann::ordered_json::parse(run_cli({"stats", "trials", QString::fromStdString(db.string()), "--json"}));
  QVERIFY(cli["rows"][0]["Sp"].is_null());

  StatisticsView view;
  view.resize(1400, 900);
  QSignalSpy refreshed(&view, &StatisticsView::refreshed);
  view.set_store(QString::fromStdString(db.string()));
  wait_idle(view, refreshed);
  QCOMPARE(
      QString::fromStdString(summary_json(TrialSummary{{SummaryKey::condition}, view.condition_rows()}, 0.95).dump()),
      QString::fromStdString(cli.dump()));

  // Localisation has no true negatives: Sp and ACC are n/a in the table and on the chart, not 0.
  auto* measures = table(view, "measuresTable");
  const int r = row_of(measures, "condition " + QString::fromStdString(cli["rows"][0]["condition"].get<std::string>()));
  QVERIFY(r >= 0);
  QCOMPARE(measures->item(r, sp_column)->text(), QStringLiteral("n/a"));
  QCOMPARE(measures->item(r, acc_column)->text(), QStringLiteral("n/a"));
  QCOMPARE(measures->item(r, tn_column)->text(), QStringLiteral("n/a"));
  QVERIFY(measures->item(r, se_column)->text().contains("n="));
  const charts::Chart& chart = view.findChild<ChartView*>("conditionChart")->chart();
  QCOMPARE(chart.series[0].point_labels[1], std::string("n/a"));
  QVERIFY(std::isnan(chart.series[0].y[1]));

  // Per-tumor sensitivity: a row per tumor of the scene, on the detail chart too.
  const auto& tumors = view.statistics()->by_tumor.rows;
  QVERIFY(!tumors.empty());
  std::int64_t detected = 0;
  for (const auto& t : tumors) detected += t.counts.tp;
  QCOMPARE(detected, std::int64_t(cli["rows"][0]["TP"].get<long long>()));
  QVERIFY(row_of(measures, "tumor " + QString::fromStdString(tumors[0].key[0])) >= 0);
  const charts::Chart& detail = view.findChild<ChartView*>("detailChart")->chart();
  QCOMPARE(detail.x_categories.size(), tumors.size());
  // No finger values, and comparisons need two conditions: the tables say so rather than 0.
  QVERIFY(view.statistics()->by_finger.rows.empty());
}

void StatisticsViewTest::exportsEqualPalprigExport() {
  TempDir dir;
  const fs::path db = dir.path() / "trials.db";
  run_participant(db, "discrimination_002.json", "sim:7");
  const QString dbq = QString::fromStdString(db.string());
  run_cli({"export", dbq, "--format", "csv", "--out", QString::fromStdString((dir.path() / "cli_csv").string())});
  run_cli({"export", dbq, "--format", "bids", "--out", QString::fromStdString((dir.path() / "cli_bids").string())});
  // The chart leaves practice trials out (as `stats trials` does) without --no-practice.
  run_cli({"export", dbq, "--format", "csv", "--out", QString::fromStdString((dir.path() / "unused").string()),
           "--plot", QString::fromStdString((dir.path() / "cli_plot").string())});
  const QByteArray cli_json = run_cli({"stats", "trials", dbq, "--json"});

  StatisticsView view;
  view.resize(1400, 900);
  QSignalSpy refreshed(&view, &StatisticsView::refreshed);
  view.set_store(dbq);
  wait_idle(view, refreshed);
  const fs::path out = dir.path() / "view";
  view.set_export_directory(QString::fromStdString(out.string()));
  QSignalSpy exported(&view, &StatisticsView::exported);
  QSignalSpy failed(&view, &StatisticsView::export_failed);
  auto click = [&](const char* button, const fs::path& sub) {
    view.set_export_directory(QString::fromStdString((out / sub).string()));
    auto* b = view.findChild<QPushButton*>(button);
    QVERIFY(b && b->isEnabled());
    const auto before = exported.count();
    QTest::mouseClick(b, Qt::LeftButton);
    QVERIFY2(exported.count() > before || exported.wait(60000),
             failed.isEmpty() ? "" : qPrintable(failed.last()[0].toString()));
  };
  click("exportLongCsv", "csv");
  click("exportBids", "bids");
  click("exportStatisticsJson", "json");
  click("exportChartPng", "png");
  click("exportChartSvg", "svg");
  QVERIFY(failed.isEmpty());

  QCOMPARE(tree(out / "csv"), tree(dir.path() / "cli_csv"));
  QCOMPARE(tree(out / "bids"), tree(dir.path() / "cli_bids"));
  QCOMPARE(QByteArray::fromStdString(read_bytes(out / "json" / "statistics.json")), cli_json);
  const QImage mine(QString::fromStdString((out / "png" / "measures_by_condition.png").string()));
  const QImage cli_png(QString::fromStdString((dir.path() / "cli_plot" / "measures_by_condition.png").string()));
  QVERIFY(!mine.isNull());
  QCOMPARE(mine, cli_png);  // the same drawing as `palprig export --plot`, pixel for pixel
  QVERIFY(fs::exists(out / "png" / "measures_by_finger.png"));
  const std::string svg = read_bytes(out / "svg" / "measures_by_condition.svg");
  QVERIFY(svg.find("<svg") != std::string::npos);
  QVERIFY(svg.find("n=") != std::string::npos);  // the n labels are text in the vector file

  // An export into a place that cannot be written is refused with a line, and nothing crashes.
  view.export_to(StatisticsView::ExportKind::statistics_json, "/proc/palprig-cannot-write-here");
  QVERIFY(failed.wait(60000));
  QVERIFY(!failed.last()[0].toString().isEmpty());
}

void StatisticsViewTest::refreshesAskedWhileOneRunsAreCoalesced() {
  TempDir dir;
  const fs::path db = dir.path() / "trials.db";
  run_participant(db, "discrimination_002.json", "sim:7");
  StatisticsView view;
  QSignalSpy refreshed(&view, &StatisticsView::refreshed);
  view.set_store(QString::fromStdString(db.string()));
  // The worker's result reaches the view only through the GUI thread's event loop, which these
  // calls do not enter: all ten arrive while the first refresh runs, and become one more.
  for (int i = 0; i < 10; ++i) view.refresh();
  QVERIFY(view.refreshing());
  QCOMPARE(wait_idle(view, refreshed), 2);
}

void StatisticsViewTest::refreshesByItselfWhenTrialsAreCommitted() {
  TempDir dir;
  const fs::path db = dir.path() / "trials.db";
  run_participant(db, "discrimination_002.json", "sim:7");
  StatisticsView view;
  QSignalSpy refreshed(&view, &StatisticsView::refreshed);
  view.set_store(QString::fromStdString(db.string()));
  wait_idle(view, refreshed);
  const auto trials = [&] {
    std::int64_t n = 0;
    for (const auto& r : view.condition_rows()) n += r.trials;
    return n;
  };
  const std::int64_t first = trials();
  QVERIFY(first > 0);
  // Another participant's session in another process: nobody calls refresh(); the view follows
  // the file's commits.
  run_participant(db, "discrimination_002.json", "sim:8");
  QTRY_VERIFY_WITH_TIMEOUT(!view.refreshing() && trials() == 2 * first, 60000);
}

void StatisticsViewTest::unreadableStoreIsNamedAndOldNumbersStay() {
  TempDir dir;
  StatisticsView view;
  QSignalSpy failed(&view, &StatisticsView::refresh_failed);
  const std::string missing = (dir.path() / "no-such.db").string();
  view.set_store(QString::fromStdString(missing));
  QVERIFY(failed.wait(60000));
  QVERIFY2(failed.last()[0].toString().contains(QString::fromStdString(missing)),
           qPrintable(failed.last()[0].toString()));
  QVERIFY(view.condition_rows().empty());
  QVERIFY(!view.findChild<QPushButton*>("exportLongCsv")->isEnabled());
  QVERIFY(view.findChild<QLabel*>("statisticsStatus")->text().contains("no-such.db"));
}

QTEST_MAIN(StatisticsViewTest)
#include "statistics_view_test.moc"
