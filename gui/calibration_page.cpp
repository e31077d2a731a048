#include "gui/calibration_page.hpp"
// About 400 lines: the page's widgets and their wiring (the runs themselves are in
// calibration_page_runs.cpp, the sweep/fit jobs in calibration_job.cpp).

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QTableWidget>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <cmath>

#include "core/error.hpp"
#include "calibration/calibration_report.hpp"
#include "calibration/calibration_writer.hpp"
#include "formats/calibration_file.hpp"
#include "charts/calibration_charts.hpp"
#include "calibration/sweep_plan.hpp"
#include "gui/free_file_name.hpp"
#include "gui/counted_text.hpp"

namespace palprig::gui {

namespace {

QDoubleSpinBox* kPa_box(double value, double lo, double hi, const char* name) {
  auto* b = new QDoubleSpinBox;
  b->setObjectName(name);
  b->setRange(lo, hi);
  b->setDecimals(1);
  b->setSuffix(" kPa");
  b->setValue(value);
  return b;
}

}  // namespace

CalibrationPage::CalibrationPage(CalibrationHost host, QWidget* parent) : QWidget(parent), host_(std::move(host)) {
  setObjectName("calibration_page");
  const SweepPlanOptions defaults;  // `palprig calibrate sweep`'s defaults

  auto* sweep_box = new QGroupBox("Sweep (paper 002 staircase)");
  auto* form = new QFormLayout(sweep_box);
  auto* channel_row = new QHBoxLayout;
  for (int c = 0; c < 3; ++c) {
    channels_[c] = new QCheckBox(QString::number(c + 1));
    channels_[c]->setObjectName(QString("cal_channel_%1").arg(c + 1));
    channels_[c]->setChecked(true);
    channel_row->addWidget(channels_[c]);
  }
  form->addRow("Channels", channel_row);
  form->addRow("From", from_ = kPa_box(defaults.from_kPa, 0, 1000, "cal_from"));
  form->addRow("To (clamped to p_max)", to_ = kPa_box(defaults.to_kPa, 0, 1000, "cal_to"));
  form->addRow("Step", step_ = kPa_box(defaults.step_kPa, 0.1, 1000, "cal_step"));
  repeats_ = new QSpinBox;
  repeats_->setObjectName("cal_repeats");
  repeats_->setRange(1, 100);
  repeats_->setValue(defaults.repeats);
  form->addRow("Repeats", repeats_);
  {
    sweep_path_ = new QLineEdit;
    sweep_path_->setObjectName("cal_sweep_path");
    sweep_path_->setPlaceholderText("beside the rig file");
    sweep_path_->setToolTip("The sweep's CSV (as `palprig calibrate sweep --out`); empty: beside the rig file");
    auto* browse = new QPushButton("...");
    browse->setMaximumWidth(32);
    connect(browse, &QPushButton::clicked, this, [this] {
      const QString p = QFileDialog::getSaveFileName(this, "Sweep data", sweep_path_->text(), "Sweep data (*.csv)");
      if (!p.isEmpty()) sweep_path_->setText(p);
    });
    auto* row = new QHBoxLayout;
    row->addWidget(sweep_path_, 1);
    row->addWidget(browse);
    form->addRow("Data file", row);
  }
  shortfall_ = new QLabel;
  shortfall_->setObjectName("cal_shortfall");
  shortfall_->setWordWrap(true);
  shortfall_->setStyleSheet("color: #9a5b00; font-weight: bold");
  shortfall_->hide();
  form->addRow(shortfall_);
  for (QDoubleSpinBox* box : {from_, to_, step_})
    connect(box, &QDoubleSpinBox::valueChanged, this, &CalibrationPage::show_shortfall);
  connect(repeats_, &QSpinBox::valueChanged, this, &CalibrationPage::show_shortfall);
  start_ = new QPushButton("Start sweep");
  start_->setObjectName("cal_start");
  stop_ = new QPushButton("Stop (vent, keep data)");
  stop_->setObjectName("cal_stop");
  stop_->setEnabled(false);
  auto* run_row = new QHBoxLayout;
  run_row->addWidget(start_);
  run_row->addWidget(stop_);
  form->addRow(run_row);
  progress_ = new QProgressBar;
  progress_->setObjectName("cal_progress");
  progress_->setRange(0, 1);
  progress_->setValue(0);
  progress_->setFormat("no sweep yet");
  form->addRow("Progress", progress_);

  auto* fit_box = new QGroupBox("Fit and save (as `palprig calibrate fit`)");
  auto* fit_form = new QFormLayout(fit_box);
  fit_ = new QPushButton("Fit");
  fit_->setObjectName("cal_fit");
  fit_->setEnabled(false);
  fit_form->addRow(fit_);
  save_path_ = new QLineEdit;
  save_path_->setObjectName("cal_save_path");
  save_path_->setPlaceholderText("beside the rig file");
  save_path_->setToolTip("The fitted calibration (JSON); empty: beside the rig file");
  auto* browse = new QPushButton("...");
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, "Save calibration", QString(), "Calibration files (*.json)");
    if (!p.isEmpty()) save_path_->setText(p);
  });
  auto* path_row = new QHBoxLayout;
  path_row->addWidget(save_path_, 1);
  path_row->addWidget(browse);
  fit_form->addRow("File", path_row);
  save_ = new QPushButton("Save");
  save_->setObjectName("cal_save");
  save_->setEnabled(false);
  use_ = new QPushButton("Use in live rig");
  use_->setObjectName("cal_use");
  use_->setEnabled(false);
  auto* save_row = new QHBoxLayout;
  save_row->addWidget(save_);
  save_row->addWidget(use_);
  fit_form->addRow(save_row);
  evaluate_ = new QPushButton("Evaluate (with / without compensation)");
  evaluate_->setObjectName("cal_evaluate");
  evaluate_->setEnabled(false);
  evaluate_->setToolTip(
      "palprig calibrate evaluate with the fitted file: the same test trajectory without and with "
      "the hysteresis compensation, RMS tracking error per channel");
  fit_form->addRow(evaluate_);

  status_ = new QLabel("Start runs the sweep on the connected rig; the live loop is vented meanwhile.");
  status_->setObjectName("cal_status");
  status_->setWordWrap(true);

  auto* left_panel = new QWidget;
  left_panel->setFixedWidth(360);
  auto* left = new QVBoxLayout(left_panel);
  left->setContentsMargins(0, 0, 0, 0);
  left->addWidget(sweep_box);
  left->addWidget(fit_box);
  left->addWidget(status_);
  left->addStretch(1);

  table_ = new QTableWidget(0, 10);
  table_->setObjectName("cal_table");
  table_->setHorizontalHeaderLabels(
      {"channel", "response", "branch", "n", "slope", "intercept", "R^2", "resid SD", "gap", "repeat SD %"});
  table_->verticalHeader()->hide();
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);

  auto* chart_host = new QWidget;
  charts_ = new QGridLayout(chart_host);
  auto* scroll = chart_scroll_ = new QScrollArea;
  scroll->setObjectName("cal_charts");
  scroll->setWidget(chart_host);
  scroll->setWidgetResizable(true);

  auto* right = new QVBoxLayout;
  right->addWidget(new QLabel("Fit table (paper 002 fig. 8 layout)"));
  right->addWidget(table_, 2);
  auto* chart_note = new QLabel(
      "Per channel: branch lines; recorded holds (the loop before compensation) and the "
      "fitted model's loops; after Evaluate, tracking error and output against target without "
      "and with compensation");
  chart_note->setWordWrap(true);  // unwrapped, its one line set the window's minimum width (1531 px)
  right->addWidget(chart_note);
  right->addWidget(scroll, 3);

  auto* layout = new QHBoxLayout(this);
  layout->addWidget(left_panel, 0);
  layout->addLayout(right, 1);

  timer_ = new QTimer(this);
  timer_->setInterval(50);
  connect(timer_, &QTimer::timeout, this, &CalibrationPage::poll_job);
  connect(start_, &QPushButton::clicked, this, &CalibrationPage::start_sweep);
  connect(stop_, &QPushButton::clicked, this, &CalibrationPage::stop_sweep);
  connect(fit_, &QPushButton::clicked, this, &CalibrationPage::fit);
  connect(&fit_watcher_, &QFutureWatcher<CalibrationFitOutcome>::finished, this, &CalibrationPage::fit_done);
  connect(evaluate_, &QPushButton::clicked, this, &CalibrationPage::evaluate);
  connect(save_, &QPushButton::clicked, this, &CalibrationPage::save);
  connect(use_, &QPushButton::clicked, this, [this] {
    if (host_.use_calibration(saved_path_.toStdString())) say("The live rig now uses " + saved_path_ + ".");
  });
}

