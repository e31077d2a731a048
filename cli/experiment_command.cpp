// palprig experiment: run a study session in the terminal (a person types the answers) or
// headless with a simulated participant (sim:SEED), against the SQLite trial store.
//   palprig experiment run  --protocol F --participant ID|sim:SEED --db F [--rig F] [--cal F] [--resume]
//   palprig experiment plan --protocol F --participant ID [--seed N]   (print the generated order)
// Every file is validated before anything moves (exit 2); a rig fault vents and exits 1; a stop
// (Ctrl-C, 'q', end of input) keeps every committed trial and the session resumable (exit 1).
#include <poll.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "cli/commands.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "experiments/participant.hpp"
#include "experiments/protocol.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/session_clock.hpp"
#include "experiments/session_loop.hpp"
#include "sessions/session_setup.hpp"
#include "experiments/simulated_participant.hpp"
#include "store/journaled_trial_store.hpp"
#include "store/trial_store.hpp"
#include "models/parse_error.hpp"

using namespace palprig;

namespace {

// A person at the terminal: answers are typed lines ("2", "12", "0" for no tumor), Enter goes
// on after a break, "q" stops the session (it stays resumable).
class TerminalParticipant final : public Participant {
 public:
  explicit TerminalParticipant(const Protocol& protocol) : protocol_(protocol) {}

  bool ready(double) override {
    if (!prompted_ready_) {
      std::cout << "Ready? Press Enter to start (q + Enter stops; the session can be resumed).\n" << std::flush;
      prompted_ready_ = true;
    }
    const auto line = next_line();
    if (!line) return false;
    prompted_ready_ = false;
    return true;
  }

  void trial_started(const PlannedTrial& trial, const Condition& condition, double) override {
    std::cout << "\nTrial " << trial.position + 1 << (trial.practice ? " (practice)" : "") << ", " << condition.name
              << (condition.mode == PresentationMode::sequential ? ": the fingers are presented one after another"
                                                                 : ": all fingers at once")
              << ".\n  Which fingers feel a tumor? Type their numbers (1 = " << protocol_.finger_names[0]
              << ", 2 = " << protocol_.finger_names[1] << ", 3 = " << protocol_.finger_names[2]
              << "), or 0 for none, then Enter.\n"
              << std::flush;
  }

  void feel(const FeltSample&) override {}

  std::optional<Response> answer(double) override {
    const auto line = next_line();
    if (!line) return std::nullopt;
    Response r;
    bool ok = !line->empty();
    bool none = false;
    for (char c : *line) {
      if (c == '0' || c == 'n') none = true;
      else if (c >= '1' && c <= '0' + kFingerCount) r.tumor_under[static_cast<std::size_t>(c - '1')] = true;
      else if (c != ' ' && c != ',') ok = false;
    }
    const bool any = r.tumor_under[0] || r.tumor_under[1] || r.tumor_under[2];
    if (!ok || (none && any)) {
      std::cout << "  Please type finger numbers 1-" << kFingerCount << " (e.g. 2 or 23), or 0 for no tumor.\n" << std::flush;
      return std::nullopt;
    }
    return r;
  }

 private:
  // One complete line from stdin if one has arrived (never blocks). "q" or the end of input
  // asks the session to stop.
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
      if (eof_) cli::stop_signal().store(SIGTERM);
      return std::nullopt;
    }
    std::string line = pending_.substr(0, newline);
    pending_.erase(0, newline + 1);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "q") {
      cli::stop_signal().store(SIGTERM);
      return std::nullopt;
    }
    return line;
  }

  const Protocol& protocol_;
  std::string pending_;
  bool eof_ = false;
  bool prompted_ready_ = false;
};

struct RunArgs {
  std::string protocol, participant, db, rig, cal, journal;
  bool resume = false, quiet = false;
  std::optional<std::uint64_t> seed;
  double speed = 0;  // simulated participants: 0 = as fast as possible, else times real time
  SimulatedObserverModel model;
};

std::string flags_text(const FingerFlags& f) {
  std::string s;
  for (int i = 0; i < kFingerCount; ++i) {
    if (f[static_cast<std::size_t>(i)]) s += std::to_string(i + 1);
  }
  return s.empty() ? "none" : s;
}

