#include "gui/session_run.hpp"

#include <QMetaObject>
#include <csignal>

#include "core/error.hpp"

namespace palprig::gui {

namespace {

// Runs on the session thread: copies each report and queues it to the GUI thread. Nothing
// here waits: invokeMethod with a queued connection only posts an event.
class QueuedListener final : public SessionListener {
 public:
  explicit QueuedListener(SessionRun* run) : run_(run) {}
  void session_started(const SessionStart& s) override {
    post([run = run_, s] { emit run->started(s); });
  }
  void runner_event(const RunnerEvent& e) override {
    if (e.kind != RunnerEvent::Kind::state_changed) return;
    post([run = run_, state = e.state, position = e.position] { emit run->runnerState(state, position); });
  }
  void trial_started(const PlannedTrial& trial, const Condition& condition) override {
    post([run = run_, trial, condition] { emit run->trialStarted(trial.position, trial, condition); });
  }
  void trial_committed(const TrialRecord& trial, int total) override {
    post([run = run_, trial, total] { emit run->trialCommitted(trial, total); });
  }
  void participant_feedback(int position, const std::string& text) override {
    post(
        [run = run_, position, text = QString::fromStdString(text)] { emit run->participantFeedback(position, text); });
  }
  void session_ended(const SessionEnd& end) override {
    post([run = run_, end] { emit run->ended(end); });
  }

 private:
  template <typename F>
  void post(F&& f) {
    QMetaObject::invokeMethod(run_, std::forward<F>(f), Qt::QueuedConnection);
  }
  SessionRun* run_;
};

// The pulse session's reports, queued the same way. Waiting (for the Ready or in a pause) is
// reported as the discrimination runner's `ready` state, so the console treats both alike.
class QueuedPulseListener final : public PulseSessionListener {
 public:
  explicit QueuedPulseListener(SessionRun* run) : run_(run) {}
  void session_started(const SessionStart& s) override {
    post([run = run_, s] { emit run->started(s); });
  }
  void trial_started(const PulseTrialStart& start, const PulseCondition& condition) override {
    post([run = run_, start, condition] {
      emit run->runnerState(RunnerState::present, start.position);
      emit run->pulseTrialStarted(start, condition);
    });
  }
  void waiting(int position, bool) override {
    post([run = run_, position] { emit run->runnerState(RunnerState::ready, position); });
  }
  void trial_committed(const PulseTrialRecord& trial, int total) override {
    post([run = run_, trial, total] { emit run->pulseTrialCommitted(trial, total); });
  }
  void session_ended(const SessionEnd& end) override {
    post([run = run_, end] { emit run->ended(end); });
  }

 private:
  template <typename F>
  void post(F&& f) {
    QMetaObject::invokeMethod(run_, std::forward<F>(f), Qt::QueuedConnection);
  }
  SessionRun* run_;
};

}  // namespace

SessionRun::SessionRun(RunControl* control, QObject* parent)
    : QObject(parent), control_(control ? control : &own_control_) {}

SessionRun::~SessionRun() { abort_and_wait(); }

void SessionRun::start(const StudySessionRequest& request, PersonFactory person) {
  launch([this, request, person = std::move(person)] {
    QueuedListener listener(this);
    run_study_session(request, person, listener, *control_);
  });
}

void SessionRun::start_pulse(const StudySessionRequest& request, PulsePersonFactory person) {
  launch([this, request, person = std::move(person)] {
    QueuedPulseListener listener(this);
    run_pulse_study(request, person, listener, *control_);
  });
}

void SessionRun::start_training(const TrainingRequest& request, const PreparedTraining& prepared, PersonFactory person,
                                PulsePersonFactory pulse_person) {
  launch([this, request, prepared, person = std::move(person), pulse_person = std::move(pulse_person)] {
    QueuedListener listener(this);
    QueuedPulseListener pulse_listener(this);
    TrainingFrontEnd front;
    front.person = person;
    front.pulse_person = pulse_person;
    front.listener = &listener;
    front.pulse_listener = &pulse_listener;
    const TrainingOutcome out = run_training_session(request, prepared, front, *control_);
    if (out.scored)
      QMetaObject::invokeMethod(
          this, [this, out] { emit trainingScored(out); }, Qt::QueuedConnection);
  });
}

void SessionRun::launch(std::function<void()> session) {
  abort_and_wait();
  control_->restart();
  control_->set_paused(false);
  running_ = true;
  const int generation = ++generation_;
  thread_ = std::thread([this, generation, session = std::move(session)] {
    QString refusal;
    int code = 0;
    try {
      session();
    } catch (const Error& e) {  // core/error.hpp: BadInput (InputError) 2, anything else of palprig's 1
      refusal = QString::fromStdString(e.what());
      code = e.exit_code();
    } catch (const std::exception& e) {
      refusal = QString::fromStdString(e.what());
      code = 1;
    }
    QMetaObject::invokeMethod(
        this,
        [this, generation, refusal, code] {
          if (generation != generation_) return;  // a session already waited for and replaced
          join();
          if (code != 0) emit refused(refusal, code);
          emit finished();
        },
        Qt::QueuedConnection);
  });
}

void SessionRun::pause() { control_->set_paused(true); }
void SessionRun::resume() { control_->set_paused(false); }
void SessionRun::abort() { control_->request_stop(); }

void SessionRun::abort_and_wait() {
  if (!thread_.joinable()) return;
  abort();
  join();
}

void SessionRun::join() {
  if (thread_.joinable()) thread_.join();
  running_ = false;
}

}  // namespace palprig::gui