CalibrationPage::~CalibrationPage() {
  cancel_sweep();
  fit_watcher_.waitForFinished();  // the fit touches only its own copies and the work folder
}

void CalibrationPage::cancel_sweep() {
  timer_->stop();
  job_.reset();  // stops (the runner vents every channel) and joins
}

QString CalibrationPage::data_path() const { return sweep_file_; }

std::filesystem::path CalibrationPage::default_file(const std::string& suffix) const {
  const std::filesystem::path folder = host_.output_folder ? host_.output_folder() : std::filesystem::current_path();
  return first_free_file(folder / (host_.rig().id + suffix));
}

void CalibrationPage::show_shortfall() {
  SweepPlanOptions plan_options;
  plan_options.from_kPa = from_->value();
  plan_options.to_kPa = to_->value();
  plan_options.step_kPa = step_->value();
  plan_options.repeats = repeats_->value();
  std::string why;
  try {
    why = sweep_fit_shortfall(plan_calibration_sweep(plan_options, host_.rig().safety.p_max_kPa));
  } catch (const std::exception&) {
    why.clear();  // Start names what is wrong with the fields
  }
  shortfall_->setText(why.empty() ? QString() : "This sweep is " + QString::fromStdString(why) + ".");
  shortfall_->setVisible(!why.empty());
}