std::string trial_line(const TrialRecord& t, int total) {
  std::string line = "trial " + std::to_string(t.planned.position + 1) + "/" + std::to_string(total) + " " + t.condition +
                     (t.planned.practice ? " (practice)" : "");
  if (t.mode != PresentationMode::scene) {
    line += " " + t.combination_label + " kPa, tumor " + flags_text(t.truth);
    line += t.answered ? ", answer " + flags_text(t.answer) + " (" + to_string(t.finger_outcomes[0]) + " " +
                             to_string(t.finger_outcomes[1]) + " " + to_string(t.finger_outcomes[2]) + ")"
                       : ", no answer";
  } else if (t.answered) {
    line += ", " + std::to_string(t.marks.size()) + " marks:";
    for (const auto& s : t.localisation.tumors) line += std::string(" ") + s.tumor + (s.hit ? " found" : " missed");
  } else {
    line += ", no answer";
  }
  if (t.answered) {
    char rt[32];
    std::snprintf(rt, sizeof rt, ", %.2f s", t.response_time_s);
    line += rt;
  }
  return line;
}

void check_levels_fit_rig(const Protocol& protocol, const RigConfig& rig) {
  for (double level : protocol.levels_kPa) {
    if (level > rig.safety.p_max_kPa) {
      throw InputError(protocol.source, "levels_kPa",
                       "levels at or below the rig's p_max of " + std::to_string(rig.safety.p_max_kPa) + " kPa (" +
                           rig.source + "), got " + std::to_string(level));
    }
  }
}

