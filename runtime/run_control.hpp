#pragma once
// RunControl: the one handle through which an operator steers whatever drives the rig now (the
// live loop, a study session, a calibration sweep or evaluation). The window's buttons, the
// terminal's keys and the process's SIGINT/SIGTERM handlers write it; the run reads it once per
// tick or pass. Every call is lock-free and never waits, so the real-time loop may read it, and
// the signal entry is async-signal-safe.
//
//   stop     end the run: vented; a session keeps its committed trials and can be resumed.
//            A stop by signal is also a fault of the run (FaultCode::signal, exit 1); an
//            operator's stop is not.
//   vent     held: every setpoint 0 kPa from the next tick and the backend disarmed, the run goes
//            on reading monitors; released: armed again, pressure rises from 0 kPa under the
//            slew limit.
//   pause    a session vents and holds the trial in progress (experiments/session_loop.hpp).
//
// A front end keeps one RunControl and hands it to each run it starts (the window's live loop,
// then a session, then the live loop again); restart() clears an operator's stop between runs.
// A signal is never cleared: the process is going away.
#include <atomic>

namespace palprig {

class RunControl {
 public:
  RunControl() = default;
  RunControl(const RunControl&) = delete;
  RunControl& operator=(const RunControl&) = delete;

  // Any thread.
  void request_stop() noexcept { stop_.store(true, std::memory_order_release); }
  void hold_vent(bool held) noexcept { vent_.store(held, std::memory_order_release); }
  void set_paused(bool paused) noexcept { pause_.store(paused, std::memory_order_release); }
  // A new run on this handle: an operator's stop of the last run is forgotten (a signal is not).
  void restart() noexcept { stop_.store(false, std::memory_order_release); }

  // Async-signal-safe: what the process's SIGINT/SIGTERM handler calls (install_stop_signals).
  void signal_stop(int signal_number) noexcept { signal_.store(signal_number, std::memory_order_release); }

  // The run's side, once per tick or pass.
  bool stop_requested() const noexcept { return stopped_by_operator() || stop_signal() != 0; }
  bool stopped_by_operator() const noexcept { return stop_.load(std::memory_order_acquire); }
  int stop_signal() const noexcept { return signal_.load(std::memory_order_acquire); }  // 0: none
  bool vent_held() const noexcept { return vent_.load(std::memory_order_acquire); }
  bool paused() const noexcept { return pause_.load(std::memory_order_acquire); }

 private:
  std::atomic<bool> stop_{false}, vent_{false}, pause_{false};
  std::atomic<int> signal_{0};
};

// The process's own handle: SIGINT and SIGTERM write it once install_stop_signals() ran. Every
// command and the window hand this one to their runs, so a signal reaches whatever runs.
RunControl& process_run_control() noexcept;
// Route SIGINT and SIGTERM to process_run_control().signal_stop(). Idempotent.
void install_stop_signals() noexcept;

}  // namespace palprig
