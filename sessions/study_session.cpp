#include "sessions/study_session.hpp"
#include "sessions/study_rig.hpp"

#include <chrono>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/session_clock.hpp"
#include "experiments/session_loop.hpp"
#include "experiments/trial_cases.hpp"
#include "study/trial_feedback.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "core/input_error.hpp"
#include "sessions/session_setup.hpp"
#include "sessions/session_telemetry.hpp"
#include "store/journaled_trial_store.hpp"
#include "store/pg_target.hpp"

namespace palprig {

namespace {

void check_levels_fit_rig(const Protocol& protocol, const RigConfig& rig) {
  for (double level : protocol.levels_kPa) {
    if (level > rig.safety.p_max_kPa) {
      throw InputError(protocol.source, "levels_kPa",
                       "levels at or below the rig's p_max of " + std::to_string(rig.safety.p_max_kPa) + " kPa (" +
                           rig.source + "), got " + std::to_string(level));
    }
  }
}

// Forwards the runner's events and commits every completed trial through the recorder.
class ListenerBridge final : public RunnerListener {
 public:
  ListenerBridge(TrialStore& store, std::int64_t session_id, const SessionPlan& plan, const Protocol& protocol,
                 SessionListener& listener)
      : recorder_(store, session_id), plan_(plan), protocol_(protocol), listener_(listener) {}

  void on_event(const RunnerEvent& e) override {
    if (e.kind == RunnerEvent::Kind::state_changed && e.state == RunnerState::ready)
      last_started_ = -1;  // a pause holds the trial
    if (e.kind == RunnerEvent::Kind::state_changed && e.state == RunnerState::present && e.position >= 0 &&
        e.position != last_started_) {
      last_started_ = e.position;
      const PlannedTrial& trial = plan_.trials.at(static_cast<std::size_t>(e.position));
      listener_.trial_started(trial, protocol_.conditions.at(static_cast<std::size_t>(trial.condition)));
    }
    listener_.runner_event(e);
  }
  void on_trial_completed(const TrialRecord& trial) override {
    recorder_.on_trial_completed(trial);  // committed before anyone is told
    listener_.trial_committed(trial, static_cast<int>(plan_.trials.size()));
    if (const auto text = trial_feedback(protocol_, trial))
      listener_.participant_feedback(trial.planned.position, *text);
  }
  int committed() const noexcept { return recorder_.committed(); }

