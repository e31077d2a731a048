#include "gui/training_view.hpp"

#include <QComboBox>
#include <QFileDialog>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>
#include <filesystem>

#include "charts/learning_charts.hpp"
#include "gui/chart_view.hpp"
#include "gui/counted_text.hpp"

namespace palprig::gui {

QString training_level_text(const Curriculum& c, int level) {
  if (level >= static_cast<int>(c.levels.size())) return "every level passed";
  return QString("level %1 of %2 '%3'")
      .arg(level + 1)
      .arg(c.levels.size())
      .arg(QString::fromStdString(c.levels[static_cast<std::size_t>(level)].name));
}

namespace {

QTableWidget* table(const QStringList& headers, const char* name) {
  auto* t = new QTableWidget(0, static_cast<int>(headers.size()));
  t->setObjectName(name);
  t->setHorizontalHeaderLabels(headers);
  t->verticalHeader()->setVisible(false);
  t->setEditTriggers(QAbstractItemView::NoEditTriggers);
  t->setSelectionBehavior(QAbstractItemView::SelectRows);
  t->setSelectionMode(QAbstractItemView::SingleSelection);
  t->horizontalHeader()->setStretchLastSection(true);
  return t;
}

}  // namespace

void TrainingView::set_row(QTableWidget* t, int row, const QStringList& cells) {
  for (int c = 0; c < cells.size(); ++c) t->setItem(row, c, new QTableWidgetItem(cells[c]));
}

TrainingView::TrainingView(TrainingHost host, QWidget* parent) : QWidget(parent), host_(std::move(host)) {
  setObjectName("training_view");
  auto* outer = new QVBoxLayout(this);
  outer->addWidget(build_form());
  auto* split = new QSplitter(Qt::Horizontal);
  split->addWidget(build_trainee_side());
  split->addWidget(build_charts());
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 3);
  split->setSizes({540, 740});  // the session table's eight columns without a scroll bar at 1280 px
  outer->addWidget(split, 1);
  set_buttons();
}

QWidget* TrainingView::build_form() {
  auto* box = new QGroupBox("Course");
  auto* grid = new QGridLayout(box);
  const auto file_row = [&](int row, const QString& label, QLineEdit*& edit, const char* name, const QString& filter) {
    edit = new QLineEdit;
    edit->setObjectName(name);
    auto* browse = new QPushButton("Browse...");
    grid->addWidget(new QLabel(label), row, 0);
    grid->addWidget(edit, row, 1);
    grid->addWidget(browse, row, 2);
    connect(edit, &QLineEdit::editingFinished, this, &TrainingView::reload);
    connect(browse, &QPushButton::clicked, this, [this, edit, label, filter] {
      const QString path = filter.isEmpty() ? QFileDialog::getSaveFileName(this, label, QString(), "", nullptr,
                                                                           QFileDialog::DontConfirmOverwrite)
                                            : QFileDialog::getOpenFileName(this, label, QString(), filter);
      if (path.isEmpty()) return;
      edit->setText(path);
      reload();
    });
  };
  file_row(0, "Curriculum", curriculum_edit_, "curriculum_file", "Curricula (*.json)");
  file_row(1, "Trial database", store_edit_, "training_store", "");
  store_edit_->setPlaceholderText("an SQLite file, or postgresql://user@host/db (the lab's store)");
  course_ = new QLabel;
  course_->setObjectName("course_summary");
  course_->setWordWrap(true);
  grid->addWidget(course_, 2, 0, 1, 3);
  return box;
}

