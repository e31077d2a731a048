#include "sessions/pulse_study.hpp"

#include "experiments/rig_stimulus.hpp"
#include "experiments/simulated_pulse_observer.hpp"
#include "formats/scene_file.hpp"
#include "core/input_error.hpp"
#include "sessions/pulse_setup.hpp"
#include "sessions/session_telemetry.hpp"
#include "sessions/session_setup.hpp"
#include "sessions/study_rig.hpp"

namespace palprig {

SessionEnd run_pulse_study(const StudySessionRequest& r, const PulsePersonFactory& person,
                           PulseSessionListener& listener, const RunControl& control) {
  refuse_server_store_for_task_session(r.store_location);
  const PulseProtocol from_file =
      r.protocol_document
          ? parse_pulse_protocol(*r.protocol_document, r.protocol_file.string(), r.protocol_file.parent_path())
          : load_pulse_protocol(r.protocol_file);
  std::uint64_t sim_seed = 0;
  bool simulated = simulated_participant(r.participant_code, sim_seed);
  if (r.simulated_seed) {
    simulated = true;
    sim_seed = *r.simulated_seed;
  }
  if (!simulated && !person) {
    throw InputError("command line", "participant",
                     "sim:SEED for a pulse protocol (a person palpates with pen input, which the terminal session does "
                     "not read; run it from the GUI)");
  }
  std::vector<SceneFile> scenes;
  for (const auto& c : from_file.conditions)
    scenes.push_back(c.generated ? SceneFile{} : load_scene_file(c.scene_file));
  StudyRig rig = load_study_rig(r.rig_file, r.calibration_file);
  refuse_speed_on_hardware(rig, r.speed);
  if (!r.telemetry_file.empty()) refuse_unusable_telemetry_file(r.telemetry_file);
  rig.take(
      r.rig,
      "pulse-localisation session");  // before the session is stored: an unreachable device leaves no empty session

  SqliteTrialStore store(r.store_location, TrialStore::Access::read_write);
  PulseObserverModel model;
  model.seed = sim_seed;
  model.skill = r.model.skill;
  PulseSessionRequest opening;
  opening.participant_code = r.participant_code;
  opening.simulated = simulated;
  opening.resume = r.resume;
  opening.seed = r.seed;
  opening.setup = {rig.rig.id, rig.rig.backend, rig.cal.source,
                   !simulated ? nlohmann::json(nullptr)
                              : nlohmann::json{{"model", "pulse observer"},
                                               {"seed", sim_seed},
                                               {"press_force_N", model.press_force_N},
                                               {"sweep_speed_mm_per_s", model.sweep_speed_mm_per_s},
                                               {"sweep_row_step_mm", model.sweep_row_step_mm},
                                               {"mark_noise_mm", model.mark_noise_mm}},
                   std::filesystem::absolute(r.protocol_file).parent_path().string()};
  const OpenedPulseSession session = open_pulse_session(store, from_file, opening);
  PulseStore pulse_store(store);
  std::unique_ptr<PulseParticipant> participant;
  if (simulated) {
    model.seed = resumed_simulation_seed(session_simulation_seed(sim_seed, session.ordinal), session.start_position);
    participant = std::make_unique<SimulatedPulseObserver>(model, rig.config.layout);
  } else {
    participant = person(session.protocol);
  }
  const int total = static_cast<int>(session.protocol.conditions.size()) * session.protocol.repetitions;
  const std::unique_ptr<SessionClock> clock = session_clock(rig, simulated, r.speed);
  listener.session_started(SessionStart{session.protocol.name, session.participant, session.session_id, session.resumed,
                                        session.start_position, total, session.seed, simulated, rig.hardware(), 0,
                                        clock->steady_origin()});

  RigStimulus output(rig.config, rig.backend());
  output.observe_with(r.tick_observer);
  SessionTelemetry telemetry(r.telemetry_file, output, *clock);
  PulseSessionOptions options;
  options.seed = session.seed;
  options.start_position = session.start_position;
  options.control = &control;
  options.on_trial_started = [&](const PulseTrialStart& s) {
    listener.trial_started(s, session.protocol.conditions.at(static_cast<std::size_t>(s.condition)));
  };
  options.on_waiting = [&](int position, bool paused) { listener.waiting(position, paused); };
  int committed = 0;
  options.on_trial = [&](const PulseTrialRecord& t) {
    pulse_store.commit_trial(session.session_id, t);  // committed before anyone is told
    ++committed;
    listener.trial_committed(t, total);
  };
  const PulseSessionResult result = run_pulse_session(session.protocol, scenes, output, *participant, *clock, options);
  rig.vent();

  SessionEnd end;
  end.completed = result.completed;
  end.stopped = result.stopped;
  end.fault = result.fault;
  if (!end.fault.empty())
    end.fault_record = save_session_fault_record(
        output, "pulse session " + std::to_string(session.session_id) + " of " + r.participant_code, r.telemetry_file,
        r.store_location);
  telemetry.finish(end);
  end.committed_trials = session.start_position + committed;
  end.total_trials = total;
  if (result.completed) store.complete_session(session.session_id);
  listener.session_ended(end);
  return end;
}

}  // namespace palprig