 private:
  SessionRecorder recorder_;
  const SessionPlan& plan_;
  const Protocol& protocol_;
  SessionListener& listener_;
  int last_started_ = -1;
};

}  // namespace

std::uint64_t resumed_simulation_seed(std::uint64_t seed, int start_position) noexcept {
  return seed + static_cast<std::uint64_t>(start_position) * 0x9E3779B97F4A7C15ULL;
}

SessionEnd run_study_session(const StudySessionRequest& request, const PersonFactory& person, SessionListener& listener,
                             const RunControl& control) {
  // Everything is loaded and validated before the rig is opened.
  const Protocol from_file = request.protocol_document
                                 ? parse_protocol(*request.protocol_document, request.protocol_file.string(),
                                                  request.protocol_file.parent_path())
                                 : load_protocol(request.protocol_file);
  std::uint64_t sim_seed = 0;
  bool simulated = parse_simulated_participant(request.participant_code, sim_seed);
  if (request.simulated_seed) {
    simulated = true;
    sim_seed = *request.simulated_seed;
  }
  if (!simulated && request.participant_code.rfind("sim:", 0) == 0) {
    throw InputError("command line", "participant",
                     "sim:SEED with a decimal seed, got '" + request.participant_code + "'");
  }
  if (!simulated && from_file.task == TaskKind::localisation && !request.person_palpates) {
    throw InputError("command line", "participant",
                     "sim:SEED for a localisation protocol (a person palpates with pen input, which the terminal "
                     "session does not read; run localisation from the GUI)");
  }
  if (!simulated && !person) {
    throw InputError("command line", "participant", "sim:SEED (this front end cannot ask a person)");
  }
  const RigConfig rig = load_rig_file(request.rig_file);
  const CalibrationModels cal =
      request.calibration_file.empty() ? CalibrationModels{} : load_calibration_file(request.calibration_file);
  check_calibration_matches(cal, rig.id, rig.source);
  check_levels_fit_rig(from_file, rig);
  const TickConfig config = make_tick_config(rig, cal);
  // Hardware runs on the wall clock, as `palprig run` insists: on simulated time a whole session
  // would pass in a few bus cycles and the regulators would never reach a stimulus.
  const bool hardware = rig.backend != "simulated";
  if (hardware && request.speed != 0 && request.speed != 1) {
    throw InputError("command line", "speed",
                     "1 (real time) or none with a hardware rig (" + rig.source + ", backend " + rig.backend +
                         "): hardware runs in real time");
  }

  if (!request.telemetry_file.empty()) refuse_unusable_telemetry_file(request.telemetry_file);

  // The store is opened first: nothing moves before it is known to be writable (a lab server
  // that cannot be reached is refused here). A postgresql:// store writes through the bench
  // journal (offline first).
  std::unique_ptr<TrialStore> store;
  JournaledTrialStore* journaled = nullptr;
  if (is_server_store_location(request.store_location)) {
    auto lab = std::make_unique<JournaledTrialStore>(
        parse_pg_target(request.store_location),
        request.journal_file.empty() ? default_journal_file() : request.journal_file);
    journaled = lab.get();
    store = std::move(lab);
  } else {
    store = open_trial_store(request.store_location, TrialStore::Access::read_write);
  }
  // The rig is opened (and vented) before the session is stored, so an unreachable device does
  // not leave an empty session behind.
  std::optional<SessionRig> rig_taken;
  rig_taken.emplace(request.rig, rig, "study session");
  SimulatedObserverModel model = request.model;
  model.seed = sim_seed;
  SessionRequest opening;
  opening.participant_code = request.participant_code;
  opening.simulated = simulated;
  opening.resume = request.resume;
  opening.seed = request.seed;
  opening.setup = {rig.id, rig.backend, cal.source, simulated ? to_json(model) : nlohmann::json(nullptr),
                   std::filesystem::absolute(request.protocol_file).parent_path().string()};
  const OpenedSession session = open_session(*store, from_file, opening);
  const Protocol& protocol = session.protocol;

  // Localisation: each trial's case (a listed scene, or a generated case made from its seed).
  TrialCases cases(protocol, session.plan.seed);

  std::unique_ptr<Participant> participant;
  if (simulated) {
    model.seed = resumed_simulation_seed(session_simulation_seed(sim_seed, session.ordinal), session.start_position);
    participant = std::make_unique<SimulatedParticipant>(model, protocol, nullptr, config.layout);
  } else {
    participant = person(protocol);
  }

  const int total = static_cast<int>(session.plan.trials.size());
  // The clock first, so the start can say where session time 0 is on steady_clock.
  std::unique_ptr<SessionClock> clock;
  if (simulated && !hardware && request.speed <= 0)
    clock = std::make_unique<SimulatedClock>();
  else
    clock = std::make_unique<SteadyClock>(simulated && !hardware ? request.speed : 1.0);
  listener.session_started(SessionStart{protocol.name, session.participant, session.session_id, session.resumed,
                                        session.start_position, total, session.plan.seed, simulated, hardware,
                                        journaled ? journaled->pushed_at_open() : 0, clock->steady_origin()});

  RigStimulus output(config, rig_taken->backend());
  output.observe_with(request.tick_observer);
  ListenerBridge bridge(*store, session.session_id, session.plan, protocol, listener);
  TrialRunner runner(protocol, session.plan, session.start_position, output, bridge,
                     protocol.task == TaskKind::localisation ? &cases : nullptr, participant->pen());

  SessionTelemetry telemetry(request.telemetry_file, output, *clock);

  SessionLoopOptions options;
  options.control = &control;
  options.output = &output;
  const SessionLoopResult result = run_session_loop(runner, *participant, *clock, options);
  (void)rig_taken->backend().vent();  // given back (and closed, when opened here) as this returns

  SessionEnd end;
  end.completed = result.completed;
  end.stopped = result.stopped;
  end.fault = result.fault;
  if (!end.fault.empty())
    end.fault_record = save_session_fault_record(
        output, "session " + std::to_string(session.session_id) + " of " + request.participant_code,
        request.telemetry_file, journaled ? journaled->journal_file() : std::filesystem::path(request.store_location));
  telemetry.finish(end);
  end.committed_trials = session.start_position + bridge.committed();
  end.total_trials = total;
  if (result.completed) store->complete_session(session.session_id);
  if (journaled) {
    // Every trial is safe in the journal; give the pusher a moment to reach the server.
    end.unpushed_trials = journaled->flush(std::chrono::seconds(10));
    end.journal_file = journaled->journal_file();
  }
  listener.session_ended(end);
  return end;
}

}  // namespace palprig