QWidget* TrainingView::build_trainee_side() {
  auto* side = new QWidget;
  auto* v = new QVBoxLayout(side);
  v->setContentsMargins(0, 0, 0, 0);
  trainees_ = table({"Trainee", "Standing", "Sessions", "In a row"}, "trainee_table");
  trainees_->setMinimumHeight(120);
  connect(trainees_, &QTableWidget::itemSelectionChanged, this, &TrainingView::show_trainee);
  v->addWidget(trainees_, 2);
  auto* enrol_row = new QHBoxLayout;
  enrol_edit_ = new QLineEdit;
  enrol_edit_->setObjectName("enrol_code");
  enrol_edit_->setPlaceholderText("a new trainee's code (never their name)");
  enrol_ = new QPushButton("&Enrol");
  enrol_->setObjectName("enrol_trainee");
  connect(enrol_, &QPushButton::clicked, this, [this] { enrol(enrol_edit_->text().trimmed()); });
  connect(enrol_edit_, &QLineEdit::textChanged, this, &TrainingView::set_buttons);
  enrol_row->addWidget(enrol_edit_, 1);
  enrol_row->addWidget(enrol_);
  v->addLayout(enrol_row);
  standing_ = new QLabel("Pick a trainee.");
  standing_->setObjectName("trainee_standing");
  standing_->setWordWrap(true);
  v->addWidget(standing_);
  sessions_ =
      table({"#", "Level", "Cases", "Found", "False marks/case", "s/case", "Normal", "Benchmark"}, "session_table");
  sessions_->setSelectionMode(QAbstractItemView::NoSelection);
  sessions_->setMinimumHeight(120);
  v->addWidget(sessions_, 3);
  auto* start_row = new QHBoxLayout;
  participant_ = new QLineEdit;
  participant_->setObjectName("training_participant");
  participant_->setPlaceholderText("the trainee palpates; sim:SEED for a simulated pilot");
  start_row->addWidget(new QLabel("Participant"));
  start_row->addWidget(participant_, 1);
  start_ = new QPushButton("&Start next session");
  start_->setObjectName("start_training_session");
  connect(start_, &QPushButton::clicked, this, &TrainingView::start_next);
  start_row->addWidget(start_);
  v->addLayout(start_row);
  status_ = new QLabel;
  status_->setObjectName("training_status");
  status_->setWordWrap(true);
  v->addWidget(status_);
  return side;
}

QWidget* TrainingView::build_charts() {
  auto* side = new QWidget;
  auto* v = new QVBoxLayout(side);
  v->setContentsMargins(0, 0, 0, 0);
  measure_ = new QComboBox;
  measure_->setObjectName("learning_measure");
  measure_->addItem("Tumors found", static_cast<int>(charts::LearningMeasure::found));
  measure_->addItem("False marks per case", static_cast<int>(charts::LearningMeasure::false_marks));
  measure_->addItem("Seconds per case", static_cast<int>(charts::LearningMeasure::time_per_case));
  measure_->addItem("Normal cases called normal", static_cast<int>(charts::LearningMeasure::normal_called));
  chart_kind_ = new QComboBox;
  chart_kind_->setObjectName("cusum_kind");
  chart_kind_->addItem("LC-CUSUM (learning)", static_cast<int>(stats::CusumChart::learning));
  chart_kind_->addItem("CUSUM (monitoring)", static_cast<int>(stats::CusumChart::monitoring));
  for (QComboBox* box : {measure_, chart_kind_})
    connect(box, &QComboBox::currentIndexChanged, this, &TrainingView::show_charts);
  auto* top = new QHBoxLayout;
  top->addWidget(new QLabel("Learning curve"));
  top->addWidget(measure_, 1);
  v->addLayout(top);
  curve_ = new ChartView;
  curve_->setObjectName("learning_curve");
  curve_->setMinimumSize(360, 220);
  v->addWidget(curve_, 1);
  auto* bottom = new QHBoxLayout;
  bottom->addWidget(new QLabel("Over the cases"));
  bottom->addWidget(chart_kind_, 1);
  v->addLayout(bottom);
  cusum_ = new ChartView;
  cusum_->setObjectName("cusum_chart");
  cusum_->setMinimumSize(360, 220);
  v->addWidget(cusum_, 1);
  return side;
}

void TrainingView::set_files(const QString& curriculum, const QString& store) {
  curriculum_edit_->setText(curriculum);
  store_edit_->setText(store);
  reload();
}

QString TrainingView::selected_trainee() const {
  const auto rows = trainees_->selectionModel()->selectedRows();
  if (rows.isEmpty()) return {};
  return trainees_->item(rows.front().row(), 0)->text();
}

void TrainingView::refuse(const QString& line) {
  status_->setProperty("refusal", line);
  status_->setStyleSheet("color: #b00020");
  status_->setText("palprig: " + line);
}

QString TrainingView::refusal_text() const { return status_->property("refusal").toString(); }
QString TrainingView::standing_text() const { return standing_->text(); }

