// CalibrationPage, the parts that run off the GUI thread: the fit (QtConcurrent) and the
// compensation evaluation (a CalibrationJob on the lent backend), with the page's busy state.
#include <QLabel>
#include <QMetaObject>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <cmath>

#include "core/error.hpp"
#include "calibration/calibration_report.hpp"
#include "calibration/calibration_writer.hpp"
#include "formats/calibration_file.hpp"
#include "charts/calibration_charts.hpp"
#include "gui/calibration_page.hpp"
#include "gui/counted_text.hpp"

namespace palprig::gui {

void CalibrationPage::fit() {
  if (job_ || fit_watcher_.isRunning()) return;
  // The same calls as `palprig calibrate fit DATA` with its defaults (paper 002's base models),
  // and the charts drawn, on a worker: Ceres on a long staircase is not for the GUI thread.
  const std::string data_file = data_path().toStdString();
  const std::filesystem::path dir = work_dir_.filePath("charts").toStdString();
  set_busy(true);
  say("Fitting (Ceres, on a worker thread)...");
  fit_watcher_.setFuture(QtConcurrent::run([data_file, dir] {
    CalibrationFitOutcome o;
    try {
      CalibrationFitOptions options;
      options.date = utc_timestamp_now();
      o.data = read_sweep_csv(data_file);
      o.result = fit_calibration(*o.data, options);
      std::filesystem::remove_all(dir);
      o.charts = charts::fit_charts(*o.data, *o.result);
      o.chart_dir = dir;
    } catch (const std::exception& e) {
      o = CalibrationFitOutcome{};
      o.error = e.what();
    }
    return o;
  }));
}

void CalibrationPage::fit_done() {
  CalibrationFitOutcome o = fit_watcher_.result();
  set_busy(false);
  evaluation_.reset();
  evaluation_charts_.clear();
  saved_path_.clear();  // a new fit is not the file saved before
  use_->setEnabled(false);
  if (!o.error.empty()) {
    result_.reset();
    save_->setEnabled(false);
    evaluate_->setEnabled(false);
    say(QString("palprig: ") + QString::fromStdString(o.error), true);
    emit fit_finished();
    return;
  }
  data_ = std::move(o.data);
  result_ = std::move(o.result);
  try {
    fit_charts_ = charts::write_charts(o.chart_dir, o.charts);
  } catch (const std::exception& e) {
    fit_charts_.clear();
    say(QString("palprig: charts not drawn: ") + QString::fromStdString(e.what()), true);
  }
  show_table();
  show_charts();
  save_->setEnabled(true);
  evaluate_->setEnabled(true);
  QStringList notes;
  for (const auto& n : result_->notes) notes << QString::fromStdString(n);
  say("Fitted." + (notes.isEmpty() ? QString() : " " + notes.join("; ")));
  emit fitted();
  emit fit_finished();
}

void CalibrationPage::set_busy(bool busy) {
  // While the fit or the evaluation runs nothing else may start; the progress bar says "busy".
  static const char* kBusyKeep = "enabled_before_busy";
  for (QPushButton* b : {start_, fit_, save_, use_, evaluate_}) {
    if (busy) {
      b->setProperty(kBusyKeep, b->isEnabled());
      b->setEnabled(false);
    } else {
      b->setEnabled(b->property(kBusyKeep).toBool());
    }
  }
  if (busy) {
    progress_->setProperty("range_before_busy", progress_->maximum());
    progress_->setProperty("value_before_busy", progress_->value());
    progress_->setRange(0, 0);
  } else {
    progress_->setRange(0, progress_->property("range_before_busy").toInt());
    progress_->setValue(progress_->property("value_before_busy").toInt());
  }
}

void CalibrationPage::evaluate() {
  if (!result_ || job_ || fit_watcher_.isRunning()) return;
  const RigConfig rig = host_.rig();
  // The file `calibrate evaluate --cal FILE` would read: the one saved, else this fit written
  // through the same writer into the page's work folder.
  const QString cal_path = !saved_path_.isEmpty() ? saved_path_ : work_dir_.filePath("fitted_calibration.json");
  CalibrationModels cal;
  EvaluationOptions options;  // `calibrate evaluate`'s defaults
  try {
    if (saved_path_.isEmpty()) write_calibration_file(cal_path.toStdString(), calibration_json(*result_));
    cal = load_calibration_file(cal_path.toStdString());
    check_calibration_matches(cal, rig.id, rig.source);
    bool any = false;
    for (std::size_t c = 0; c < kFingerCount; ++c) any |= (options.channels[c] = !cal.hysteresis[c].is_identity());
    if (!any) throw BadInput("calibration: a hysteresis model on at least one channel to evaluate");
  } catch (const std::exception& e) {
    say(QString("palprig: ") + e.what(), true);
    return;
  }
  options.realtime = rig.backend != "simulated";  // as `calibrate evaluate`: hardware in real time
  evaluation_.reset();
  evaluation_charts_.clear();
  const std::filesystem::path dir = work_dir_.filePath("evaluation").toStdString();
  std::filesystem::remove_all(dir);
  try {
    job_ = std::make_unique<CalibrationJob>(host_.opened_rig().lease("the compensation evaluation"), control(), rig,
                                            std::move(cal), options, dir);
  } catch (const std::exception& e) {  // RigBusy: something else holds the rig
    say(QString("palprig: ") + e.what(), true);
    return;
  }
  set_busy(true);
  stop_->setEnabled(true);
  say(QString("Evaluating %1 on rig %2 (%3): the test trajectory without, then with compensation...")
          .arg(cal_path, QString::fromStdString(rig.id), options.realtime ? "real time" : "simulated time"));
  timer_->start();
}

void CalibrationPage::evaluation_done(const CalibrationJob& job) {
  set_busy(false);
  stop_->setEnabled(false);
  if (!job.error().empty()) {
    say(QString("palprig: ") + QString::fromStdString(job.error()), true);
    return;
  }
  evaluation_ = job.evaluation();
  try {
    evaluation_charts_ = charts::write_charts(job.chart_dir(), job.evaluation_charts());
  } catch (const std::exception& e) {
    evaluation_charts_.clear();
    say(QString("palprig: charts not drawn: ") + QString::fromStdString(e.what()), true);
  }
  const EvaluationResult& r = *evaluation_;
  QStringList lines;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!job.evaluated_channels()[c]) continue;
    lines << QString("channel %1: RMS %2 -> %3 kPa (%4x), gap %5 -> %6 kPa")
                 .arg(c + 1)
                 .arg(number_text(r.uncompensated.channels[c].rms_error_kPa, 3),
                      number_text(r.compensated.channels[c].rms_error_kPa, 3), number_text(r.improvement[c], 1),
                      number_text(r.uncompensated.channels[c].gap_kPa, 2),
                      number_text(r.compensated.channels[c].gap_kPa, 2));
  }
  QString text = "Evaluated (as `palprig calibrate evaluate`): " + lines.join("; ") + ".";
  const EvaluationRun& bad = r.uncompensated.stopped || r.uncompensated.faulted ? r.uncompensated : r.compensated;
  if (bad.faulted)
    text = "Fault: " + QString::fromStdString(bad.fault) + "; every channel vented. " + text;
  else if (bad.stopped)
    text = "Stopped: every channel vented. " + text;
  say(text, bad.faulted);
  show_charts();
  // Bring the new charts into view once the layout has placed them (queued after its request).
  if (!evaluation_charts_.empty()) {
    const QString first = QString::fromStdString("cal_chart_" + evaluation_charts_.front().stem().string());
    QMetaObject::invokeMethod(
        this,
        [this, first] {
          if (auto* chart = findChild<QLabel*>(first)) chart_scroll_->ensureWidgetVisible(chart, 0, 0);
        },
        Qt::QueuedConnection);
  }
}

}  // namespace palprig::gui
