#include "gui/main_window.hpp"
#include "gui/participant_screen.hpp"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QCloseEvent>
#include <QFileDialog>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QShortcut>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>

#include "gui/calibration_page.hpp"
#include "gui/experiment_page.hpp"
#include "gui/live_page.hpp"
#include "gui/rig_panel.hpp"
#include "core/input_error.hpp"
#include "gui/training_view.hpp"

namespace palprig::gui {

MainWindow::MainWindow(std::unique_ptr<LiveRun> run, LiveRunFiles files, LiveRunOptions options, QWidget* parent)
    : QMainWindow(parent), run_(std::move(run)), files_(std::move(files)), options_(std::move(options)) {
  setObjectName("main_window");
  tabs_ = new QTabWidget;
  setCentralWidget(tabs_);
  build_live_page();
  build_calibration_page();
  build_experiment_page();
  build_training_view();

  status_ = new QLabel;
  status_->setObjectName("loop_status");
  // A long line (a recording's path) is cut at the window's edge rather than widening the window.
  status_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  statusBar()->addPermanentWidget(status_, 1);

  QMenu* file = menuBar()->addMenu("&File");
  file->addAction("Open &scene...", this,
                  [this] { choose_file("scene", &LiveRunFiles::scene_path, "Scenes (*.json)"); });
  file->addAction("Open &rig...", this, [this] { choose_file("rig", &LiveRunFiles::rig_path, "Rig files (*.json)"); });
  file->addAction("Open &calibration...", this,
                  [this] { choose_file("calibration", &LiveRunFiles::cal_path, "Calibration files (*.json)"); });
  file->addSeparator();
  file->addAction("&Quit", QKeySequence::Quit, this, &QWidget::close);

  // Esc vents from anywhere in the window, whatever has the focus.
  auto* vent = new QShortcut(QKeySequence(Qt::Key_Escape), this);
  vent->setContext(Qt::ApplicationShortcut);
  connect(vent, &QShortcut::activated, this, [this] {
    if (calibration_page_->sweeping()) calibration_page_->stop_sweep();  // the sweep owns the rig
    if (experiment_page_->session_running()) experiment_page_->pause();  // vents, holds the trial
    live_page_->rig_panel()->vent_now();
  });
  live_pause_ = new QShortcut(QKeySequence(Qt::Key_Space), this);
  connect(live_pause_, &QShortcut::activated, this, [this] { live_page_->toggle_pause(); });
  connect(tabs_, &QTabWidget::currentChanged, this,
          [this] { live_pause_->setEnabled(tabs_->currentWidget() == live_page_); });
  auto* outlines = new QShortcut(QKeySequence(Qt::CTRL | Qt::Key_T), this);
  connect(outlines, &QShortcut::activated, this, [this] { live_page_->tumor_outlines()->toggle(); });

  timer_ = new QTimer(this);
  timer_->setInterval(16);  // 60 Hz display; the loop never waits for it
  connect(timer_, &QTimer::timeout, this, &MainWindow::poll);
  timer_->start();
  setWindowTitle(QString("palprig - %1").arg(QString::fromStdString(run_->setup().scene.name)));
  resize(1280, 860);
}

MainWindow::~MainWindow() {
  experiment_page_->abort_and_wait();  // the session vents and gives the rig back first
  calibration_page_->cancel_sweep();   // before the backend it borrowed goes with run_
  if (run_) run_->stop();
}

void MainWindow::build_calibration_page() {
  CalibrationHost host;
  host.rig = [this] { return run_->setup().rig; };
  // A sweep or an evaluation leases the window's rig: the live loop gives way, and the poll
  // starts it again when the lease goes back (controller/rig_lease.hpp).
  host.opened_rig = [this]() -> Rig& { return run_->rig(); };
  host.control = options_.control;
  host.output_folder = [this] {
    // Beside the rig file the user opened; the shipped rigs (the default simulated one) are
    // not the user's folder: the current directory then, as the command line writes there.
    std::error_code ec;
    const std::filesystem::path rig =
        files_.rig_path.empty() ? std::filesystem::path{} : std::filesystem::path(files_.rig_path);
    const auto shipped = std::filesystem::weakly_canonical(files_.data_dir / "rigs", ec);
    if (rig.empty() || std::filesystem::weakly_canonical(rig, ec).parent_path() == shipped)
      return std::filesystem::current_path(ec);
    return std::filesystem::absolute(rig, ec).parent_path();
  };
  host.use_calibration = [this](const std::string& path) {
    LiveRunFiles f = files_;
    f.cal_path = path;
    QWidget* current = tabs_->currentWidget();
    const bool ok = open_files(f);
    tabs_->setCurrentWidget(current);
    return ok;
  };
  calibration_page_ = new CalibrationPage(std::move(host));
  tabs_->addTab(calibration_page_, "Calibration");
}

void MainWindow::build_experiment_page() {
  ExperimentHost host;
  host.rig_file = [this] {
    return files_.rig_path.empty() ? files_.data_dir / "rigs" / "simulated.json"
                                   : std::filesystem::path(files_.rig_path);
  };
  host.calibration_file = [this] { return std::filesystem::path(files_.cal_path); };
  // A session leases the window's rig (the live loop gives way; the poll starts it again when
  // the lease goes back). The live loop is stopped while a session runs, so its feed has one
  // producer at a time; the LiveRun is not replaced during a session (choose_file refuses), so
  // the pointers stay valid.
  host.opened_rig = [this]() -> Rig& { return run_->rig(); };
  host.control = options_.control;
  host.tick_observer = [this]() -> TickObserver* { return &run_->feed(); };
  experiment_page_ = new ExperimentPage(std::move(host));
  tabs_->addTab(experiment_page_, "Experiment");
}

void MainWindow::build_training_view() {
  TrainingHost host;
  // The session runs on the experiment console, where the participant screen is; the window
  // shows it there.
  host.start = [this](const TrainingRequest& request, const PreparedTraining& prepared, QString& refusal) {
    if (!experiment_page_->begin_training(request, prepared)) {
      refusal = experiment_page_->refusal_text();
      return false;
    }
    tabs_->setCurrentWidget(experiment_page_);
    return true;
  };
  host.session_running = [this] { return experiment_page_->session_running(); };
  training_view_ = new TrainingView(std::move(host));
  connect(&experiment_page_->session_run(), &SessionRun::trainingScored, training_view_, &TrainingView::show_outcome);
  connect(experiment_page_, &ExperimentPage::trainingFinished, training_view_, &TrainingView::session_finished);
  tabs_->addTab(training_view_, "Training");
}

void MainWindow::build_live_page() {
  const int index = live_page_ ? tabs_->indexOf(live_page_) : -1;
  if (live_page_) {
    tabs_->removeTab(index);
    delete live_page_;
  }
  // The bundled phantom is the demo (its tumors shown); any other scene is a case to palpate.
  live_page_ = new LivePage(*run_, files_.scene_path.empty());
  // VENT during a session vents the session's rig: the session pauses (it vents and holds the
  // trial, as Esc does).
  connect(live_page_->rig_panel(), &RigPanel::vented, this, [this] {
    if (experiment_page_ && experiment_page_->session_running()) experiment_page_->pause();
  });
  tabs_->insertTab(std::max(index, 0), live_page_, "Live rig");
  tabs_->setCurrentWidget(live_page_);
}

void MainWindow::poll() {
  if (options_.control && options_.control->stop_signal() != 0) {
    close_without_asking_ = true;
    close();  // SIGINT/SIGTERM: the loop has vented on its own already
    return;
  }
  run_->poll_finished();
  // Whoever holds the rig: a session (the gauges and traces follow it, no Arm), a sweep or an
  // evaluation (the live page is idle), or the live loop, which starts again once the rig is free.
  run_->resume_when_free();
  const bool lent = run_->lent();
  const bool session_owns = lent && experiment_page_->session_running();
  if (session_owns != session_owns_rig_) {
    live_page_->set_session_owns_rig(session_owns);
    session_owns_rig_ = session_owns;
  }
  live_page_->setEnabled(!(lent && !session_owns));
  const FeedStatus st = live_page_->poll();
  if (experiment_page_->session_running()) {
    status_->setText(
        "study session running: it owns the rig (the live loop is stopped until it ends; the Live rig tab shows the "
        "session's pressures)");
    emit polled();
    return;
  }
  status_->setText(QString("loop %1 Hz   overruns %2   wake-up p50 %3 us  p99 %4 us   ticks %5%6%7")
                       .arg(st.loop_rate_hz, 0, 'f', 0)
                       .arg(st.overruns)
                       .arg(st.wake_p50_us, 0, 'f', 1)
                       .arg(st.wake_p99_us, 0, 'f', 1)
                       .arg(st.ticks)
                       .arg(st.dropped ? QString("   display dropped %1").arg(st.dropped) : QString())
                       .arg(run_->telemetry_file().empty()
                                ? QString()
                                : "   recording to " + QString::fromStdString(run_->telemetry_file().string())));
  emit polled();
}

bool MainWindow::open_files(const LiveRunFiles& files) {
  auto refuse = [this](const char* what) {
    delete refusal_;
    refusal_ = new QMessageBox(QMessageBox::Critical, "palprig", QString("palprig: ") + what, QMessageBox::Ok, this);
    refusal_->setObjectName("refusal_dialog");
    refusal_->open();  // window-modal, not exec(): the poll timer and the loop go on
  };
  LiveRunSetup setup;
  try {
    setup = load_live_run(files);  // refused here: nothing was stopped, nothing moves
  } catch (const std::exception& e) {
    refuse(e.what());
    return false;
  }
  bool opened = true;
  // The old rig vents and closes (and gives up its device) before the new one opens; the live
  // page refers to the old run, so it goes first.
  delete live_page_;
  live_page_ = nullptr;
  session_owns_rig_ = false;
  run_.reset();
  try {
    run_ = std::make_unique<LiveRun>(std::move(setup), options_);
  } catch (const std::exception& e) {
    refuse(e.what());  // the new rig did not open: back to the files that worked
    opened = false;
    run_ = std::make_unique<LiveRun>(load_live_run(files_), options_);
  }
  if (opened) files_ = files;
  build_live_page();
  setWindowTitle(QString("palprig - %1").arg(QString::fromStdString(run_->setup().scene.name)));
  return opened;
}

void MainWindow::choose_file(const QString& what, std::string LiveRunFiles::*field, const QString& filter) {
  if (experiment_page_->session_running()) {
    // Opening files restarts the live loop on a new backend: not while a session owns the rig.
    QMessageBox::information(
        this, "palprig",
        "A study session owns the rig: open the " + what + " after it ends (Abort keeps every committed trial).");
    return;
  }
  const QString path = QFileDialog::getOpenFileName(this, "Open " + what, QString(), filter);
  if (path.isEmpty()) return;
  LiveRunFiles f = files_;
  f.*field = path.toStdString();
  open_files(f);
}

void MainWindow::closeEvent(QCloseEvent* e) {
  if (experiment_page_->session_running()) {
    if (!close_without_asking_) {
      QMessageBox question(QMessageBox::Question, "palprig",
                           "A study session is running. Stop it and close? Every channel is vented; every committed "
                           "trial is kept and the session can be resumed.",
                           QMessageBox::Yes | QMessageBox::No, this);
      question.setObjectName("close_question");
      question.setDefaultButton(QMessageBox::No);
      close_question_ = &question;
      const int answer = question.exec();
      close_question_ = nullptr;
      if (answer != QMessageBox::Yes) {
        e->ignore();
        return;
      }
    }
    experiment_page_->abort_and_wait();  // vents, keeps what was committed
  }
  // A participant screen on its own display is a second top-level window: it comes back, or
  // the application would not end with the console's window.
  experiment_page_->participant_screen()->back_to_console();
  timer_->stop();
  calibration_page_->cancel_sweep();  // the runner vents every channel
  run_->stop();                       // the loop vents every channel as it ends
  e->accept();
}

}  // namespace palprig::gui
