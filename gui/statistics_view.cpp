#include "gui/statistics_view.hpp"
#include "core/error.hpp"
#include "gui/counted_text.hpp"

#include <QDateTime>
#include <QFileDialog>
#include <QFileInfo>
#include <QFileSystemWatcher>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>
#include <exception>
#include <filesystem>

#include "charts/chart_svg.hpp"
#include "gui/chart_view.hpp"
#include "charts/measures_chart.hpp"
#include "gui/pulse_statistics.hpp"
#include "io/checked_output.hpp"
#include "gui/statistics_tables.hpp"
#include "store/trial_export.hpp"
#include "store/trial_summary_report.hpp"

namespace palprig::gui {

namespace {

// The options of `palprig stats trials` with no flags: practice left out, 95 % intervals.
SummaryOptions view_options() {
  SummaryOptions options;
  options.by = {SummaryKey::condition};
  return options;
}

// Runs on the worker: its own read-only connection, closed before returning.
StatisticsRefresh compute(const std::string& location) {
  StatisticsRefresh r;
  try {
    const auto store = open_trial_store(location, TrialStore::Access::read_only);
    r.statistics = std::make_shared<const TrialStatistics>(compute_trial_statistics(*store, view_options()));
  } catch (const std::exception& e) {
    r.error = QString::fromStdString(e.what());
  }
  return r;
}

// A store with pulse trials only: its charts are the pulse ones.
bool pulse_only(const TrialStatistics& s) { return !s.pulse.empty() && s.by_condition.rows.empty(); }

charts::Chart condition_chart(const TrialStatistics& s) {
  return pulse_only(s) ? charts::pulse_hit_rate_chart(s.pulse, s.confidence) : charts::measures_chart(s.by_condition);
}

charts::Chart detail_chart(const TrialStatistics& s) {
  if (pulse_only(s)) return charts::pulse_distance_chart(s.pulse);
  if (!s.by_tumor.rows.empty() && s.by_finger.rows.empty()) return charts::tumor_sensitivity_chart(s.by_tumor);
  return charts::measures_chart(s.by_finger, "Se, Sp, PPV and ACC per finger value (Wilson 95 % intervals)", "finger ");
}

std::string detail_chart_name(const TrialStatistics& s) {
  if (pulse_only(s)) return "pulse_distance_by_condition";
  return !s.by_tumor.rows.empty() && s.by_finger.rows.empty() ? "sensitivity_by_tumor" : "measures_by_finger";
}

bool has_bars(const charts::Chart& chart) {
  for (const auto& series : chart.series)
    if (!series.y.empty()) return true;
  return false;
}

// Runs on the worker (charts: on the GUI thread); the same library calls as `palprig export` and
// `palprig stats trials --json`.
StatisticsExport run_export(StatisticsView::ExportKind kind, const std::string& location,
                            const std::filesystem::path& dir, const std::shared_ptr<const TrialStatistics>& shown) {
  using Kind = StatisticsView::ExportKind;
  StatisticsExport out;
  try {
    std::filesystem::create_directories(dir);
    std::vector<std::filesystem::path> files;
    if (kind == Kind::long_csv || kind == Kind::bids || kind == Kind::statistics_json) {
      const auto store = open_trial_store(location, TrialStore::Access::read_only);
      if (kind == Kind::statistics_json) {
        const SummaryOptions options = view_options();
        const auto path = dir / "statistics.json";
        CheckedOutputFile file(path);
        file.write(stats_trials_text(*store, options, "json"));  // byte for byte `stats trials --json`
        file.commit();
        files.push_back(path);
      } else {
        const ExportResult r = kind == Kind::bids ? export_bids(*store, dir, ExportOptions{})
                                                  : export_long_csv(*store, dir, ExportOptions{});
        files = r.files;
      }
    } else {
      // The charts as the view shows them (the numbers of the last refresh).
      if (!shown) throw BadInput("no statistics shown yet: refresh first");
      const char* ext = kind == Kind::chart_png ? ".png" : ".svg";
      auto write = [&](const charts::Chart& chart, const std::string& name) {
        const auto path = dir / (name + ext);
        if (kind == Kind::chart_png)
          charts::write_chart_png(chart, path);
        else
          charts::write_chart_svg(chart, path);
        files.push_back(path);
      };
      write(condition_chart(*shown), pulse_only(*shown) ? "pulse_hit_rate_by_condition" : "measures_by_condition");
      const charts::Chart detail = detail_chart(*shown);
      if (has_bars(detail)) write(detail, detail_chart_name(*shown));
    }
    for (const auto& f : files) out.files << QString::fromStdString(f.string());
  } catch (const std::exception& e) {
    out.error = QString::fromStdString(e.what());
  }
  return out;
}

QTableWidget* make_table(QWidget* parent, const char* name) {
  auto* table = new QTableWidget(parent);
  table->setObjectName(name);
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table->verticalHeader()->setVisible(false);
  table->setAlternatingRowColors(true);
  return table;
}

}  // namespace

StatisticsView::StatisticsView(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* top = new QHBoxLayout;
  status_ = new QLabel(tr("no trial store"), this);
  status_->setObjectName("statisticsStatus");
  status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  top->addWidget(status_, 1);
  auto* refresh_button = new QPushButton(tr("Refresh"), this);
  refresh_button->setObjectName("refreshStatistics");
  connect(refresh_button, &QPushButton::clicked, this, &StatisticsView::refresh);
  top->addWidget(refresh_button);
  const std::pair<ExportKind, const char*> buttons[] = {{ExportKind::long_csv, "Long CSV"},
                                                        {ExportKind::bids, "BIDS"},
                                                        {ExportKind::statistics_json, "Statistics JSON"},
                                                        {ExportKind::chart_png, "Chart PNG"},
                                                        {ExportKind::chart_svg, "Chart SVG"}};
  const char* names[] = {"exportLongCsv", "exportBids", "exportStatisticsJson", "exportChartPng", "exportChartSvg"};
  for (std::size_t i = 0; i < std::size(buttons); ++i) {
    auto* b = new QPushButton(tr(buttons[i].second), this);
    b->setObjectName(names[i]);
    b->setEnabled(false);
    const ExportKind kind = buttons[i].first;
    connect(b, &QPushButton::clicked, this, [this, kind] { ask_and_export(kind); });
    top->addWidget(b);
    export_buttons_.push_back(b);
  }
  layout->addLayout(top);

  auto* charts = new QSplitter(Qt::Horizontal, this);
  condition_chart_ = new ChartView(charts);
  condition_chart_->setObjectName("conditionChart");
  detail_chart_ = new ChartView(charts);
  detail_chart_->setObjectName("detailChart");
  auto* vertical = tables_ = new QSplitter(Qt::Vertical, this);
  vertical->addWidget(charts);
  measures_table_ = make_table(vertical, "measuresTable");
  comparisons_table_ = make_table(vertical, "comparisonsTable");
  pulse_table_ = make_table(vertical, "pulseTable");
  pulse_table_->setVisible(false);
  vertical->setSizes({520, 230, 170});  // the charts get most of the height (scaled with the view)
  // During a session the experiment page leaves this view little height (at 1280 x 800 the charts
  // were squeezed to their titles): the charts keep a readable height and the view scrolls
  // instead, so the window never grows past the screen.
  charts->setMinimumHeight(240);
  auto* scroll = new QScrollArea(this);
  scroll->setObjectName("statisticsScroll");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setWidget(vertical);
  layout->addWidget(scroll, 1);

  file_watcher_ = new QFileSystemWatcher(this);
  change_delay_ = new QTimer(this);
  change_delay_->setSingleShot(true);
  change_delay_->setInterval(250);  // a commit touches the WAL several times: one refresh for them
  connect(change_delay_, &QTimer::timeout, this, &StatisticsView::refresh);
  connect(file_watcher_, &QFileSystemWatcher::fileChanged, this, [this] { change_delay_->start(); });
  connect(&refresh_watcher_, &QFutureWatcher<StatisticsRefresh>::finished, this, &StatisticsView::refresh_done);
  connect(&export_watcher_, &QFutureWatcher<StatisticsExport>::finished, this,
          [this] { export_finished(export_watcher_.result()); });
  condition_chart_->set_chart(charts::Chart{}, tr("no scored trial yet"));
  detail_chart_->set_chart(charts::Chart{}, tr("no scored trial yet"));
}

StatisticsView::~StatisticsView() {
  // The workers hold only their own connections and copies; wait so none outlives the view.
  refresh_watcher_.waitForFinished();
  export_watcher_.waitForFinished();
}

void StatisticsView::set_store(const QString& store_location) {
  location_ = store_location;
  statistics_.reset();
  if (!file_watcher_->files().isEmpty()) file_watcher_->removePaths(file_watcher_->files());
  refresh();
}

const std::vector<PulseConditionSummary>& StatisticsView::pulse_rows() const {
  static const std::vector<PulseConditionSummary> none;
  return statistics_ ? statistics_->pulse : none;
}

const std::vector<SummaryRow>& StatisticsView::condition_rows() const {
  static const std::vector<SummaryRow> none;
  return statistics_ ? statistics_->by_condition.rows : none;
}

void StatisticsView::refresh() {
  if (location_.isEmpty()) return;
  if (running_) {
    pending_ = true;  // coalesced: one more refresh after the running one, however many asked
    return;
  }
  start_refresh();
}

void StatisticsView::start_refresh() {
  running_ = true;
  pending_ = false;
  status_->setText(tr("%1: refreshing…").arg(location_));
  refresh_watcher_.setFuture(QtConcurrent::run(compute, location_.toStdString()));
}

void StatisticsView::refresh_done() {
  running_ = false;
  const StatisticsRefresh r = refresh_watcher_.result();
  watch_store_files();
  if (r.statistics) {
    statistics_ = r.statistics;
    display(*statistics_);
  } else {
    status_->setText(tr("cannot read: %1").arg(r.error));
  }
  if (pending_) start_refresh();
  if (r.statistics)
    emit refreshed();
  else
    emit refresh_failed(r.error);
}

void StatisticsView::display(const TrialStatistics& s) {
  std::int64_t trials = 0;
  for (const SummaryRow& row : s.by_condition.rows) trials += row.trials;
  int pulse_trials = 0;
  for (const PulseConditionSummary& row : s.pulse) pulse_trials += row.trials;
  const QString pulse_text = counted(pulse_trials, "pulse-localisation trial", "pulse-localisation trials") + ", " +
                             counted(static_cast<long long>(s.pulse.size()), "condition", "conditions");
  if (pulse_only(s)) {
    status_->setText(tr("%1: %2 · %3").arg(location_, pulse_text, QDateTime::currentDateTime().toString("HH:mm:ss")));
  } else {
    status_->setText(tr("%1: %2, %3 (practice left out)%4 · %5")
                         .arg(location_)
                         .arg(counted(trials, "scored trial", "scored trials"))
                         .arg(counted(static_cast<long long>(s.by_condition.rows.size()), "condition", "conditions"))
                         .arg(s.pulse.empty() ? QString() : "; " + pulse_text)
                         .arg(QDateTime::currentDateTime().toString("HH:mm:ss")));
  }
  condition_chart_->set_chart(condition_chart(s), tr("no scored trial yet"));
  detail_chart_->set_chart(detail_chart(s), tr("no finger values or tumors scored yet"));
  fill_measures_table(*measures_table_, s);
  fill_comparisons_table(*comparisons_table_, s);
  fill_pulse_table(*pulse_table_, s.pulse, s.confidence);
  // A pulse-only store has nothing for the Se/Sp tables: the pulse table takes their room.
  const bool was_pulse_only = measures_table_->isHidden();
  pulse_table_->setVisible(!s.pulse.empty());
  measures_table_->setVisible(!pulse_only(s));
  comparisons_table_->setVisible(!pulse_only(s));
  if (pulse_only(s) != was_pulse_only) {
    tables_->setSizes(pulse_only(s) ? QList<int>{520, 0, 0, 230}
                                    : QList<int>{520, 230, 170, s.pulse.empty() ? 0 : 150});
  }
  for (auto* b : export_buttons_) b->setEnabled(!export_watcher_.isRunning() && !chart_export_pending_);
}

void StatisticsView::watch_store_files() {
  // Files only: a server store has nothing to watch (the console calls refresh() per trial).
  // Re-added after every refresh because a checkpoint may replace the WAL.
  for (const QString& f : {location_, location_ + "-wal"}) {
    if (QFileInfo::exists(f) && !file_watcher_->files().contains(f)) file_watcher_->addPath(f);
  }
}

void StatisticsView::ask_and_export(ExportKind kind) {
  QString dir = export_dir_;
  if (dir.isEmpty()) {
    dir = QFileDialog::getExistingDirectory(this, tr("Export into folder"), QFileInfo(location_).absolutePath());
    if (dir.isEmpty()) return;
  }
  export_to(kind, dir);
}

void StatisticsView::export_to(ExportKind kind, const QString& dir) {
  if (export_watcher_.isRunning() || chart_export_pending_) {
    emit export_failed(tr("an export is still running"));
    return;
  }
  for (auto* b : export_buttons_) b->setEnabled(false);
  status_->setText(tr("exporting to %1…").arg(dir));
  if (kind == ExportKind::chart_png || kind == ExportKind::chart_svg) {
    // Charts are drawn on the GUI thread (QCustomPlot is a widget), at the event loop's next turn.
    chart_export_pending_ = true;
    QTimer::singleShot(0, this, [this, kind, dir] {
      const StatisticsExport r =
          run_export(kind, location_.toStdString(), std::filesystem::path(dir.toStdString()), statistics_);
      chart_export_pending_ = false;
      export_finished(r);
    });
    return;
  }
  export_watcher_.setFuture(QtConcurrent::run(run_export, kind, location_.toStdString(),
                                              std::filesystem::path(dir.toStdString()), statistics_));
}

void StatisticsView::export_finished(const StatisticsExport& r) {
  for (auto* b : export_buttons_) b->setEnabled(statistics_ != nullptr);
  if (!r.error.isEmpty()) {
    status_->setText(tr("export refused: %1").arg(r.error));
    emit export_failed(r.error);
  } else {
    status_->setText(
        tr("exported %1 file(s) to %2").arg(r.files.size()).arg(QFileInfo(r.files.value(0)).absolutePath()));
    emit exported(r.files);
  }
}

}  // namespace palprig::gui
