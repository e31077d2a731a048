#pragma once
// Readiness of a machine to run palprig's real-time loop: what `palprig rt-check` reports to
// the lab engineer setting up a rig PC. Three parts, each testable on its own:
//   - parsers of the kernel's own text (uname -v, the kernel config, /sys cpu lists), pure;
//   - probe_system(): reads /sys and /proc under given roots (a fixture tree in tests) and
//     tries what the loop will ask for (SCHED_FIFO, mlockall, the PM QoS request);
//   - assess(): the facts plus a measured run of the loop -> findings, advice and a verdict.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/latency_histogram.hpp"

namespace palprig {

enum class PreemptModel { unknown, none, voluntary, full, dynamic, rt };
const char* to_string(PreemptModel m) noexcept;

// "#1 SMP PREEMPT_RT ..." -> rt, "... PREEMPT_DYNAMIC ..." -> dynamic, "... PREEMPT ..." ->
// full; anything else -> unknown (uname -v does not name none or voluntary).
PreemptModel preempt_model_from_uname(std::string_view uname_version) noexcept;
// The text of a kernel config (/proc/config.gz unpacked, /boot/config-*): CONFIG_PREEMPT_RT,
// CONFIG_PREEMPT_DYNAMIC, CONFIG_PREEMPT, CONFIG_PREEMPT_VOLUNTARY, CONFIG_PREEMPT_NONE.
PreemptModel preempt_model_from_config(std::string_view config_text) noexcept;
// /sys/kernel/debug/sched/preempt: "none voluntary (full) lazy" -> full (the one in brackets).
PreemptModel preempt_model_from_debugfs(std::string_view text) noexcept;
// A kernel CPU list ("", "3", "1-3,6"); throws BadInput on anything else.
std::vector<int> parse_cpu_list(std::string_view text);

struct IdleState {
  std::string name;
  int exit_latency_us = 0;
};

struct SystemFacts {
  std::string kernel_release, kernel_version;
  PreemptModel preempt = PreemptModel::unknown;
  std::string preempt_source;  // which file or string told
  int cpus_online = 0;
  std::vector<int> isolated_cpus;
  std::vector<std::string> governors;  // one per CPU with cpufreq; empty: no cpufreq
  std::string idle_driver;             // cpuidle driver, "" when none
  std::vector<IdleState> idle_states;  // of cpu0
  bool hypervisor = false;             // /proc/cpuinfo flags name "hypervisor": a virtual machine
  long rt_runtime_us = -1;             // /proc/sys/kernel/sched_rt_runtime_us (-1: no throttling)
  // What the loop will ask for, tried for real (0/empty when not tried).
  std::optional<std::uint64_t> rtprio_soft, rtprio_hard;  // nullopt: unlimited
  bool fifo_permitted = false;
  std::string fifo_error;
  bool mlock_permitted = false;
  std::string mlock_error;
  bool cpu_dma_latency_ok = false;
  std::string cpu_dma_latency_error;
};

struct ProbeRoots {
  std::filesystem::path sys = "/sys", proc = "/proc", boot = "/boot";
  std::string cpu_dma_latency = "/dev/cpu_dma_latency";
  bool try_permissions = true;  // false in fixture tests: no FIFO/mlock/PM QoS attempts
};

// Reads the files and tries the permissions with the loop's FIFO priority. Never throws for a
// missing file: the fact stays unknown/empty.
SystemFacts probe_system(const ProbeRoots& roots = {}, int fifo_priority = 80);

// A measured run of the loop (palprig's own run_loop in real time).
struct LoopMeasurement {
  double rate_hz = 1000, seconds = 0;
  std::uint64_t ticks = 0, overruns = 0, missed_periods = 0;
  LatencySummary wake, tick;  // tick: the tick plus the backend calls
  std::string practices, note;
};

struct Finding {
  enum class Level { ok, info, warn, fail } level = Level::ok;
  std::string topic, text;
};
const char* to_string(Finding::Level l) noexcept;

struct Readiness {
  bool ready = false;    // the machine held the configured rate
  double budget_us = 0;  // one period
  double needed_us = 0;  // measured p99.9 wake-up latency + p99.9 tick time
  std::vector<Finding> findings;
  std::vector<std::string> advice;
};

// Ready when the measured loop missed at most one period in 10,000 ticks (and at most one in
// any run shorter than that) and its p99.9 wake-up latency plus p99.9 tick time fit in one
// period. The facts only add findings and advice: a machine that holds the rate is ready even
// without PREEMPT_RT, and one that does not is not ready however well it is set up.
Readiness assess(const SystemFacts& facts, const LoopMeasurement& measured, int fifo_priority = 80);

}  // namespace palprig
