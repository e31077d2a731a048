// palprig experiment: run a study session in the terminal (a person types the answers) or
// headless with a simulated participant (sim:SEED), against the trial store. The session itself
// is sessions/study_session's run_study_session; this file parses, prints and sets the exit code.
//   palprig experiment run  --protocol F --participant ID|sim:SEED --db F [--rig F] [--cal F] [--resume]
//   palprig experiment plan --protocol F --participant ID [--db F | --number N] [--seed N]
//     (print the generated order; standard error says for which participant number)
// Every file is validated before anything moves (exit 2); a rig fault vents and exits 1; a stop
// (Ctrl-C, 'q', end of input) keeps every committed trial and the session resumable (exit 1).
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "cli/pulse_experiment.hpp"
#include "cli/threshold_experiment.hpp"
#include "experiments/pulse_session.hpp"
#include "study/threshold_protocol.hpp"
#include "formats/json_file.hpp"
#include "core/input_error.hpp"
#include "study/protocol.hpp"
#include "experiments/terminal_participant.hpp"
#include "study/session_plan.hpp"
#include "sessions/session_preview.hpp"
#include "sessions/session_setup.hpp"
#include "sessions/session_telemetry.hpp"
#include "sessions/study_session.hpp"
#include "runtime/run_control.hpp"

using namespace palprig;

namespace {

struct RunArgs {
  StudySessionRequest request;
  bool quiet = false;
  double sim_threshold_noise_kPa = 0.8, sim_threshold_criterion_kPa = 0.5;  // threshold protocols
};

std::string trial_line(const TrialRecord& t, int total) {
  std::string line = "trial " + std::to_string(t.planned.position + 1) + "/" + std::to_string(total) + " " +
                     t.condition + (t.planned.practice ? " (practice)" : "");
  if (t.mode != PresentationMode::scene) {
    line += " " + t.combination_label + " kPa, tumor " + finger_numbers_text(t.truth);
    line += t.answered ? ", answer " + finger_numbers_text(t.answer) + " (" + to_string(t.finger_outcomes[0]) + " " +
                             to_string(t.finger_outcomes[1]) + " " + to_string(t.finger_outcomes[2]) + ")"
                       : ", no answer";
  } else {
    if (!t.case_name.empty()) line += " " + t.case_name;
    if (!t.answered) {
      line += ", no answer";
    } else {
      line += ", " + std::to_string(t.marks.size()) + " marks:";
      for (const auto& s : t.localisation.tumors) line += std::string(" ") + s.tumor + (s.hit ? " found" : " missed");
      if (t.case_tumors == 0) line += t.marks.empty() ? " no tumor (TN)" : " no tumor (FP)";
    }
  }
  if (t.answered) {
    char rt[32];
    std::snprintf(rt, sizeof rt, ", %.2f s", t.response_time_s);
    line += rt;
  }
  return line;
}

// Prints what the session reports: a person sees prompts and "Answer recorded" (no feedback on
// correctness: it would train them during the study; the scores are in the database), a
// simulated session one line per trial.
class TerminalReport final : public SessionListener {
 public:
  TerminalReport(const std::string& db, bool quiet) : db_(db), quiet_(quiet) {}

  void session_started(const SessionStart& s) override {
    simulated_ = s.simulated;
    std::cout << "palprig experiment: " << s.protocol_name << ", participant " << s.participant.code << " (no. "
              << s.participant.number << "), session " << s.session_id << ", "
              << (s.resumed ? "resumed at trial " + std::to_string(s.start_position + 1) : std::string("new")) << ", "
              << s.total_trials << " trials, seed " << s.seed << ", database " << db_
              << (s.real_time_hardware && s.simulated ? ", real time (hardware rig)" : "") << "\n"
              << std::flush;
    if (s.pushed_from_journal > 0) {
      std::cout << "palprig experiment: " << s.pushed_from_journal
                << " trials left in the journal by an earlier run pushed to " << db_ << "\n"
                << std::flush;
    }
    session_id_ = s.session_id;
  }
  void runner_event(const RunnerEvent& e) override {
    if (!simulated_ && e.kind == RunnerEvent::Kind::state_changed && e.state == RunnerState::rest) {
      std::cout << "\nBreak.\n" << std::flush;
    }
  }
  void trial_committed(const TrialRecord& t, int total) override {
    if (!simulated_)
      std::cout << "  Answer recorded (" << t.planned.position + 1 << " of " << total << ").\n" << std::flush;
    else if (!quiet_)
      std::cout << trial_line(t, total) << "\n" << std::flush;
  }
  void participant_feedback(int, const std::string& text) override {
    if (!simulated_) std::cout << "  " << text << "\n" << std::flush;
  }
  std::int64_t session_id() const noexcept { return session_id_; }

