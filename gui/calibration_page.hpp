#pragma once
// CalibrationPage: `palprig calibrate sweep` and `fit` in the window. The operator picks the
// channels and the staircase (from/to/step/repeats, the CLI's defaults), Start hands the rig
// over from the live loop (stopped and vented by the window) to a CalibrationJob on its own
// thread, the progress bar follows the sweep's progress callback, Stop vents and keeps what was
// recorded; the rig goes back to the live loop (vented) when the sweep ends. Fit calls
// fit_calibration as `calibrate fit` does and shows paper 002's fig. 8 table and the charts of
// gui/calibration_charts (branch lines; recorded hysteresis and the fitted model's loops).
// Save writes the file through calibration_writer (checked by the controller's own reader
// before it replaces anything); "Use in live rig" reloads the window with it. Evaluate runs
// `palprig calibrate evaluate`'s call (evaluate_compensation with its defaults) with the fitted
// file on a CalibrationJob: tracking errors and output-against-target loops without and with
// compensation (gui/calibration_charts' plot_evaluation). The Ceres fit runs on a worker
// (QtConcurrent) too, with the buttons disabled and the progress bar busy meanwhile.
#include <QFutureWatcher>
#include <QWidget>
#include <functional>
#include <memory>
#include <optional>

#include <QTemporaryDir>

#include "calibration/calibration_fit.hpp"
#include "calibration/compensation_evaluation.hpp"
#include "calibration/sweep_csv.hpp"
#include "formats/rig_file.hpp"
#include "gui/calibration_job.hpp"

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QScrollArea;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QTimer;
class QGridLayout;

namespace palprig::gui {

// One fit, made on a worker: the data read, the library's result and its charts as data (drawn
// on the GUI thread: QCustomPlot is a widget), or the library's refusal.
struct CalibrationFitOutcome {
  std::optional<SweepData> data;
  std::optional<CalibrationResult> result;
  std::vector<charts::NamedChart> charts;
  std::filesystem::path chart_dir;
  std::string error;
};

// What the page needs from the window that owns the rig.
struct CalibrationHost {
  std::function<RigConfig()> rig;  // the connected rig's configuration
  // The window's opened rig: a sweep or an evaluation leases it (the live loop gives way, and
  // starts again when the lease goes back).
  std::function<Rig&()> opened_rig;
  RunControl* control = nullptr;                            // the window's operator handle (Stop)
  std::function<bool(const std::string&)> use_calibration;  // reload the window with this file
  // Where the sweep data and the fitted file go unless the user chooses: beside the rig file
  // the user opened (the shipped rigs' folder is not the user's: the current directory then).
  std::function<std::filesystem::path()> output_folder;
};

class CalibrationPage final : public QWidget {
  Q_OBJECT
 public:
  explicit CalibrationPage(CalibrationHost host, QWidget* parent = nullptr);
  ~CalibrationPage() override;

  bool sweeping() const noexcept { return job_ != nullptr; }  // a sweep or an evaluation holds the rig
  bool fitting() const noexcept { return fit_watcher_.isRunning(); }
  void stop_sweep();  // VENT while calibrating: the runner vents every channel, data kept
  // The window is closing: stop and join the sweep now, before the backend goes; the rig is
  // not handed back.
  void cancel_sweep();
  const std::optional<CalibrationResult>& result() const noexcept { return result_; }
  const std::optional<EvaluationResult>& evaluation() const noexcept { return evaluation_; }
  QString data_path() const;  // the last sweep's data file
  // Where a file of the page goes by default: output_folder()/RIGID-SUFFIX, first free name.
  std::filesystem::path default_file(const std::string& suffix) const;

 signals:
  void sweep_finished();  // tests wait on these
  void fitted();
  void fit_finished();  // after fitted(), or after the library refused the fit
  void saved(const QString& path);
  void evaluation_finished();  // after the evaluation completed, stopped, faulted or was refused

 private:
  void start_sweep();
  void poll_job();
  void fit();
  void fit_done();
  void evaluate();
  void evaluation_done(const CalibrationJob& job);
  void set_busy(bool busy);
  void save();
  void show_table();
  void show_charts();
  void say(const QString& text, bool error = false);
  void show_shortfall();  // the staircase's fields make a sweep too short to fit: said now

  CalibrationHost host_;
  RunControl own_control_;  // when the host gives none
  RunControl& control() noexcept { return host_.control ? *host_.control : own_control_; }
  QTemporaryDir work_dir_;  // the chart PNGs shown on the page (the data and the fit go where the user says)
  std::unique_ptr<CalibrationJob> job_;
  std::optional<CalibrationResult> result_;
  std::optional<SweepData> data_;
  std::optional<EvaluationResult> evaluation_;
  std::vector<std::filesystem::path> fit_charts_, evaluation_charts_;
  QFutureWatcher<CalibrationFitOutcome> fit_watcher_;
  QCheckBox* channels_[3] = {};
  QDoubleSpinBox *from_ = nullptr, *to_ = nullptr, *step_ = nullptr;
  QSpinBox* repeats_ = nullptr;
  QPushButton *start_ = nullptr, *stop_ = nullptr, *fit_ = nullptr, *save_ = nullptr, *use_ = nullptr,
              *evaluate_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* status_ = nullptr;
  QTableWidget* table_ = nullptr;
  QGridLayout* charts_ = nullptr;
  QScrollArea* chart_scroll_ = nullptr;
  QLineEdit* save_path_ = nullptr;
  QLineEdit* sweep_path_ = nullptr;
  QLabel* shortfall_ = nullptr;
  QString sweep_file_;  // the data file of the last sweep started
  QTimer* timer_ = nullptr;
  QString saved_path_;
};

}  // namespace palprig::gui
