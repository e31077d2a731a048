// Threshold sessions from the command line: a person answers in the terminal ("1"/"2" for the
// stronger interval, "y"/"n" for yes-no), or the simulated threshold observer (sim:SEED)
// answers from what the rig delivered. Every trial is committed with the tracks' state;
// --resume continues the same staircases after a stop or a kill.
#include "cli/threshold_experiment.hpp"

#include <poll.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/simulated_participant.hpp"
#include "experiments/threshold_observer.hpp"
#include "experiments/threshold_session.hpp"
#include "formats/calibration_file.hpp"
#include "formats/json_file.hpp"
#include "formats/rig_file.hpp"
#include "models/parse_error.hpp"
#include "sessions/threshold_setup.hpp"
#include "store/threshold_store.hpp"

namespace palprig::cli {

namespace {

class TerminalThresholdParticipant final : public ThresholdParticipant {
 public:
  explicit TerminalThresholdParticipant(ThresholdMethod method) : method_(method) {}

  bool ready(double) override {
    if (!prompted_) {
      std::cout << "Ready? Press Enter to start (q + Enter stops; the session can be resumed).\n" << std::flush;
      prompted_ = true;
    }
    return next_line().has_value();
  }
  void trial_started(const ThresholdTrialInfo& trial, double) override {
    std::cout << "\nTrial " << trial.position + 1 << " ("
              << (trial.spec->fingers == FingerSet::one ? "one finger" : "three fingers") << ")\n" << std::flush;
  }
  void interval_started(int interval, double) override {
    std::cout << "  interval " << interval + 1 << "\n" << std::flush;
  }
  void feel(int, const FeltSample&) override {}
  std::optional<int> answer(double) override {
    if (!asked_) {
      std::cout << (method_ == ThresholdMethod::two_afc ? "  Which interval was stronger? Type 1 or 2, then Enter.\n"
                                                        : "  Was the second interval stronger? Type y or n, then Enter.\n")
                << std::flush;
      asked_ = true;
    }
    const auto line = next_line();
    if (!line) return std::nullopt;
    if (method_ == ThresholdMethod::two_afc && (*line == "1" || *line == "2")) {
      asked_ = false;
      return *line == "1" ? 0 : 1;
    }
    if (method_ == ThresholdMethod::yes_no && (*line == "y" || *line == "n")) {
      asked_ = false;
      return *line == "y" ? 1 : 0;
    }
    std::cout << (method_ == ThresholdMethod::two_afc ? "  Please type 1 or 2.\n" : "  Please type y or n.\n") << std::flush;
    return std::nullopt;
  }

 private:
  // One complete line from stdin if one has arrived (never blocks); "q" or the end of input stops.
  std::optional<std::string> next_line() {
    pollfd p{STDIN_FILENO, POLLIN, 0};
    while (!eof_ && ::poll(&p, 1, 0) > 0 && (p.revents & (POLLIN | POLLHUP))) {
      char buf[256];
      const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
      if (n <= 0) {
        eof_ = true;
        break;
      }
      pending_.append(buf, static_cast<std::size_t>(n));
      if (pending_.find('\n') != std::string::npos) break;
    }
    const auto newline = pending_.find('\n');
    if (newline == std::string::npos) {
      if (eof_) stop_signal().store(SIGTERM);
      return std::nullopt;
    }
    std::string line = pending_.substr(0, newline);
    pending_.erase(0, newline + 1);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "q") {
      stop_signal().store(SIGTERM);
      return std::nullopt;
    }
    return line;
  }

