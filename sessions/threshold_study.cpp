#include "sessions/threshold_study.hpp"

#include <cstdio>

#include "experiments/rig_stimulus.hpp"
#include "core/input_error.hpp"
#include "sessions/session_setup.hpp"
#include "sessions/session_telemetry.hpp"
#include "sessions/study_rig.hpp"
#include "sessions/threshold_setup.hpp"
#include "store/threshold_store.hpp"

namespace palprig {

namespace {

std::string one_decimal(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f", x);
  return buf;
}

}  // namespace

ThresholdEnd run_threshold_study(const ThresholdStudyRequest& request, const ThresholdPersonFactory& person,
                                 ThresholdSessionListener& listener, const RunControl& control) {
  const StudySessionRequest& r = request.session;
  refuse_server_store_for_task_session(r.store_location);
  const ThresholdProtocol from_file = load_threshold_protocol(r.protocol_file);
  std::uint64_t sim_seed = 0;
  const bool simulated = simulated_participant(r.participant_code, sim_seed);
  if (!simulated && !person)
    throw InputError("command line", "participant", "sim:SEED (this front end cannot ask a person)");
  StudyRig rig = load_study_rig(r.rig_file, r.calibration_file);
  if (!r.telemetry_file.empty()) refuse_unusable_telemetry_file(r.telemetry_file);
  if (from_file.max_pressure_kPa() > rig.rig.safety.p_max_kPa) {
    throw InputError(from_file.source, "threshold.reference_kPa",
                     "reference + the largest track level at or below the rig's p_max of " +
                         one_decimal(rig.rig.safety.p_max_kPa) + " kPa (" + rig.rig.source + "), got " +
                         one_decimal(from_file.max_pressure_kPa()));
  }
  refuse_speed_on_hardware(rig, r.speed);
  rig.take(r.rig, "threshold session");  // before the session is stored: an unreachable device leaves no empty session

  SqliteTrialStore store(r.store_location, TrialStore::Access::read_write);
  ThresholdObserverModel model = request.observer;
  model.seed = sim_seed;
  ThresholdSessionRequest opening;
  opening.participant_code = r.participant_code;
  opening.simulated = simulated;
  opening.resume = r.resume;
  opening.seed = r.seed;
  opening.setup = {rig.rig.id, rig.rig.backend, rig.cal.source, simulated ? to_json(model) : nlohmann::json(nullptr),
                   std::filesystem::absolute(r.protocol_file).parent_path().string()};
  OpenedThresholdSession session = open_threshold_session(store, from_file, opening);
  ThresholdStore threshold_store(store);

  std::unique_ptr<ThresholdParticipant> participant;
  if (simulated) {
    model.seed = resumed_simulation_seed(session_simulation_seed(sim_seed, session.ordinal), session.start_position);
    participant = std::make_unique<SimulatedThresholdObserver>(model);
  } else {
    participant = person(session.protocol.method);
  }
  const std::unique_ptr<SessionClock> clock = session_clock(rig, simulated, r.speed);
  listener.session_started(ThresholdStart{
      SessionStart{session.protocol.name, session.participant, session.session_id, session.resumed,
                   session.start_position, 0, session.seed, simulated, rig.hardware(), 0, clock->steady_origin()},
      session.protocol.method, static_cast<int>(session.tracks.size())});

  RigStimulus output(rig.config, rig.backend());
  output.observe_with(r.tick_observer);
  SessionTelemetry telemetry(r.telemetry_file, output, *clock);
  ThresholdSessionOptions options;
  options.seed = session.seed;
  options.start_position = session.start_position;
  options.control = &control;
  int committed = 0;
  options.on_trial = [&](const ThresholdTrialRecord& t) {
    threshold_store.commit_trial(session.session_id, t);  // committed before anyone is told
    ++committed;
    listener.trial_committed(t);
  };
  const ThresholdSessionResult result =
      run_threshold_session(session.protocol, session.tracks, output, *participant, *clock, options);
  rig.vent();

  ThresholdEnd end;
  end.session.completed = result.completed;
  end.session.stopped = result.stopped;
  end.session.fault = result.fault;
  if (!result.fault.empty())
    end.session.fault_record = save_session_fault_record(
        output, "threshold session " + std::to_string(session.session_id) + " of " + r.participant_code,
        r.telemetry_file, r.store_location);
  telemetry.finish(end.session);
  end.session.committed_trials = session.start_position + committed;
  end.session_id = session.session_id;
  if (result.completed) store.complete_session(session.session_id);
  end.tracks = std::move(session.tracks);
  return end;
}

}  // namespace palprig