void CalibrationPage::say(const QString& text, bool error) {
  status_->setText(text);
  status_->setStyleSheet(error ? "color: #b00000; font-weight: bold" : "");
}

void CalibrationPage::start_sweep() {
  if (job_) return;
  const RigConfig rig = host_.rig();
  SweepPlanOptions plan_options;
  plan_options.from_kPa = from_->value();
  plan_options.to_kPa = to_->value();
  plan_options.step_kPa = step_->value();
  plan_options.repeats = repeats_->value();
  SweepRunOptions run;
  bool any = false;
  for (int c = 0; c < 3; ++c) any |= (run.channels[c] = channels_[c]->isChecked());
  // As `calibrate sweep`: the simulated rig runs in simulated time, hardware in real time.
  run.realtime = rig.backend != "simulated";
  run.slew_kPa_per_s = rig.safety.slew_kPa_per_s;  // steps pass the safety stage at the rig's slew, as the CLI's
  SweepSchedule schedule;
  try {
    if (!any) throw BadInput("channels: at least one channel to sweep");
    schedule = plan_calibration_sweep(plan_options, rig.safety.p_max_kPa);  // refused before anything moves
  } catch (const std::exception& e) {
    say(QString("palprig: ") + e.what(), true);
    return;
  }
  result_.reset();
  data_.reset();
  evaluation_.reset();
  fit_->setEnabled(false);
  save_->setEnabled(false);
  use_->setEnabled(false);
  evaluate_->setEnabled(false);
  table_->setRowCount(0);
  // The data goes where the user said, else beside the rig file; an earlier sweep is never replaced.
  const QString chosen = sweep_path_->text().trimmed();
  if (!chosen.isEmpty() && std::filesystem::exists(chosen.toStdString())) {
    say("palprig: " + chosen + ": exists; choose a new file for the sweep data (an earlier sweep is never overwritten)",
        true);
    return;
  }
  sweep_file_ = chosen.isEmpty() ? QString::fromStdString(default_file("-sweep.csv").string()) : chosen;
  try {
    job_ = std::make_unique<CalibrationJob>(host_.opened_rig().lease("the calibration sweep"), control(), rig,
                                            std::move(schedule), run, data_path().toStdString());
  } catch (const std::exception& e) {  // RigBusy: something else holds the rig
    say(QString("palprig: ") + e.what(), true);
    return;
  }
  progress_->setFormat("%v of %m holds");
  progress_->setRange(0, int(job_->holds_total()));
  progress_->setValue(0);
  start_->setEnabled(false);
  stop_->setEnabled(true);
  say(QString("Sweeping on rig %1 (%2)...")
          .arg(QString::fromStdString(rig.id), run.realtime ? "real time" : "simulated time"));
  timer_->start();
}

void CalibrationPage::stop_sweep() {
  if (job_) job_->stop();
}