 private:
  std::string db_;
  bool quiet_;
  bool simulated_ = false;
  std::int64_t session_id_ = 0;
};

void run_experiment(const RunArgs& a) {
  StudySessionRequest request = a.request;
  if (request.rig_file.empty()) request.rig_file = cli::data_dir() / "rigs" / "simulated.json";
  // Threshold protocols (staircases, QUEST) and the pulse task run in their own files.
  const nlohmann::json document = read_json_file(request.protocol_file);
  if (is_threshold_protocol(document)) {
    ThresholdStudyRequest threshold{request, {}};
    threshold.observer.noise_kPa = a.sim_threshold_noise_kPa;
    threshold.observer.criterion_kPa = a.sim_threshold_criterion_kPa;
    cli::run_threshold_experiment(threshold, a.quiet);
    return;
  }
  if (is_pulse_protocol(document)) {
    cli::run_pulse_experiment(request, a.quiet);
    return;
  }
  TerminalReport report(request.store_location, a.quiet);
  install_stop_signals();
  const PersonFactory terminal = [](const Protocol& protocol) {
    return std::make_unique<TerminalParticipant>(protocol, std::cout, process_run_control(), STDIN_FILENO);
  };
  const SessionEnd end = run_study_session(request, terminal, report, process_run_control());
  if (const std::string telemetry = telemetry_summary(end); !telemetry.empty()) std::cout << telemetry << "\n";
  if (end.unpushed_trials > 0) {
    std::cerr << "palprig: the lab server has not confirmed every trial yet; they are kept in the journal "
              << end.journal_file.string() << ": push them with palprig store sync --from " << end.journal_file.string()
              << " --to " << request.store_location << "\n";
  }
  if (end.completed) {
    std::cout << "session " << report.session_id()
              << " completed: " << cli::counted(end.committed_trials, "trial", "trials") << " in "
              << request.store_location << "\n";
    return;
  }
  if (!end.fault.empty()) {
    std::cerr << "palprig: rig fault: " << end.fault << "; " << end.committed_trials << " of " << end.total_trials
              << " trials kept, continue with --resume" << (end.fault_record.empty() ? "" : "; " + end.fault_record)
              << "\n";
  } else {
    std::cerr << "palprig: session " << report.session_id() << " stopped after " << end.committed_trials << " of "
              << end.total_trials << " trials (all kept); continue with --resume\n";
  }
  cli::finish(cli::kExitFault);
}

void register_run(CLI::App* experiment) {
  auto a = std::make_shared<RunArgs>();
  auto* sub = experiment->add_subcommand(
      "run",
      "Run (or --resume) a session: trials from a protocol file, answers typed in the terminal or given by a "
      "simulated participant (sim:SEED), each trial committed to the SQLite database as it completes");
  sub->add_option("--protocol", a->request.protocol_file,
                  "Protocol file (JSON), e.g. data/protocols/discrimination_002.json")
      ->required();
  sub->add_option("--participant", a->request.participant_code,
                  "Participant code, or sim:SEED for a simulated participant (model observer)")
      ->required();
  sub->add_option("--db", a->request.store_location,
                  "Trial store: an SQLite file (created when missing) or the lab's PostgreSQL server, "
                  "postgresql://user@host:port/dbname (password from PGPASSWORD or ~/.pgpass)")
      ->required();
  sub->add_option("--journal", a->request.journal_file,
                  "With a postgresql:// store: the bench's local journal (SQLite) every trial is written to first; "
                  "default $PALPRIG_JOURNAL, else ~/.local/state/palprig/journal.sqlite");
  sub->add_option("--rig", a->request.rig_file, "Rig file (JSON); default: the simulated rig data/rigs/simulated.json");
  sub->add_option("--cal", a->request.calibration_file, "Calibration file (JSON); default: paper 002's models");
  sub->add_option("--telemetry", a->request.telemetry_file,
                  "Record every rig tick of the session to FILE (.bin binary, else CSV; as run --telemetry), on the "
                  "session clock of the stored onsets; a new file (an existing one is never overwritten)");
  sub->add_flag("--resume", a->request.resume, "Continue this participant's unfinished session with this protocol");
  sub->add_option("--seed", a->request.seed,
                  "Seed of the generated order; default: derived from participant and protocol");
  sub->add_option("--speed", a->request.speed,
                  "Simulated participant only: 0 = as fast as possible on simulated time (default), "
                  "1 = real time, 10 = ten times faster than real time")
      ->check(CLI::Range(0.0, 1e6));
  sub->add_flag("--quiet", a->quiet, "Simulated participant: no line per trial");
  sub->add_option("--sim-noise-kPa", a->request.model.noise_kPa,
                  "Simulated: sd of each finger's perceived pressure (three fingers at once)")
      ->default_val(a->request.model.noise_kPa)
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--sim-sequential-noise-factor", a->request.model.sequential_noise_factor,
                  "Simulated: noise multiplier when fingers come one after another")
      ->default_val(a->request.model.sequential_noise_factor)
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--sim-criterion-kPa", a->request.model.criterion_kPa,
                  "Simulated: a finger perceived this much above the lowest one has a tumor")
      ->default_val(a->request.model.criterion_kPa)
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--sim-rt-simultaneous", a->request.model.simultaneous.mean_s,
                  "Simulated: mean response time in s, three fingers at once (log-normal; sd --sim-rt-sd-simultaneous)")
      ->default_val(a->request.model.simultaneous.mean_s)
      ->check(CLI::Range(0.05, 600.0));
  sub->add_option("--sim-rt-sd-simultaneous", a->request.model.simultaneous.sd_s, "Simulated: response time sd in s")
      ->default_val(a->request.model.simultaneous.sd_s)
      ->check(CLI::Range(0.0, 600.0));
  sub->add_option("--sim-rt-sequential", a->request.model.sequential.mean_s,
                  "Simulated: mean response time in s, one finger at a time")
      ->default_val(a->request.model.sequential.mean_s)
      ->check(CLI::Range(0.05, 600.0));
  sub->add_option("--sim-rt-sd-sequential", a->request.model.sequential.sd_s, "Simulated: response time sd in s")
      ->default_val(a->request.model.sequential.sd_s)
      ->check(CLI::Range(0.0, 600.0));
  // The simulated threshold observer (experiments/threshold_observer.hpp)
  sub->add_option("--sim-threshold-noise-kPa", a->sim_threshold_noise_kPa,
                  "Simulated, threshold protocols: sd of each finger's perceived pressure per interval")
      ->default_val(a->sim_threshold_noise_kPa)
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option(
         "--sim-threshold-criterion-kPa", a->sim_threshold_criterion_kPa,
         "Simulated, yes-no threshold protocols: 'stronger' when the second interval is felt this much above the first")
      ->default_val(a->sim_threshold_criterion_kPa)
      ->check(CLI::Range(0.0, 100.0));
  sub->callback([a] { run_experiment(*a); });
}