void TrainingView::reload() {
  const QString keep = selected_trainee();
  status_->setProperty("refusal", QString());
  status_->setStyleSheet("");
  status_->clear();
  curriculum_.reset();
  standings_.clear();
  {
    const QSignalBlocker quiet(trainees_);
    trainees_->setRowCount(0);
  }
  course_->clear();
  const std::string curriculum_file = curriculum_edit_->text().trimmed().toStdString();
  const std::string store = store_edit_->text().trimmed().toStdString();
  if (curriculum_file.empty()) {
    course_->setText("Choose a curriculum file (data/curricula/ has one to start from).");
    show_trainee();
    return;
  }
  try {
    curriculum_ = load_curriculum(curriculum_file);
    QStringList levels;
    for (const auto& l : curriculum_->levels) levels << QString::fromStdString(l.name);
    course_->setText(QString("'%1': %2 (%3)")
                         .arg(QString::fromStdString(curriculum_->name))
                         .arg(counted(static_cast<int>(curriculum_->levels.size()), "level", "levels"))
                         .arg(levels.join(", ")));
    // A store not made yet has no trainees: enrolling the first one creates it.
    if (!store.empty() && (is_server_store_location(store) || std::filesystem::exists(store)))
      standings_ = curriculum_standings(store, *curriculum_);
  } catch (const std::exception& e) {
    refuse(e.what());
  }
  {
    const QSignalBlocker quiet(trainees_);
    trainees_->setRowCount(static_cast<int>(standings_.size()));
    for (int row = 0; row < static_cast<int>(standings_.size()); ++row) {
      const TraineeStanding& t = standings_[static_cast<std::size_t>(row)];
      const QString run =
          t.standing.finished
              ? "-"
              : QString("%1 of %2")
                    .arg(t.standing.consecutive_met)
                    .arg(
                        curriculum_->levels[static_cast<std::size_t>(t.standing.level)].benchmark.consecutive_sessions);
      set_row(trainees_, row,
              {QString::fromStdString(t.trainee), training_level_text(*curriculum_, t.standing.level),
               QString::number(t.standing.sessions), run});
    }
    trainees_->resizeColumnsToContents();
  }
  if (!keep.isEmpty()) select_trainee(keep);
  show_trainee();
}

bool TrainingView::select_trainee(const QString& code) {
  for (int row = 0; row < trainees_->rowCount(); ++row) {
    if (trainees_->item(row, 0)->text() == code) {
      trainees_->selectRow(row);
      return true;
    }
  }
  return false;
}

bool TrainingView::enrol(const QString& code) {
  if (!curriculum_ || code.isEmpty()) {
    refuse(curriculum_ ? "enter the trainee's code" : "choose a curriculum file");
    return false;
  }
  const QString store = store_edit_->text().trimmed();
  if (store.isEmpty()) {
    refuse("choose the trial database (an SQLite file is created when missing)");
    return false;
  }
  try {
    enrol_trainee(store.toStdString(), *curriculum_, code.toStdString());
  } catch (const std::exception& e) {
    refuse(e.what());
    return false;
  }
  enrol_edit_->clear();
  reload();
  select_trainee(code);
  status_->setText(QString("%1 enrolled in '%2'.").arg(code, QString::fromStdString(curriculum_->name)));
  return true;
}

bool TrainingView::start_next() {
  const QString code = selected_trainee();
  if (!curriculum_ || code.isEmpty()) {
    refuse(curriculum_ ? "pick a trainee" : "choose a curriculum file");
    return false;
  }
  if (host_.session_running && host_.session_running()) {
    refuse("a session is running on the experiment console: it ends (or is aborted) first");
    return false;
  }
  TrainingRequest r;
  r.curriculum_file = curriculum_edit_->text().trimmed().toStdString();
  r.trainee = code.toStdString();
  r.store_location = store_edit_->text().trimmed().toStdString();
  r.participant = participant_->text().trimmed().toStdString();
  QString refusal, started;
  try {
    // Refused here: nothing stored, nothing moved. (Held where it is made, never moved: the
    // console copies what it needs into the session thread.)
    const PreparedTraining prepared = prepare_training_session(r);
    if (!host_.start || !host_.start(r, prepared, refusal)) {
      refuse(refusal.isEmpty() ? "the experiment console could not start the session" : refusal);
      return false;
    }
    started = QString("%1's session %2 at %3 runs on the Experiment tab (%4 cases).")
                  .arg(code)
                  .arg(prepared.plan.session_number)
                  .arg(training_level_text(*curriculum_, prepared.plan.level))
                  .arg(prepared.plan.cases.size());
  } catch (const std::exception& e) {
    refuse(e.what());
    return false;
  }
  status_->setProperty("refusal", QString());
  status_->setStyleSheet("");
  status_->setText(started);
  set_buttons();
  emit sessionStarted();
  return true;
}

void TrainingView::session_finished() {
  const QString status = status_->text();
  reload();
  if (refusal_text().isEmpty()) status_->setText(status);
}

void TrainingView::set_buttons() {
  const bool running = host_.session_running && host_.session_running();
  // A trainee who passed every level has no next session (`train next --level` runs one again).
  bool finished = false;
  for (const auto& t : standings_)
    if (QString::fromStdString(t.trainee) == selected_trainee()) finished = t.standing.finished;
  start_->setEnabled(curriculum_.has_value() && !selected_trainee().isEmpty() && !running && !finished);
  enrol_->setEnabled(curriculum_.has_value() && !enrol_edit_->text().trimmed().isEmpty());
}

}  // namespace palprig::gui
