#pragma once
// The live statistics of a trial store: Se, Sp, PPV, ACC per condition and per finger
// value with Wilson intervals as asymmetric error bars (n above each bar, "n/a" where a measure
// has no cases), per-tumor sensitivity for localisation, response time mean/sd per condition
// with paper 002's t-test, and paper 002's combined-interval comparison (eq. 10).
//
// Threads: every read of the store happens on a worker (QtConcurrent) over its own read-only
// connection (SQLITE_OPEN_READONLY), so a slow disk or a big store never freezes the window, and
// the view can never change what it shows. A refresh asked while one runs is coalesced into one
// more refresh after it. The view refreshes by itself when the SQLite file or its WAL changes
// (each committed trial), a quarter of a second after the last change.
//
// Exports (buttons, or export_to for the console and tests) run on a worker too and call the
// same library functions as `palprig export` (long CSV, BIDS) and `palprig stats trials --json`
// (statistics.json); the charts are written as PNG and SVG from the same drawing as the screen,
// on the GUI thread (QCustomPlot draws them, and it is a widget; a chart takes a few tens of ms),
// from the event loop's next turn, so exported() follows export_to as for the other kinds.
//
// Pulse-localisation trials: hit rate per condition with its Wilson interval and n,
// distance to the artery mean / median / IQR, from PulseStore::summarise (the same call as
// `palprig stats trials`), in their own table and, when the store has only pulse trials, in the
// two charts (gui/pulse_statistics).
#include <QFutureWatcher>
#include <QString>
#include <QStringList>
#include <QWidget>
#include <memory>
#include <vector>

#include "store/trial_statistics.hpp"
#include "store/trial_summary.hpp"

class QFileSystemWatcher;
class QLabel;
class QPushButton;
class QSplitter;
class QTableWidget;
class QTimer;

namespace palprig::gui {

class ChartView;

// What one refresh produced: the numbers, or the one-line reason the store could not be read.
struct StatisticsRefresh {
  std::shared_ptr<const TrialStatistics> statistics;
  QString error;
};

// What one export wrote, or why it could not.
struct StatisticsExport {
  QStringList files;
  QString error;
};

class StatisticsView : public QWidget {
  Q_OBJECT
 public:
  enum class ExportKind { long_csv, bids, statistics_json, chart_png, chart_svg };

  explicit StatisticsView(QWidget* parent = nullptr);
  ~StatisticsView() override;

  // The store to read: a SQLite file (or postgresql:// URI once the lab store lands). Starts a refresh.
  void set_store(const QString& store_location);
  QString store_location() const { return location_; }

  // Numbers of the last completed refresh (for tests and the screenshot): the same rows
  // `palprig stats trials --json` prints (store/trial_summary.hpp).
  const std::vector<SummaryRow>& condition_rows() const;
  // Pulse rows of the last completed refresh (empty without pulse trials).
  const std::vector<PulseConditionSummary>& pulse_rows() const;
  // Everything of the last completed refresh; null before the first one.
  const TrialStatistics* statistics() const { return statistics_.get(); }
  bool refreshing() const { return running_; }

  // The export buttons write into this folder without asking (the console's session folder,
  // tests); empty (the default): they ask with a folder dialog.
  void set_export_directory(const QString& dir) { export_dir_ = dir; }
  // Writes one export of the current store into `dir` (created when missing) off the GUI thread;
  // exported() or export_failed() follows.
  void export_to(ExportKind kind, const QString& dir);

 public slots:
  void refresh();  // recompute off the GUI thread; a refresh asked while one runs is coalesced

 signals:
  void refreshed();                             // the view now shows the numbers of the last refresh
  void refresh_failed(const QString& message);  // the store could not be read; old numbers stay
  void exported(const QStringList& files);
  void export_failed(const QString& message);

 private:
  void start_refresh();
  void refresh_done();
  void display(const TrialStatistics& statistics);
  void watch_store_files();
  void ask_and_export(ExportKind kind);
  void export_finished(const StatisticsExport& result);

  QString location_, export_dir_;
  std::shared_ptr<const TrialStatistics> statistics_;
  bool running_ = false, pending_ = false;
  bool chart_export_pending_ = false;  // a chart export waits for the event loop (GUI thread)
  QFutureWatcher<StatisticsRefresh> refresh_watcher_;
  QFutureWatcher<StatisticsExport> export_watcher_;
  QFileSystemWatcher* file_watcher_ = nullptr;
  QTimer* change_delay_ = nullptr;
  QLabel* status_ = nullptr;
  ChartView* condition_chart_ = nullptr;
  ChartView* detail_chart_ = nullptr;  // per finger value (discrimination) or per tumor (localisation)
  QTableWidget* measures_table_ = nullptr;
  QTableWidget* comparisons_table_ = nullptr;
  QTableWidget* pulse_table_ = nullptr;
  QSplitter* tables_ = nullptr;  // charts, measures, comparisons, pulse
  std::vector<QPushButton*> export_buttons_;
};

}  // namespace palprig::gui
