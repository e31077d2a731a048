#pragma once
// ExperimentPage: the experimenter's console for a study session (the "Experiment" tab).
// Protocol, participant code and trial database; the planned order before Begin (the same
// library call as `palprig experiment plan`, or the stored order of a session to resume);
// Begin, Pause (vents, holds the trial), Resume, Abort (vents, keeps what was committed); the
// offer to resume this participant's unfinished session at the exact trial, as `--resume`;
// pilot runs with the simulated participant (sim:SEED) at a chosen speed; a trial list ticked
// as each trial is committed; the participant screen (which can go full screen on a second
// display); the files written, listed at the end. The session itself is run_study_session on
// SessionRun's thread: the same code as `palprig experiment run`. A pulse-localisation protocol
// ("task": "pulse") runs run_pulse_study the same way, with its own plan, rows and marking
// screen (experiment_page_pulse.cpp).
#include <QWidget>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "study/protocol.hpp"
#include "experiments/pulse_session.hpp"
#include "study/session_plan.hpp"
#include "gui/gui_participant.hpp"
#include "gui/session_run.hpp"

class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTabWidget;
class QTableWidget;
class QVBoxLayout;

namespace palprig::gui {

class ParticipantScreen;
class StatisticsView;

// What the page needs from the window: the rig it is on and the window's opened rig, which a
// session leases for its length (the live loop gives way, vented, and starts again after), and
// the window's operator handle (Pause, Abort).
struct ExperimentHost {
  std::function<std::filesystem::path()> rig_file;
  std::function<std::filesystem::path()> calibration_file;  // empty: paper 002's models
  std::function<Rig&()> opened_rig;                         // none: the session opens rig_file itself
  RunControl* control = nullptr;                            // null: the page keeps its own
  // Where the session's rig ticks go for the live view (the live page's feed); null: nowhere.
  std::function<TickObserver*()> tick_observer;
};

struct ExperimentFields {
  std::string protocol, participant, store;
  double speed = 0;            // simulated participant only (0: as fast as the simulated rig allows)
  std::string telemetry = {};  // the session's rig ticks to this new file (.bin or .csv); empty: none
};

class ParticipantKeys;

class ExperimentPage final : public QWidget {
  Q_OBJECT
 public:
  explicit ExperimentPage(ExperimentHost host, QWidget* parent = nullptr);
  ~ExperimentPage() override;

  void set_fields(const ExperimentFields& fields);  // and shows the plan / resume offer
  ExperimentFields fields() const;
  // Begin (resume=false) or resume the unfinished session. False when refused at once (the
  // line is in refusal_text()); a refusal from the session thread comes as sessionRefused.
  bool begin(bool resume);
  // A trainee's next session of a curriculum (the Training view's Start next session): the
  // participant screen set up with its cases, then run as begin() runs a protocol, scored at its
  // end (experiment_page_training.cpp). request.participant: empty for the trainee themself (a
  // person), sim:SEED for a simulated pilot. False when refused at once (refusal_text()).
  bool begin_training(const TrainingRequest& request, const PreparedTraining& prepared);
  bool training_running() const noexcept { return training_ && run_.running(); }
  void pause();
  void resume();
  void abort();
  // The Abort button: asks first (a window-modal "End the session?" box, objectName
  // "abort_confirmation"); Yes aborts.
  void ask_abort();
  // Abort and wait for the session thread; every committed trial is kept (the session's lease
  // on the rig goes back as it ends).
  void abort_and_wait();

  bool session_running() const noexcept { return run_.running(); }
  bool resume_offered() const noexcept { return offered_session_.has_value(); }
  int offered_start_position() const noexcept { return offered_start_; }
  QString refusal_text() const;
  QStringList files_written() const { return files_written_; }
  ParticipantScreen* participant_screen() const noexcept { return screen_; }
  QTableWidget* trial_table() const noexcept { return table_; }
  // While a person's session runs with the participant screen in this window (one display),
  // the trial list hides the answer key (stimulus, tumor, score; a pulse trial's distance and
  // hit) unless the experimenter shows it with this button (objectName "show_answer_key").
  bool answer_key_hidden() const noexcept { return answer_key_hidden_; }
  QPushButton* show_answer_key_button() const noexcept { return show_key_; }
  // The live statistics of the session's store (gui/statistics_view), refreshed on every commit.
  StatisticsView* statistics() const noexcept { return statistics_; }
  void show_statistics();  // brings the Statistics tab to the front
  SessionRun& session_run() noexcept { return run_; }
  // The pulse protocol chosen (null for the other tasks).
  const PulseProtocol* pulse_protocol() const noexcept { return pulse_protocol_ ? &*pulse_protocol_ : nullptr; }

