#pragma once
// Real-time set-up for the loop thread, the practices cyclictest and ros2_control's real-time
// guide share, each one optional and each one reported:
//   - mlockall(MCL_CURRENT | MCL_FUTURE): no page fault on the loop's memory;
//   - SCHED_FIFO at `fifo_priority` (80 by default, see thread_priorities.hpp);
//   - a PM QoS request (/dev/cpu_dma_latency held at 0 us) so no CPU sleeps in a deep idle
//     state between ticks (CpuLatencyRequest, held by the returned RealtimeSetup);
//   - timer slack of the thread at 1 ns (the default 50 us slack delays every wake-up of a
//     SCHED_OTHER thread; FIFO threads get none anyway);
//   - a prefaulted stack (touch it once after mlockall, so the first deep call does not fault);
//   - optional pinning of the loop thread to one CPU (`cpu`, e.g. an isolated one).
// When the system refuses one, the loop still runs and `note` says which and why in one line.
#include <cstddef>
#include <string>

#include "runtime/cpu_latency_request.hpp"

namespace palprig {

struct RealtimeOptions {
  bool fifo = true;
  int fifo_priority = 80;
  bool lock_memory = true;
  bool pm_qos = true;                                          // off: a laptop on battery
  long timer_slack_ns = 1;                                     // 0: leave the thread's slack alone
  std::size_t prefault_stack_bytes = std::size_t{256} * 1024;  // 0: no prefault
  int cpu = -1;                                                // -1: no pinning
};

struct RealtimeSetup {
  bool memory_locked = false;
  bool fifo = false;
  bool timer_slack_set = false;
  bool stack_prefaulted = false;
  bool pinned = false;
  CpuLatencyRequest pm_qos;  // held as long as this object lives
  std::string note;          // empty when everything asked for was granted
};

// Applies the options to the calling thread (and mlockall/PM QoS to the process). Never throws.
RealtimeSetup enter_realtime(const RealtimeOptions& options) noexcept;
// Kept for callers that only want FIFO and locked memory (no PM QoS, no pinning).
RealtimeSetup enter_realtime(int fifo_priority = 80, bool want_fifo = true) noexcept;

// What was in effect, for summaries: "SCHED_FIFO 80, mlockall, PM QoS 0 us, timer slack 1 ns,
// stack prefaulted 256 KiB, CPU 1" (only the parts granted).
std::string describe_practices(const RealtimeSetup& setup, const RealtimeOptions& options);

// The CPUs this process may run on, as a kernel CPU list ("0-1"), and whether `cpu` is one of
// them: `--cpu` is checked against it before anything moves.
std::string allowed_cpus_text();
bool cpu_allowed(int cpu) noexcept;

// Puts the calling thread on SCHED_FIFO at `priority` (0: leave it at normal scheduling).
// Returns an empty string on success, else one line saying why not (for worker threads:
// the Modbus bus thread and the tablet reader, whose priorities sit below the loop's).
std::string set_thread_fifo(int priority) noexcept;

}  // namespace palprig