  ThresholdMethod method_;
  std::string pending_;
  bool eof_ = false, prompted_ = false, asked_ = false;
};

std::string format(double x, int decimals = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

void print_estimates(const std::vector<AdaptiveTrack>& tracks) {
  for (const AdaptiveTrack& t : tracks) {
    const TrackEstimate e = t.estimate();
    std::cout << "  " << t.spec().name << ": threshold " << format(e.threshold_kPa) << " kPa at "
              << format(100 * e.target_probability, 1) << " % correct, " << e.trials << " trials";
    if (t.spec().procedure == AdaptiveProcedure::staircase) {
      std::cout << ", " << e.reversals << " reversals (sd of the averaged reversals " << format(e.sd) << " kPa)";
    } else {
      std::cout << ", posterior sd " << format(e.sd) << " log10 units, 95 % credible interval " << format(e.ci_low_kPa)
                << " .. " << format(e.ci_high_kPa) << " kPa";
    }
    std::cout << (t.finished() ? "" : " (not finished)") << "\n";
  }
}

}  // namespace

void run_threshold_experiment(const ThresholdRunRequest& a) {
  const ThresholdProtocol from_file = load_threshold_protocol(a.protocol);
  std::uint64_t sim_seed = 0;
  const bool simulated = parse_simulated_participant(a.participant, sim_seed);
  if (!simulated && a.participant.rfind("sim:", 0) == 0) {
    throw InputError("command line", "participant", "sim:SEED with a decimal seed, got '" + a.participant + "'");
  }
  const RigConfig rig = a.rig.empty() ? load_rig_file(data_dir() / "rigs" / "simulated.json") : load_rig_file(a.rig);
  const CalibrationModels cal = a.cal.empty() ? CalibrationModels{} : load_calibration_file(a.cal);
  check_calibration_matches(cal, rig.id, rig.source);
  if (from_file.max_pressure_kPa() > rig.safety.p_max_kPa) {
    throw InputError(from_file.source, "threshold.reference_kPa",
                     "reference + the largest track level at or below the rig's p_max of " +
                         format(rig.safety.p_max_kPa, 1) + " kPa (" + rig.source + "), got " +
                         format(from_file.max_pressure_kPa(), 1));
  }
  const TickConfig config = make_tick_config(rig, cal);
  std::unique_ptr<RigBackend> backend = make_backend(rig);
  backend->open();

  SqliteTrialStore store(a.db, TrialStore::Access::read_write);
  ThresholdObserverModel model;
  model.noise_kPa = a.sim_noise_kPa;
  model.criterion_kPa = a.sim_criterion_kPa;
  model.seed = sim_seed;
  ThresholdSessionRequest request;
  request.participant_code = a.participant;
  request.simulated = simulated;
  request.resume = a.resume;
  request.seed = a.seed;
  request.setup = {rig.id, rig.backend, cal.source, simulated ? to_json(model) : nlohmann::json(nullptr),
                   std::filesystem::absolute(a.protocol).parent_path().string()};
  OpenedThresholdSession session = open_threshold_session(store, from_file, request);
  ThresholdStore threshold_store(store);

  std::unique_ptr<ThresholdParticipant> participant;
  if (simulated) {
    // A resumed observer continues from a seed moved on by the trials done (new answers, same tracks).
    model.seed = sim_seed + static_cast<std::uint64_t>(session.start_position) * 0x9E3779B97F4A7C15ULL;
    participant = std::make_unique<SimulatedThresholdObserver>(model);
  } else {
    participant = std::make_unique<TerminalThresholdParticipant>(session.protocol.method);
  }
  std::cout << "palprig experiment: " << session.protocol.name << " (threshold, " << to_string(session.protocol.method)
            << ", " << session.tracks.size() << " interleaved tracks), participant " << session.participant.code
            << ", session " << session.session_id << ", "
            << (session.resumed ? "resumed at trial " + std::to_string(session.start_position + 1) : std::string("new"))
            << ", seed " << session.seed << ", database " << a.db << "\n"
            << std::flush;

  RigStimulus output(config, *backend);
  std::unique_ptr<SessionClock> clock;
  if (simulated && a.speed <= 0) clock = std::make_unique<SimulatedClock>();
  else clock = std::make_unique<SteadyClock>(simulated ? a.speed : 1.0);
  install_stop_signals();
  ThresholdSessionOptions options;
  options.seed = session.seed;
  options.start_position = session.start_position;
  options.stop = &stop_signal();
  int committed = 0;
  options.on_trial = [&](const ThresholdTrialRecord& t) {
    threshold_store.commit_trial(session.session_id, t);
    ++committed;
    if (!simulated) {
      std::cout << "  Answer recorded.\n" << std::flush;
    } else if (!a.quiet) {
      std::cout << "trial " << t.position + 1 << " " << t.track_name << " +" << format(t.level_kPa) << " kPa, "
                << (t.answered ? (t.correct ? "correct" : "wrong") : "no answer") << (t.reversal ? ", reversal" : "")
                << "\n" << std::flush;
    }
  };
  const ThresholdSessionResult result =
      run_threshold_session(session.protocol, session.tracks, output, *participant, *clock, options);
  backend->vent();
  backend->close();

  const int done = session.start_position + committed;
  if (result.completed) {
    store.complete_session(session.session_id);
    std::cout << "session " << session.session_id << " completed: " << done << " trials in " << a.db << "\n";
    print_estimates(session.tracks);
    return;
  }
  if (!result.fault.empty()) {
    std::cerr << "palprig: rig fault: " << result.fault << "; " << done << " trials kept, continue with --resume\n";
  } else {
    std::cerr << "palprig: session " << session.session_id << " stopped after " << done
              << " trials (all kept); continue with --resume\n";
  }
  finish(kExitFault);
}

}  // namespace palprig::cli
