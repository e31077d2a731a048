#pragma once
// SessionRun: the GUI's one adapter to sessions/study_session's run_study_session (and to
// sessions/pulse_study's run_pulse_study for pulse protocols), as LiveRun is to run_loop. The session runs on its own
// thread; what it reports (SessionListener calls, on that thread) is copied and handed to the GUI thread with queued
// calls, so the session thread never waits for the window. Pause, Resume and Abort reach the session loop through
// the window's RunControl, which it reads every pass.
#include <QObject>
#include <QString>
#include <atomic>
#include <memory>
#include <thread>

#include <functional>

#include "sessions/pulse_study.hpp"
#include "sessions/study_session.hpp"
#include "sessions/training_session.hpp"

namespace palprig::gui {

class SessionRun final : public QObject {
  Q_OBJECT
 public:
  // `control`: the window's operator handle (null: the run keeps its own).
  explicit SessionRun(RunControl* control = nullptr, QObject* parent = nullptr);
  ~SessionRun() override;  // aborts (vents) and joins a running session

  // Starts the session thread. `person` makes the GUI participant (null for sim:SEED).
  // A refusal (InputError) or a failure to open the rig arrives as refused().
  void start(const StudySessionRequest& request, PersonFactory person);
  // The same for a pulse-localisation protocol (run_pulse_study): started, runnerState (ready
  // while waiting for the participant or holding a pause), ended, refused and finished as above,
  // and the pulse trials as pulseTrialStarted / pulseTrialCommitted.
  void start_pulse(const StudySessionRequest& request, PulsePersonFactory person);
  // A trainee's next session (sessions/training_session's run_training_session, prepared on the
  // GUI thread so the participant screen knows its cases): the signals of start() or start_pulse()
  // as its level's task is, then trainingScored (a completed session) before finished.
  void start_training(const TrainingRequest& request, const PreparedTraining& prepared, PersonFactory person,
                      PulsePersonFactory pulse_person);
  bool running() const noexcept { return running_; }
  bool paused() const noexcept { return control_->paused(); }

  void pause();   // vents and holds the trial in progress
  void resume();  // presents the held trial again from its start
  void abort();   // vents; every committed trial is kept and the session stays resumable
  // Abort and wait for the session thread (it reads the stop flag every loop period).
  void abort_and_wait();

 signals:
  void started(const palprig::SessionStart& start);
  void trialStarted(int position, const palprig::PlannedTrial& trial, const palprig::Condition& condition);
  void runnerState(palprig::RunnerState state, int position);
  void trialCommitted(const palprig::TrialRecord& trial, int total);
  // The protocol asks for feedback: what the participant is told about the trial just committed.
  void participantFeedback(int position, const QString& text);
  void ended(const palprig::SessionEnd& end);
  void pulseTrialStarted(const palprig::PulseTrialStart& start, const palprig::PulseCondition& condition);
  void pulseTrialCommitted(const palprig::PulseTrialRecord& trial, int total);
  // A training session completed and was scored: its benchmark and the trainee's standing after.
  void trainingScored(const palprig::TrainingOutcome& outcome);
  void refused(const QString& line, int exit_code);  // the CLI's one line; 2 input, 1 rig
  void finished();                                   // after ended() or refused(): the thread is gone

 private:
  void join();
  // Starts the session thread running `session` (which throws InputError for a refusal).
  void launch(std::function<void()> session);

  std::thread thread_;
  RunControl own_control_;
  RunControl* control_;
  bool running_ = false;
  int generation_ = 0;  // GUI thread: which start() a queued end belongs to
};

}  // namespace palprig::gui