 signals:
  void sessionStarted();
  void trialCommitted(int position);
  void sessionEnded(const palprig::SessionEnd& end);
  void sessionRefused(const QString& line, int exit_code);
  // A training session's thread has ended (completed and scored, stopped, faulted or refused).
  void trainingFinished();

 private:
  // The trial table's columns. kResponseTime: from onset (paper 002's measure, its t-test); kRtAfterStimulus: from the
  // end of the stimulus (what the participant was asked to answer after). kCommitted stays last.
  enum Column {
    kPosition,
    kBlock,
    kCondition,
    kStimulus,
    kTumor,
    kAnswer,
    kScore,
    kResponseTime,
    kRtAfterStimulus,
    kConfidence,
    kCommitted,
    kColumns
  };

  // The widgets (experiment_page_layout.cpp).
  QWidget* build_session_form();
  void build_session_controls(QVBoxLayout* left_layout);
  QWidget* build_trial_list();
  QWidget* build_participant_side();
  void connect_session();  // the session run's signals to the page
  void update_plan();      // the planned order (or stored order) and the resume offer
  void show_plan(const Protocol& protocol, const SessionPlan& plan);
  void tick_row(const TrialRecord& trial);
  void refuse(const QString& line);
  void set_buttons();
  void show_files();
  void on_started(const SessionStart& s);
  void on_ended(const SessionEnd& e);
  // Pulse localisation (experiment_page_pulse.cpp).
  void set_table_columns(bool pulse);
  bool update_pulse_plan(const ExperimentFields& f);  // false: not a pulse protocol
  void show_pulse_order(const PulseProtocol& protocol, const std::vector<int>& order);
  void tick_pulse_row(const PulseTrialRecord& trial);
  void start_pulse_run(const StudySessionRequest& request);
  void connect_pulse();
  std::vector<int> answer_key_columns() const;  // of the table's current task (experiment_page_pulse.cpp)
  void apply_answer_key();                      // hides or shows those columns for the state above
  // A session has just started (begin() or a trainee's session): the participant's keys on a
  // person's session, the key hidden from them (their own display when there is a second one).
  void session_started_for_participant();

  ExperimentHost host_;
  SessionRun run_;
  std::shared_ptr<ParticipantChannel> channel_;
  std::optional<Protocol> protocol_;
  std::optional<PulseProtocol> pulse_protocol_;
  std::optional<std::int64_t> offered_session_;
  int offered_start_ = 0;
  bool simulated_ = false;
  bool pause_held_ = false;
  bool person_session_ = false;  // a person (not sim:SEED) answers in the session running
  bool training_ = false;        // the session running is a trainee's (begin_training)
  bool answer_key_hidden_ = false;
  bool last_completed_ =
      false;  // the last session ended completed  // the session loop reported the pause (vented, holding)
  QStringList files_written_;  // the database first, then exports
  QString store_note_;

  QLineEdit* protocol_edit_ = nullptr;
  QLineEdit* participant_edit_ = nullptr;
  QLineEdit* store_edit_ = nullptr;
  QLineEdit* telemetry_edit_ = nullptr;
  QDoubleSpinBox* speed_ = nullptr;
  QLabel* plan_note_ = nullptr;
  QLabel* resume_note_ = nullptr;
  QPushButton* begin_ = nullptr;
  QPushButton* resume_session_ = nullptr;
  QPushButton* pause_ = nullptr;
  QPushButton* continue_ = nullptr;
  QPushButton* abort_ = nullptr;
  ParticipantKeys* participant_keys_ = nullptr;  // installed while a person's session runs
  QPushButton* full_screen_ = nullptr;
  QPushButton* show_key_ = nullptr;
  QLabel* status_ = nullptr;
  QLabel* files_ = nullptr;
  QTableWidget* table_ = nullptr;
  ParticipantScreen* screen_ = nullptr;
  QWidget* statistics_area_ = nullptr;
  QTabWidget* results_ = nullptr;
  StatisticsView* statistics_ = nullptr;
  QVBoxLayout* statistics_layout_ = nullptr;
};

}  // namespace palprig::gui
