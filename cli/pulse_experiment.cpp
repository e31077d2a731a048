// Pulse-localisation sessions from the command line: the simulated participant (sim:SEED)
// palpates each condition's scene through the rig and marks the pulse; each trial is committed
// as it completes; --resume continues the stored order. A person palpates with pen input, which
// the terminal does not read: that runs from the GUI's experiment console.
#include "cli/pulse_experiment.hpp"

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/simulated_participant.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "models/parse_error.hpp"
#include "sessions/pulse_setup.hpp"

namespace palprig::cli {

void run_pulse_experiment(const PulseRunRequest& a) {
  const PulseProtocol from_file = load_pulse_protocol(a.protocol);
  std::uint64_t sim_seed = 0;
  if (!parse_simulated_participant(a.participant, sim_seed)) {
    throw InputError("command line", "participant",
                     "sim:SEED for a pulse protocol (a person palpates with pen input, which the terminal session does "
                     "not read; run it from the GUI)");
  }
  std::vector<SceneFile> scenes;
  for (const auto& c : from_file.conditions) scenes.push_back(c.generated ? SceneFile{} : load_scene_file(c.scene_file));
  const RigConfig rig = a.rig.empty() ? load_rig_file(data_dir() / "rigs" / "simulated.json") : load_rig_file(a.rig);
  const CalibrationModels cal = a.cal.empty() ? CalibrationModels{} : load_calibration_file(a.cal);
  check_calibration_matches(cal, rig.id, rig.source);
  const TickConfig config = make_tick_config(rig, cal);
  std::unique_ptr<RigBackend> backend = make_backend(rig);
  backend->open();

  SqliteTrialStore store(a.db, TrialStore::Access::read_write);
  PulseObserverModel model;
  model.seed = sim_seed;
  PulseSessionRequest request;
  request.participant_code = a.participant;
  request.simulated = true;
  request.resume = a.resume;
  request.seed = a.seed;
  request.setup = {rig.id, rig.backend, cal.source,
                   nlohmann::json{{"model", "pulse observer"}, {"seed", sim_seed}, {"press_force_N", model.press_force_N},
                                  {"sweep_speed_mm_per_s", model.sweep_speed_mm_per_s},
                                  {"sweep_row_step_mm", model.sweep_row_step_mm}, {"mark_noise_mm", model.mark_noise_mm}},
                   std::filesystem::absolute(a.protocol).parent_path().string()};
  const OpenedPulseSession session = open_pulse_session(store, from_file, request);
  PulseStore pulse_store(store);
  model.seed = sim_seed + static_cast<std::uint64_t>(session.start_position) * 0x9E3779B97F4A7C15ULL;
  SimulatedPulseObserver participant(model, config.layout);
  const int total = static_cast<int>(session.protocol.conditions.size()) * session.protocol.repetitions;
  std::cout << "palprig experiment: " << session.protocol.name << " (pulse localisation), participant "
            << session.participant.code << ", session " << session.session_id << ", "
            << (session.resumed ? "resumed at trial " + std::to_string(session.start_position + 1) : std::string("new"))
            << ", " << total << " trials, seed " << session.seed << ", database " << a.db << "\n"
            << std::flush;

  RigStimulus output(config, *backend);
  std::unique_ptr<SessionClock> clock;
  if (a.speed <= 0) clock = std::make_unique<SimulatedClock>();
  else clock = std::make_unique<SteadyClock>(a.speed);
  install_stop_signals();
  PulseSessionOptions options;
  options.seed = session.seed;
  options.start_position = session.start_position;
  options.stop = &stop_signal();
  int committed = 0;
  options.on_trial = [&](const PulseTrialRecord& t) {
    pulse_store.commit_trial(session.session_id, t);
    ++committed;
    if (a.quiet) return;
    char buf[256];
    if (t.answered) {
      std::snprintf(buf, sizeof buf, "trial %d/%d %s: mark (%.1f, %.1f) mm, %.1f mm from %s, %s", t.position + 1, total,
                    t.condition.c_str(), t.mark_x_mm, t.mark_y_mm, t.distance_mm, t.artery.c_str(), t.hit ? "hit" : "miss");
    } else {
      std::snprintf(buf, sizeof buf, "trial %d/%d %s: no mark", t.position + 1, total, t.condition.c_str());
    }
    std::cout << buf << "\n" << std::flush;
  };
  const PulseSessionResult result = run_pulse_session(session.protocol, scenes, output, participant, *clock, options);
  backend->vent();
  backend->close();
  const int done = session.start_position + committed;
  if (result.completed) {
    store.complete_session(session.session_id);
    std::cout << "session " << session.session_id << " completed: " << done << " trials in " << a.db << "\n";
    return;
  }
  std::cerr << "palprig: " << (result.fault.empty() ? "session stopped" : "rig fault: " + result.fault) << " after "
            << done << " of " << total << " trials (all kept); continue with --resume\n";
  finish(kExitFault);
}

}  // namespace palprig::cli
