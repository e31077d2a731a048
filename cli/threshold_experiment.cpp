// Threshold sessions from the command line: a person answers in the terminal ("1"/"2" for the
// stronger interval, "y"/"n" for yes-no), or the simulated threshold observer (sim:SEED)
// answers from what the rig delivered. Every trial is committed with the tracks' state;
// --resume continues the same staircases after a stop or a kill.
#include "cli/threshold_experiment.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "sessions/session_telemetry.hpp"
#include "experiments/terminal_threshold_participant.hpp"
#include "runtime/run_control.hpp"

namespace palprig::cli {

namespace {

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

class TerminalThresholdReport final : public ThresholdSessionListener {
 public:
  TerminalThresholdReport(const std::string& db, bool quiet) : db_(db), quiet_(quiet) {}

  void session_started(const ThresholdStart& s) override {
    const SessionStart& c = s.session;
    simulated_ = c.simulated;
    std::cout << "palprig experiment: " << c.protocol_name << " (threshold, " << to_string(s.method) << ", " << s.tracks
              << " interleaved tracks), participant " << c.participant.code << ", session " << c.session_id << ", "
              << (c.resumed ? "resumed at trial " + std::to_string(c.start_position + 1) : std::string("new"))
              << ", seed " << c.seed << ", database " << db_ << "\n"
              << std::flush;
  }
  void trial_committed(const ThresholdTrialRecord& t) override {
    if (!simulated_) {
      std::cout << "  Answer recorded.\n" << std::flush;
    } else if (!quiet_) {
      std::cout << "trial " << t.position + 1 << " " << t.track_name << " +" << format(t.level_kPa) << " kPa, "
                << (t.answered ? (t.correct ? "correct" : "wrong") : "no answer") << (t.reversal ? ", reversal" : "")
                << "\n"
                << std::flush;
    }
  }

 private:
  std::string db_;
  bool quiet_, simulated_ = false;
};

}  // namespace

void run_threshold_experiment(const ThresholdStudyRequest& request, bool quiet) {
  const std::string& db = request.session.store_location;
  TerminalThresholdReport report(db, quiet);
  install_stop_signals();
  const ThresholdPersonFactory terminal = [](ThresholdMethod method) {
    return std::make_unique<TerminalThresholdParticipant>(method, std::cout, process_run_control(), STDIN_FILENO);
  };
  const ThresholdEnd end = run_threshold_study(request, terminal, report, process_run_control());
  if (const std::string telemetry = telemetry_summary(end.session); !telemetry.empty()) std::cout << telemetry << "\n";
  const int done = end.session.committed_trials;
  if (end.session.completed) {
    std::cout << "session " << end.session_id << " completed: " << cli::counted(done, "trial", "trials") << " in " << db
              << "\n";
    print_estimates(end.tracks);
    return;
  }
  if (!end.session.fault.empty()) {
    std::cerr << "palprig: rig fault: " << end.session.fault << "; " << done << " trials kept, continue with --resume"
              << (end.session.fault_record.empty() ? "" : "; " + end.session.fault_record) << "\n";
  } else {
    std::cerr << "palprig: session " << end.session_id << " stopped after " << done
              << " trials (all kept); continue with --resume\n";
  }
  finish(kExitFault);
}

}  // namespace palprig::cli
