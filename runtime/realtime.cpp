#include "runtime/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <cerrno>
#include <cstring>

namespace palprig {

namespace {

// Touches `bytes` of stack below the caller's frame so the pages are mapped (and, after
// mlockall, locked) before the first tick needs them. noinline + the volatile buffer keep the
// compiler from dropping the touches.
__attribute__((noinline)) void prefault_stack(std::size_t bytes) noexcept {
  constexpr std::size_t kChunk = std::size_t{16} * 1024;
  volatile unsigned char buf[kChunk];
  for (std::size_t i = 0; i < kChunk; i += 4096) buf[i] = 0;
  asm volatile("" : : "r"(buf) : "memory");  // the touches are the point: keep them
  if (bytes > kChunk) prefault_stack(bytes - kChunk);
}

void append(std::string& note, const std::string& line) {
  if (!note.empty()) note += "; ";
  note += line;
}

}  // namespace

RealtimeSetup enter_realtime(const RealtimeOptions& o) noexcept {
  RealtimeSetup r;
  try {
    if (o.lock_memory) {
      if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0)
        r.memory_locked = true;
      else
        append(r.note, std::string("mlockall refused (") + std::strerror(errno) + ")");
    }
    if (o.fifo) {
      sched_param sp{};
      sp.sched_priority = o.fifo_priority;
      const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
      if (rc == 0)
        r.fifo = true;
      else
        append(r.note, std::string("SCHED_FIFO refused (") + std::strerror(rc) +
                           "): running at normal priority; grant CAP_SYS_NICE or an rtprio limit for lower jitter");
    }
    if (o.pm_qos) {
      r.pm_qos = CpuLatencyRequest(0);
      if (!r.pm_qos.held()) append(r.note, r.pm_qos.note());
    }
    if (o.timer_slack_ns > 0) {
      if (prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(o.timer_slack_ns), 0, 0, 0) == 0)
        r.timer_slack_set = true;
      else
        append(r.note, std::string("timer slack not set (") + std::strerror(errno) + ")");
    }
    if (o.cpu >= 0) {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(o.cpu, &set);
      const int rc = o.cpu < CPU_SETSIZE ? pthread_setaffinity_np(pthread_self(), sizeof set, &set) : EINVAL;
      if (rc == 0)
        r.pinned = true;
      else
        append(r.note, "cannot pin the loop to CPU " + std::to_string(o.cpu) + " (" + std::strerror(rc) + ")");
    }
    if (o.prefault_stack_bytes > 0) {
      prefault_stack(o.prefault_stack_bytes);
      r.stack_prefaulted = true;
    }
  } catch (...) {}
  return r;
}

RealtimeSetup enter_realtime(int fifo_priority, bool want_fifo) noexcept {
  RealtimeOptions o;
  o.fifo = want_fifo;
  o.fifo_priority = fifo_priority;
  o.pm_qos = false;
  o.timer_slack_ns = 0;
  o.prefault_stack_bytes = 0;
  return enter_realtime(o);
}

std::string describe_practices(const RealtimeSetup& r, const RealtimeOptions& o) {
  std::string s;
  if (r.fifo) append(s, "SCHED_FIFO " + std::to_string(o.fifo_priority));
  if (r.memory_locked) append(s, "mlockall");
  if (r.pm_qos.held()) append(s, "PM QoS 0 us");
  if (r.timer_slack_set) append(s, "timer slack " + std::to_string(o.timer_slack_ns) + " ns");
  if (r.stack_prefaulted) append(s, "stack prefaulted " + std::to_string(o.prefault_stack_bytes / 1024) + " KiB");
  if (r.pinned) append(s, "CPU " + std::to_string(o.cpu));
  for (std::size_t i = 0; (i = s.find("; ", i)) != std::string::npos;) s.replace(i, 2, ", ");
  return s.empty() ? "none" : s;
}

bool cpu_allowed(int cpu) noexcept {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (cpu < 0 || cpu >= CPU_SETSIZE || sched_getaffinity(0, sizeof set, &set) != 0) return false;
  return CPU_ISSET(cpu, &set);
}

std::string allowed_cpus_text() {
  std::string s;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (!cpu_allowed(c)) continue;
    int end = c;
    while (end + 1 < CPU_SETSIZE && cpu_allowed(end + 1)) ++end;
    s += (s.empty() ? "" : ",") + std::to_string(c) + (end > c ? "-" + std::to_string(end) : "");
    c = end;
  }
  return s;
}

std::string set_thread_fifo(int priority) noexcept {
  if (priority <= 0) return {};
  sched_param sp{};
  sp.sched_priority = priority;
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
  if (rc == 0) return {};
  try {
    return "SCHED_FIFO " + std::to_string(priority) + " refused (" + std::strerror(rc) + ")";
  } catch (...) {
    return {};
  }
}

}  // namespace palprig
