#pragma once
// TrainingView: the trainer's page of a training programme (the "Training" tab). A curriculum
// and a trial store; the trainees enrolled in it and where each stands (the same library calls
// as `palprig train status`), enrolling a trainee; for the trainee picked: their level, the
// benchmark of that level, their sessions, the learning curve of a chosen measure with the
// benchmark line of each session's level, and the LC-CUSUM or CUSUM chart over their cases (the
// charts `palprig stats learning --plot` writes, charts/learning_charts.hpp); and Start next
// session, which runs their next session at their present level (or continues the one they
// left) on the experiment console, where the participant screen is, as `palprig train next`
// would. Empty participant: the trainee palpates; sim:SEED: a simulated pilot trainee.
//
// The store is read on the GUI thread: a course's records are a few rows per session (a read
// takes milliseconds on an SQLite file); a session's trials are never read here.
#include <QString>
#include <QStringList>
#include <QWidget>
#include <functional>
#include <optional>
#include <vector>

#include "sessions/training_session.hpp"
#include "store/training_history.hpp"

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTableWidget;

namespace palprig::gui {

class ChartView;

// "level 2 of 3 'medium tumors'", or "every level passed".
QString training_level_text(const Curriculum& curriculum, int level);

// What the view needs from the window: the experiment console that runs the session.
struct TrainingHost {
  // Starts the prepared session; false when refused at once (`refusal` then holds the line).
  std::function<bool(const TrainingRequest&, const PreparedTraining&, QString& refusal)> start;
  std::function<bool()> session_running;
};

class TrainingView final : public QWidget {
  Q_OBJECT
 public:
  explicit TrainingView(TrainingHost host, QWidget* parent = nullptr);

  // Sets the curriculum file and the store and reads them (reload()).
  void set_files(const QString& curriculum, const QString& store);
  // Reads the curriculum and every trainee's standing again, keeping the trainee picked. A bad
  // curriculum or store is one line in the status (refusal_text()), nothing else shown.
  void reload();
  bool select_trainee(const QString& code);  // false: no such trainee in the list
  QString selected_trainee() const;
  // Enrols `code` (the store is created when missing) and selects them.
  bool enrol(const QString& code);
  // The selected trainee's next session on the experiment console; false when refused (the line
  // in refusal_text()).
  bool start_next();
  // A session of the view's completed and was scored: its scores and benchmark in the status.
  void show_outcome(const TrainingOutcome& outcome);
  // The session's thread ended (the console says so): the standings and charts are read again.
  void session_finished();

  QString refusal_text() const;
  QString standing_text() const;
  QTableWidget* trainee_table() const noexcept { return trainees_; }
  QTableWidget* session_table() const noexcept { return sessions_; }
  ChartView* curve_view() const noexcept { return curve_; }
  ChartView* cusum_view() const noexcept { return cusum_; }
  QComboBox* measure_box() const noexcept { return measure_; }
  QComboBox* chart_box() const noexcept { return chart_kind_; }
  QLineEdit* participant_edit() const noexcept { return participant_; }
  QPushButton* start_button() const noexcept { return start_; }

 signals:
  void sessionStarted();  // the console took the session (the window shows it)

 private:
  // One row of a table: its cells left to right (the trainee and session tables).
  static void set_row(QTableWidget* t, int row, const QStringList& cells);
  QWidget* build_form();
  QWidget* build_trainee_side();
  QWidget* build_charts();
  void show_trainee();  // the selected trainee's standing, sessions and charts
  void show_charts();
  void refuse(const QString& line);
  void set_buttons();

  TrainingHost host_;
  std::optional<Curriculum> curriculum_;
  std::vector<TraineeStanding> standings_;
  std::optional<TrainingCurves> curves_;

  QLineEdit* curriculum_edit_ = nullptr;
  QLineEdit* store_edit_ = nullptr;
  QLabel* course_ = nullptr;
  QTableWidget* trainees_ = nullptr;
  QLineEdit* enrol_edit_ = nullptr;
  QPushButton* enrol_ = nullptr;
  QLabel* standing_ = nullptr;
  QTableWidget* sessions_ = nullptr;
  QLineEdit* participant_ = nullptr;
  QPushButton* start_ = nullptr;
  QLabel* status_ = nullptr;
  QComboBox* measure_ = nullptr;
  QComboBox* chart_kind_ = nullptr;
  ChartView* curve_ = nullptr;
  ChartView* cusum_ = nullptr;
};

}  // namespace palprig::gui
