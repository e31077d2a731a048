#include "runtime/run_control.hpp"

#include <csignal>

namespace palprig {

RunControl& process_run_control() noexcept {
  static RunControl control;
  return control;
}

namespace {

// Only an atomic store: async-signal-safe (std::atomic<int> is lock-free here, checked below).
extern "C" void palprig_on_stop_signal(int signal_number) { process_run_control().signal_stop(signal_number); }

static_assert(std::atomic<int>::is_always_lock_free, "a signal handler may only store to a lock-free atomic");

}  // namespace

void install_stop_signals() noexcept {
  (void)process_run_control();  // constructed before a signal can arrive
  struct sigaction action {};
  action.sa_handler = palprig_on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace palprig
