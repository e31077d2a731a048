#pragma once
// A threshold session (staircases, QUEST) end to end, as `palprig experiment run`
// starts it for a protocol with "task": "threshold": files checked, the rig opened, the session
// started or resumed (and held: one process per session) in the trial store, each trial
// committed with every track's state, the rig vented and closed. A person answers through the
// front end's ThresholdParticipant (the terminal's, experiments/terminal_threshold_participant);
// sim:SEED is the simulated threshold observer.
#include <functional>
#include <memory>
#include <vector>

#include "study/adaptive_track.hpp"
#include "experiments/threshold_observer.hpp"
#include "experiments/threshold_session.hpp"
#include "sessions/study_session.hpp"

namespace palprig {

struct ThresholdStudyRequest {
  StudySessionRequest session;      // protocol, participant, store, rig (required), calibration, resume, seed, speed
  ThresholdObserverModel observer;  // sim:SEED's noise and criterion; its seed comes from sim:SEED
};

struct ThresholdStart {
  SessionStart session;  // total_trials is 0: adaptive tracks end when they end
  ThresholdMethod method = ThresholdMethod::two_afc;
  int tracks = 0;
};

struct ThresholdEnd {
  SessionEnd session;  // total_trials is 0
  std::int64_t session_id = 0;
  std::vector<AdaptiveTrack> tracks;  // their estimates after the last trial
};

class ThresholdSessionListener {
 public:
  virtual ~ThresholdSessionListener() = default;
  virtual void session_started(const ThresholdStart&) {}
  virtual void trial_committed(const ThresholdTrialRecord&) {}
};

// Makes the person who answers once the method is known; not called for sim:SEED.
using ThresholdPersonFactory = std::function<std::unique_ptr<ThresholdParticipant>(ThresholdMethod)>;

// Throws InputError for refused input, before the rig moves (or when the store refuses).
ThresholdEnd run_threshold_study(const ThresholdStudyRequest& request, const ThresholdPersonFactory& person,
                                 ThresholdSessionListener& listener, const RunControl& control);

}  // namespace palprig