void CalibrationPage::poll_job() {
  if (!job_) return;
  if (!job_->is_evaluation()) progress_->setValue(int(job_->holds_done()));
  if (!job_->finished()) return;
  timer_->stop();
  std::unique_ptr<CalibrationJob> job = std::move(job_);
  if (job->is_evaluation()) {
    evaluation_done(*job);
    job.reset();  // joined, and its lease given back: the live loop starts again
    emit evaluation_finished();
    return;
  }
  const std::string error = job->error();
  const SweepOutcome o = job->recording().outcome;
  job.reset();  // joined, and its lease given back: the live loop starts again
  if (error.empty()) {
    progress_->setRange(0, int(o.holds_planned));
    progress_->setValue(int(o.holds_done));  // the last progress call may have come after the poll's read
  }
  start_->setEnabled(true);
  stop_->setEnabled(false);
  if (!error.empty()) {
    say(QString("palprig: ") + QString::fromStdString(error), true);
  } else {
    QString text = QString("%1 of %2 holds (%3 not settled) in %4 s of rig time -> %5")
                       .arg(o.holds_done)
                       .arg(o.holds_planned)
                       .arg(o.holds_unsettled)
                       .arg(o.duration_s, 0, 'f', 1)
                       .arg(data_path());
    if (o.stopped) text = "Stopped: every channel vented; kept " + text;
    if (o.faulted) text = "Fault: " + QString::fromStdString(o.fault) + "; every channel vented; kept " + text;
    say(text, o.faulted);
    fit_->setEnabled(o.holds_done > 0);
  }
  emit sweep_finished();
}

void CalibrationPage::show_table() {
  table_->setRowCount(0);
  auto rows = [this](const QString& who, const QString& response, const BranchFits& f) {
    const std::pair<const char*, const LineFit*> branches[] = {
        {"inflation", &f.inflation}, {"deflation", &f.deflation}, {"both", &f.both}};
    for (const auto& [name, line] : branches) {
      const int r = table_->rowCount();
      table_->insertRow(r);
      const QString cells[] = {who,
                               response,
                               name,
                               QString::number(line->n),
                               number_text(line->slope, 4),
                               number_text(line->intercept, 3),
                               number_text(line->r_squared, 4),
                               number_text(line->residual_sd, 3),
                               number_text(f.gap, 3),
                               number_text(f.repeat_sd_percent, 2)};
      for (int c = 0; c < 10; ++c) table_->setItem(r, c, new QTableWidgetItem(cells[c]));
    }
  };
  for (const ChannelCalibration& ch : result_->channels) {
    if (ch.regulator) rows(QString::number(ch.channel), "monitor", *ch.regulator);
    if (ch.response) rows(QString::number(ch.channel), QString::fromStdString(result_->sensor_name), *ch.response);
  }
  if (result_->pooled_regulator) rows("all", "monitor", *result_->pooled_regulator);
  if (result_->pooled_response) rows("all", QString::fromStdString(result_->sensor_name), *result_->pooled_response);
}

void CalibrationPage::show_charts() {
  while (QLayoutItem* item = charts_->takeAt(0)) {
    delete item->widget();
    delete item;
  }
  // Per channel one row: its regulator (and sensor) branch lines, then the hysteresis chart:
  // the recorded holds (the loop before compensation) with the fitted model's major and minor
  // loops (what the tick inverts). After an evaluation, one more row per channel: its tracking
  // error and its output-against-target loops without and with compensation.
  int row = -1, column = 0;
  std::string group;
  std::vector<std::filesystem::path> pngs = fit_charts_;
  pngs.insert(pngs.end(), evaluation_charts_.begin(), evaluation_charts_.end());
  for (const auto& png : pngs) {
    const std::string stem = png.stem().string();  // channel_N_regulator, evaluate_channel_N_loops, ...
    const std::string this_group = stem.substr(0, stem.rfind('_'));
    if (this_group != group) {
      group = this_group;
      ++row;
      column = 0;
    }
    auto* image = new QLabel;
    image->setObjectName(QString::fromStdString("cal_chart_" + stem));
    image->setPixmap(QPixmap(QString::fromStdString(png.string())).scaledToWidth(420, Qt::SmoothTransformation));
    charts_->addWidget(image, row, column++);
    image->show();  // at once, so a grab right after the fit has it
  }
}

void CalibrationPage::save() {
  if (!result_) return;
  QString path = save_path_->text().trimmed();
  if (path.isEmpty()) {  // beside the rig file, never over an earlier calibration
    path = QString::fromStdString(default_file("-calibration.json").string());
    save_path_->setText(path);
  }
  try {
    // The writer renames into place only after the controller's reader accepted the file.
    write_calibration_file(path.toStdString(), calibration_json(*result_));
  } catch (const std::exception& e) {
    say(QString("palprig: ") + e.what(), true);
    return;
  }
  saved_path_ = path;
  use_->setEnabled(true);
  say("Saved " + path + ".");
  emit saved(path);
}

}  // namespace palprig::gui