void register_plan(CLI::App* experiment) {
  struct Args {
    std::string protocol, participant, db;
    std::optional<int> number;
    std::optional<std::uint64_t> seed;
  };
  auto a = std::make_shared<Args>();
  auto* sub = experiment->add_subcommand(
      "plan",
      "Print the trial order a participant would get (nothing is stored); counterbalancing follows the participant's "
      "number in the store (--db), which standard error names");
  sub->add_option("--protocol", a->protocol, "Protocol file (JSON)")->required();
  sub->add_option("--participant", a->participant, "Participant code (the default seed derives from it)")->required();
  auto* db = sub->add_option("--db", a->db,
                             "Trial store the session would run on: the participant's number there (or the next "
                             "enrolment's), and an unfinished session's stored order; nothing is written");
  sub->add_option("--number", a->number,
                  "Participant number for counterbalancing without a store (default 1, the first enrolled)")
      ->check(CLI::Range(1, 1000000))
      ->excludes(db);
  sub->add_option("--seed", a->seed, "Seed; default: derived from participant and protocol");
  sub->callback([a] {
    const Protocol p = load_protocol(a->protocol);
    std::string how;
    SessionPlan plan;
    if (!a->db.empty()) {
      SessionPreview preview = preview_session(a->db, p, a->participant);
      const std::string number = "no. " + std::to_string(preview.participant_number);
      if (preview.unfinished_session && !a->seed) {
        how = number + " in " + a->db + ", whose unfinished session " + std::to_string(*preview.unfinished_session) +
              " (" + cli::counted(preview.completed_trials, "trial", "trials") +
              " done) continues this stored order with --resume";
        plan = std::move(preview.plan);
      } else {
        how = preview.enrolled      ? number + ", enrolled in " + a->db
              : preview.store_found ? number + ", the next enrolment in " + a->db + " (not enrolled yet)"
                                    : number + ", the first enrolment (" + a->db + " does not exist yet)";
        plan = make_session_plan(p, preview.participant_number,
                                 a->seed ? *a->seed : default_session_seed(a->participant, p.name));
      }
    } else {
      const int number = a->number.value_or(1);
      how = "no. " + std::to_string(number) +
            (a->number ? std::string(" (--number)")
                       : std::string(" (no --db: the first enrolment; --db STORE plans for the number there)"));
      plan = make_session_plan(p, number, a->seed ? *a->seed : default_session_seed(a->participant, p.name));
    }
    write_plan_csv(std::cout, p, plan);
    std::cerr << "palprig experiment plan: " << p.name << ", participant " << a->participant << " as " << how
              << ", seed " << plan.seed << "\n";
  });
}

}  // namespace

void register_experiment_command(CLI::App& app) {
  auto* experiment = app.add_subcommand("experiment",
                                        "Run study sessions (paper 002's discrimination and localisation "
                                        "studies, or your own protocol files)");
  experiment->require_subcommand(1);
  register_run(experiment);
  register_plan(experiment);
}