void run_experiment(const RunArgs& a) {
  // Everything is loaded and validated before the rig is opened.
  const Protocol from_file = load_protocol(a.protocol);
  std::uint64_t sim_seed = 0;
  const bool simulated = parse_simulated_participant(a.participant, sim_seed);
  if (!simulated && a.participant.rfind("sim:", 0) == 0) {
    throw InputError("command line", "--participant", "sim:SEED with a decimal seed, got '" + a.participant + "'");
  }
  if (!simulated && from_file.task == TaskKind::localisation) {
    throw InputError("command line", "--participant",
                     "sim:SEED for a localisation protocol (a person palpates with pen input, which the terminal "
                     "session does not read; run localisation from the GUI)");
  }
  const RigConfig rig = a.rig.empty() ? load_rig_file(cli::data_dir() / "rigs" / "simulated.json") : load_rig_file(a.rig);
  const CalibrationModels cal = a.cal.empty() ? CalibrationModels{} : load_calibration_file(a.cal);
  check_calibration_matches(cal, rig.id, rig.source);
  check_levels_fit_rig(from_file, rig);
  const TickConfig config = make_tick_config(rig, cal);

  // The store is opened first (a lab server that cannot be reached is refused before anything
  // moves); the rig is opened (and vented) before the session is stored, so an unreachable
  // device does not leave an empty session behind.
  if (!a.journal.empty()) ::setenv("PALPRIG_JOURNAL", a.journal.c_str(), 1);
  const auto opened_store = open_trial_store(a.db, TrialStore::Access::read_write);
  TrialStore& store = *opened_store;
  auto* journaled = dynamic_cast<JournaledTrialStore*>(&store);
  if (journaled && journaled->pushed_at_open() > 0) {
    std::cout << "palprig experiment: " << journaled->pushed_at_open() << " trials left in the journal "
              << journaled->journal_file().string() << " pushed to " << a.db << "\n";
  }
  std::unique_ptr<RigBackend> backend = make_backend(rig);
  backend->open();
  SimulatedObserverModel model = a.model;
  model.seed = sim_seed;
  SessionRequest request;
  request.participant_code = a.participant;
  request.simulated = simulated;
  request.resume = a.resume;
  request.seed = a.seed;
  request.setup = {rig.id, rig.backend, cal.source, simulated ? to_json(model) : nlohmann::json(nullptr),
                   std::filesystem::absolute(a.protocol).parent_path().string()};
  const OpenedSession session = open_session(store, from_file, request);
  const Protocol& protocol = session.protocol;

  std::optional<SceneFile> scene;
  if (protocol.task == TaskKind::localisation) scene = load_scene_file(protocol.localisation.scene_file);

  std::unique_ptr<Participant> participant;
  if (simulated) {
    // A resumed simulated session continues its random stream from a seed moved on by the
    // number of trials done, so the answers differ from those of the lost attempt.
    model.seed = sim_seed + static_cast<std::uint64_t>(session.start_position) * 0x9E3779B97F4A7C15ULL;
    participant = std::make_unique<SimulatedParticipant>(model, protocol, scene ? scene->scene.get() : nullptr, config.layout);
  } else {
    participant = std::make_unique<TerminalParticipant>(protocol);
  }

  const int total = static_cast<int>(session.plan.trials.size());
  std::cout << "palprig experiment: " << protocol.name << ", participant " << session.participant.code << " (no. "
            << session.participant.number << "), session " << session.session_id << ", "
            << (session.resumed ? "resumed at trial " + std::to_string(session.start_position + 1) : std::string("new"))
            << ", " << total << " trials, seed " << session.plan.seed << ", database " << a.db << "\n"
            << std::flush;

  RigStimulus output(config, *backend);
  SessionRecorder recorder(
      store, session.session_id,
      [&](const RunnerEvent& e) {
        if (!simulated && e.kind == RunnerEvent::Kind::state_changed && e.state == RunnerState::rest) {
          std::cout << "\nBreak.\n" << std::flush;
        }
      },
      [&](const TrialRecord& t) {
        // A person gets no feedback on correctness (it would train them during the study); the
        // scores are in the database. A simulated session prints the whole line.
        if (!simulated) std::cout << "  Answer recorded (" << t.planned.position + 1 << " of " << total << ").\n" << std::flush;
        else if (!a.quiet) std::cout << trial_line(t, total) << "\n" << std::flush;
      });
  TrialRunner runner(protocol, session.plan, session.start_position, output, recorder,
                     scene ? scene->scene.get() : nullptr, participant->pen());

  std::unique_ptr<SessionClock> clock;
  if (simulated && a.speed <= 0) clock = std::make_unique<SimulatedClock>();
  else clock = std::make_unique<SteadyClock>(simulated ? a.speed : 1.0);

  cli::install_stop_signals();
  SessionLoopOptions options;
  options.stop = &cli::stop_signal();
  options.output = &output;
  const SessionLoopResult result = run_session_loop(runner, *participant, *clock, options);
  backend->vent();
  backend->close();

  const int done = session.start_position + recorder.committed();
  if (result.completed) store.complete_session(session.session_id);
  if (journaled) {
    // Every trial is safe in the journal; give the pusher a moment to reach the server.
    const std::int64_t pending = journaled->flush(std::chrono::seconds(10));
    if (pending > 0) {
      std::cerr << "palprig: the lab server has not confirmed every trial yet; they are kept in the journal "
                << journaled->journal_file().string() << ": push them with palprig store sync --from "
                << journaled->journal_file().string() << " --to " << a.db << "\n";
    }
  }
  if (result.completed) {
    std::cout << "session " << session.session_id << " completed: " << done << " trials in " << a.db << "\n";
    return;
  }
  if (!result.fault.empty()) {
    std::cerr << "palprig: rig fault: " << result.fault << "; " << done << " of " << total
              << " trials kept, continue with --resume\n";
  } else {
    std::cerr << "palprig: session " << session.session_id << " stopped after " << done << " of " << total
              << " trials (all kept); continue with --resume\n";
  }
  cli::finish(cli::kExitFault);
}

