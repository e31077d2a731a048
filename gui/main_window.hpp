#pragma once
// MainWindow: the palprig application window. One page per job in a QTabWidget ("Live rig",
// "Calibration", "Experiment", the study session console, and "Training", a course's trainees
// whose sessions run on the experiment console), a status bar with the
// loop's rate, overruns and wake-up latency, and the window-wide shortcuts (Esc is VENT).
// It owns the LiveRun; closing the window stops the loop, which vents every channel.
#include <QMainWindow>
#include <atomic>
#include <memory>

#include "gui/live_run.hpp"

class QLabel;
class QMessageBox;
class QShortcut;
class QTabWidget;
class QTimer;

namespace palprig::gui {

class CalibrationPage;
class ExperimentPage;
class LivePage;
class TrainingView;

class MainWindow final : public QMainWindow {
  Q_OBJECT
 public:
  MainWindow(std::unique_ptr<LiveRun> run, LiveRunFiles files, LiveRunOptions options, QWidget* parent = nullptr);
  ~MainWindow() override;

  LiveRun& run() noexcept { return *run_; }
  LivePage* live_page() const noexcept { return live_page_; }
  CalibrationPage* calibration_page() const noexcept { return calibration_page_; }
  ExperimentPage* experiment_page() const noexcept { return experiment_page_; }
  TrainingView* training_view() const noexcept { return training_view_; }
  // Closing during a study session asks first (the session is aborted, vented, and every
  // committed trial kept); scripted runs (screenshot, signals) close without asking.
  void set_close_without_asking(bool on) noexcept { close_without_asking_ = on; }
  QMessageBox* close_question() const noexcept { return close_question_; }
  QTabWidget* pages() const noexcept { return tabs_; }
  QLabel* status_text() const noexcept { return status_; }
  // Load other files (File menu). A refused file shows the same one line as the CLI in a
  // dialog and leaves the running rig as it was; returns false then.
  bool open_files(const LiveRunFiles& files);
  QMessageBox* last_refusal() const noexcept { return refusal_; }

 signals:
  void polled();  // after every poll (tests wait on it)

 protected:
  void closeEvent(QCloseEvent*) override;

 private:
  void poll();
  void build_live_page();
  void build_calibration_page();
  void build_experiment_page();
  void build_training_view();
  void choose_file(const QString& what, std::string LiveRunFiles::*field, const QString& filter);

  std::unique_ptr<LiveRun> run_;
  LiveRunFiles files_;
  LiveRunOptions options_;
  bool session_owns_rig_ = false;  // the live page follows a session's ticks
  QTabWidget* tabs_ = nullptr;
  LivePage* live_page_ = nullptr;
  CalibrationPage* calibration_page_ = nullptr;
  ExperimentPage* experiment_page_ = nullptr;
  TrainingView* training_view_ = nullptr;
  QShortcut* live_pause_ = nullptr;  // Space on the Live tab only (the participant's Space is Ready)
  bool close_without_asking_ = false;
  QMessageBox* close_question_ = nullptr;
  QLabel* status_ = nullptr;
  QTimer* timer_ = nullptr;
  QMessageBox* refusal_ = nullptr;
};

}  // namespace palprig::gui
