// Pulse-localisation sessions from the command line: the simulated participant (sim:SEED)
// palpates each condition's scene through the rig and marks the pulse; each trial is committed
// as it completes; --resume continues the stored order. A person palpates with pen input, which
// the terminal does not read: that runs from the GUI's experiment console.
#include "cli/pulse_experiment.hpp"

#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "sessions/pulse_study.hpp"
#include "sessions/session_telemetry.hpp"
#include "runtime/run_control.hpp"

namespace palprig::cli {

namespace {

class TerminalPulseReport final : public PulseSessionListener {
 public:
  TerminalPulseReport(const std::string& db, bool quiet) : db_(db), quiet_(quiet) {}

  void session_started(const SessionStart& s) override {
    session_id_ = s.session_id;
    std::cout << "palprig experiment: " << s.protocol_name << " (pulse localisation), participant "
              << s.participant.code << ", session " << s.session_id << ", "
              << (s.resumed ? "resumed at trial " + std::to_string(s.start_position + 1) : std::string("new")) << ", "
              << s.total_trials << " trials, seed " << s.seed << ", database " << db_ << "\n"
              << std::flush;
  }
  void trial_committed(const PulseTrialRecord& t, int total) override {
    if (quiet_) return;
    char buf[256];
    if (t.answered) {
      std::snprintf(buf, sizeof buf, "trial %d/%d %s: mark (%.1f, %.1f) mm, %.1f mm from %s, %s", t.position + 1, total,
                    t.condition.c_str(), t.mark_x_mm, t.mark_y_mm, t.distance_mm, t.artery.c_str(),
                    t.hit ? "hit" : "miss");
    } else {
      std::snprintf(buf, sizeof buf, "trial %d/%d %s: no mark", t.position + 1, total, t.condition.c_str());
    }
    std::cout << buf << "\n" << std::flush;
  }
  std::int64_t session_id() const noexcept { return session_id_; }

 private:
  std::string db_;
  bool quiet_;
  std::int64_t session_id_ = 0;
};

}  // namespace

void run_pulse_experiment(const StudySessionRequest& request, bool quiet) {
  TerminalPulseReport report(request.store_location, quiet);
  install_stop_signals();
  const SessionEnd end = run_pulse_study(request, nullptr, report, process_run_control());
  if (const std::string telemetry = telemetry_summary(end); !telemetry.empty()) std::cout << telemetry << "\n";
  if (end.completed) {
    std::cout << "session " << report.session_id()
              << " completed: " << cli::counted(end.committed_trials, "trial", "trials") << " in "
              << request.store_location << "\n";
    return;
  }
  std::cerr << "palprig: " << (end.fault.empty() ? "session stopped" : "rig fault: " + end.fault) << " after "
            << end.committed_trials << " of " << end.total_trials << " trials (all kept); continue with --resume"
            << (end.fault_record.empty() ? "" : "; " + end.fault_record) << "\n";
  finish(kExitFault);
}

}  // namespace palprig::cli