void register_run(CLI::App* experiment) {
  auto a = std::make_shared<RunArgs>();
  auto* sub = experiment->add_subcommand(
      "run", "Run (or --resume) a session: trials from a protocol file, answers typed in the terminal or given by a "
             "simulated participant (sim:SEED), each trial committed to the SQLite database as it completes");
  sub->add_option("--protocol", a->protocol, "Protocol file (JSON), e.g. data/protocols/discrimination_002.json")->required();
  sub->add_option("--participant", a->participant,
                  "Participant code, or sim:SEED for a simulated participant (model observer)")->required();
  sub->add_option("--db", a->db,
                  "Trial store: an SQLite file (created when missing) or the lab's PostgreSQL server, "
                  "postgresql://user@host:port/dbname (password from PGPASSWORD or ~/.pgpass)")->required();
  sub->add_option("--journal", a->journal,
                  "With a postgresql:// store: the bench's local journal (SQLite) every trial is written to first; "
                  "default $PALPRIG_JOURNAL, else ~/.local/state/palprig/journal.sqlite");
  sub->add_option("--rig", a->rig, "Rig file (JSON); default: the simulated rig data/rigs/simulated.json");
  sub->add_option("--cal", a->cal, "Calibration file (JSON); default: paper 002's models");
  sub->add_flag("--resume", a->resume, "Continue this participant's unfinished session with this protocol");
  sub->add_option("--seed", a->seed, "Seed of the generated order; default: derived from participant and protocol");
  sub->add_option("--speed", a->speed,
                  "Simulated participant only: 0 = as fast as possible on simulated time (default), "
                  "1 = real time, 10 = ten times faster than real time")->check(CLI::Range(0.0, 1e6));
  sub->add_flag("--quiet", a->quiet, "Simulated participant: no line per trial");
  sub->add_option("--sim-noise-kPa", a->model.noise_kPa,
                  "Simulated: sd of each finger's perceived pressure (three fingers at once)")->default_val(a->model.noise_kPa)
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--sim-sequential-noise-factor", a->model.sequential_noise_factor,
                  "Simulated: noise multiplier when fingers come one after another")
      ->default_val(a->model.sequential_noise_factor)->check(CLI::Range(0.0, 100.0));
  sub->add_option("--sim-criterion-kPa", a->model.criterion_kPa,
                  "Simulated: a finger perceived this much above the lowest one has a tumor")
      ->default_val(a->model.criterion_kPa)->check(CLI::Range(0.0, 100.0));
  sub->add_option("--sim-rt-simultaneous", a->model.simultaneous.mean_s,
                  "Simulated: mean response time in s, three fingers at once (log-normal; sd --sim-rt-sd-simultaneous)")
      ->default_val(a->model.simultaneous.mean_s)->check(CLI::Range(0.05, 600.0));
  sub->add_option("--sim-rt-sd-simultaneous", a->model.simultaneous.sd_s, "Simulated: response time sd in s")
      ->default_val(a->model.simultaneous.sd_s)->check(CLI::Range(0.0, 600.0));
  sub->add_option("--sim-rt-sequential", a->model.sequential.mean_s, "Simulated: mean response time in s, one finger at a time")
      ->default_val(a->model.sequential.mean_s)->check(CLI::Range(0.05, 600.0));
  sub->add_option("--sim-rt-sd-sequential", a->model.sequential.sd_s, "Simulated: response time sd in s")
      ->default_val(a->model.sequential.sd_s)->check(CLI::Range(0.0, 600.0));
  sub->callback([a] { run_experiment(*a); });
}

void register_plan(CLI::App* experiment) {
  struct Args {
    std::string protocol, participant;
    int number = 1;
    std::optional<std::uint64_t> seed;
  };
  auto a = std::make_shared<Args>();
  auto* sub = experiment->add_subcommand("plan", "Print the trial order a participant would get (nothing is stored)");
  sub->add_option("--protocol", a->protocol, "Protocol file (JSON)")->required();
  sub->add_option("--participant", a->participant, "Participant code (the default seed derives from it)")->required();
  sub->add_option("--number", a->number, "Participant number for counterbalancing (1 = first enrolled)")
      ->default_val(1)->check(CLI::Range(1, 1000000));
  sub->add_option("--seed", a->seed, "Seed; default: derived from participant and protocol");
  sub->callback([a] {
    const Protocol p = load_protocol(a->protocol);
    const std::uint64_t seed = a->seed ? *a->seed : default_session_seed(a->participant, p.name);
    const SessionPlan plan = make_session_plan(p, a->number, seed);
    std::cout << "position,block,condition,mode,practice,stimulus_kPa,tumor_fingers,break_after\n";
    for (const PlannedTrial& t : plan.trials) {
      const Condition& c = p.conditions[static_cast<std::size_t>(t.condition)];
      std::string stimulus = "scene", tumor = "";
      if (t.combination >= 0) {
        const auto& combination = p.combinations[static_cast<std::size_t>(t.combination)];
        stimulus = combination.label;
        tumor = flags_text(combination.tumor);
      }
      std::cout << t.position + 1 << "," << t.block + 1 << "," << c.name << "," << to_string(c.mode) << ","
                << (t.practice ? 1 : 0) << "," << stimulus << "," << tumor << "," << (t.break_after ? 1 : 0) << "\n";
    }
  });
}

}  // namespace

void register_experiment_command(CLI::App& app) {
  auto* experiment = app.add_subcommand("experiment", "Run study sessions (paper 002's discrimination and localisation "
                                                      "studies, or your own protocol files)");
  experiment->require_subcommand(1);
  register_run(experiment);
  register_plan(experiment);
}
