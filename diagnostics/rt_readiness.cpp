#include "diagnostics/rt_readiness.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/utsname.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/error.hpp"
#include "runtime/cpu_latency_request.hpp"

namespace palprig {

const char* to_string(PreemptModel m) noexcept {
  switch (m) {
    case PreemptModel::none: return "none (server)";
    case PreemptModel::voluntary: return "voluntary (desktop)";
    case PreemptModel::full: return "full (low-latency desktop)";
    case PreemptModel::dynamic: return "dynamic (chosen at boot)";
    case PreemptModel::rt: return "PREEMPT_RT (real time)";
    case PreemptModel::unknown: break;
  }
  return "unknown";
}

const char* to_string(Finding::Level l) noexcept {
  switch (l) {
    case Finding::Level::ok: return "ok";
    case Finding::Level::info: return "info";
    case Finding::Level::warn: return "warn";
    case Finding::Level::fail: return "FAIL";
  }
  return "?";
}

namespace {

bool has_word(std::string_view text, std::string_view word) {
  for (std::size_t at = text.find(word); at != std::string_view::npos; at = text.find(word, at + 1)) {
    const bool left = at == 0 || text[at - 1] == ' ';
    const std::size_t end = at + word.size();
    const bool right = end == text.size() || text[end] == ' ' || text[end] == '\n';
    if (left && right) return true;
  }
  return false;
}

bool config_set(std::string_view config, std::string_view option) {
  const std::string line = std::string(option) + "=y";
  for (std::size_t at = config.find(line); at != std::string_view::npos; at = config.find(line, at + 1)) {
    const bool starts_line = at == 0 || config[at - 1] == '\n';
    const std::size_t end = at + line.size();
    if (starts_line && (end == config.size() || config[end] == '\n')) return true;
  }
  return false;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && s[b] == ' ') ++b;
  return s.substr(b);
}

std::optional<std::string> read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::optional<std::string> read_gzip(const std::filesystem::path& p) {
  gzFile f = gzopen(p.c_str(), "rb");
  if (!f) return std::nullopt;
  std::string out;
  char buf[16384];
  int n;
  while ((n = gzread(f, buf, sizeof buf)) > 0) out.append(buf, std::size_t(n));
  gzclose(f);
  if (n < 0 || out.empty()) return std::nullopt;
  return out;
}

void try_fifo(SystemFacts& f, int priority) {
  // On a thread of its own, so the calling thread keeps its scheduling.
  std::thread t([&] {
    sched_param sp{};
    sp.sched_priority = priority;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    f.fifo_permitted = rc == 0;
    if (rc != 0) f.fifo_error = std::strerror(rc);
  });
  t.join();
}

void try_mlock(SystemFacts& f) {
  if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
    f.mlock_permitted = true;
    munlockall();
  } else {
    f.mlock_error = std::strerror(errno);
  }
}

std::string us_text(double us) {
  char b[32];
  std::snprintf(b, sizeof b, us >= 1000 ? "%.2f ms" : "%.0f us", us >= 1000 ? us / 1000 : us);
  return b;
}

}  // namespace

PreemptModel preempt_model_from_uname(std::string_view v) noexcept {
  if (has_word(v, "PREEMPT_RT")) return PreemptModel::rt;
  if (has_word(v, "PREEMPT_DYNAMIC")) return PreemptModel::dynamic;
  if (has_word(v, "PREEMPT")) return PreemptModel::full;
  return PreemptModel::unknown;
}

PreemptModel preempt_model_from_config(std::string_view c) noexcept {
  if (config_set(c, "CONFIG_PREEMPT_RT")) return PreemptModel::rt;
  if (config_set(c, "CONFIG_PREEMPT_DYNAMIC")) return PreemptModel::dynamic;
  if (config_set(c, "CONFIG_PREEMPT")) return PreemptModel::full;
  if (config_set(c, "CONFIG_PREEMPT_VOLUNTARY")) return PreemptModel::voluntary;
  if (config_set(c, "CONFIG_PREEMPT_NONE")) return PreemptModel::none;
  return PreemptModel::unknown;
}

PreemptModel preempt_model_from_debugfs(std::string_view t) noexcept {
  const auto open = t.find('('), close = t.find(')');
  if (open == std::string_view::npos || close == std::string_view::npos || close < open) return PreemptModel::unknown;
  const std::string_view mode = t.substr(open + 1, close - open - 1);
  if (mode == "none") return PreemptModel::none;
  if (mode == "voluntary") return PreemptModel::voluntary;
  if (mode == "full" || mode == "lazy") return PreemptModel::full;
  return PreemptModel::unknown;
}

std::vector<int> parse_cpu_list(std::string_view text) {
  std::vector<int> cpus;
  std::string s = trim(std::string(text));
  if (s.empty()) return cpus;
  std::stringstream ss(s);
  std::string part;
  auto number = [&](const std::string& n) {
    if (n.empty() || n.size() > 5 || !std::all_of(n.begin(), n.end(), [](char c) { return c >= '0' && c <= '9'; }))
      throw BadInput("a CPU list like 1-3,6, got \"" + s + "\"");
    return std::stoi(n);
  };
  while (std::getline(ss, part, ',')) {
    const auto dash = part.find('-');
    if (dash == std::string::npos) {
      cpus.push_back(number(part));
    } else {
      const int a = number(part.substr(0, dash)), b = number(part.substr(dash + 1));
      if (b < a) throw BadInput("a CPU list like 1-3,6, got \"" + s + "\"");
      for (int c = a; c <= b; ++c) cpus.push_back(c);
    }
  }
  return cpus;
}

SystemFacts probe_system(const ProbeRoots& roots, int fifo_priority) {
  SystemFacts f;
  const auto cpu_dir = roots.sys / "devices/system/cpu";
  // Kernel and preemption model: the most specific source that answers.
  if (auto v = read_text(roots.proc / "sys/kernel/osrelease")) f.kernel_release = trim(*v);
  if (auto v = read_text(roots.proc / "sys/kernel/version")) f.kernel_version = trim(*v);
  if (auto rt = read_text(roots.sys / "kernel/realtime"); rt && trim(*rt) == "1") {
    f.preempt = PreemptModel::rt;
    f.preempt_source = (roots.sys / "kernel/realtime").string();
  }
  if (f.preempt == PreemptModel::unknown) {
    if (auto d = read_text(roots.sys / "kernel/debug/sched/preempt")) {
      f.preempt = preempt_model_from_debugfs(*d);
      if (f.preempt != PreemptModel::unknown) f.preempt_source = (roots.sys / "kernel/debug/sched/preempt").string();
    }
  }
  if (f.preempt == PreemptModel::unknown) {
    std::optional<std::string> config = read_gzip(roots.proc / "config.gz");
    std::filesystem::path from = roots.proc / "config.gz";
    if (!config && !f.kernel_release.empty()) {
      from = roots.boot / ("config-" + f.kernel_release);
      config = read_text(from);
    }
    if (config) {
      f.preempt = preempt_model_from_config(*config);
      // A dynamic kernel boots in its configured default unless preempt= says otherwise;
      // uname and the config cannot tell which, so it stays "dynamic".
      if (f.preempt != PreemptModel::unknown) f.preempt_source = from.string();
    }
  }
  if (f.preempt == PreemptModel::unknown && !f.kernel_version.empty()) {
    f.preempt = preempt_model_from_uname(f.kernel_version);
    if (f.preempt != PreemptModel::unknown) f.preempt_source = "uname -v";
  }
  if (auto on = read_text(cpu_dir / "online")) {
    try {
      f.cpus_online = int(parse_cpu_list(*on).size());
    } catch (const BadInput&) {}
  }
  if (auto iso = read_text(cpu_dir / "isolated")) {
    try {
      f.isolated_cpus = parse_cpu_list(*iso);
    } catch (const BadInput&) {}
  }
  for (int c = 0; c < 4096; ++c) {
    const auto dir = cpu_dir / ("cpu" + std::to_string(c));
    std::error_code ec;
    if (!std::filesystem::exists(dir, ec)) break;
    if (auto g = read_text(dir / "cpufreq/scaling_governor")) f.governors.push_back(trim(*g));
  }
  if (auto d = read_text(cpu_dir / "cpuidle/current_driver")) f.idle_driver = trim(*d);
  for (int s = 0; s < 64; ++s) {
    const auto dir = cpu_dir / "cpu0/cpuidle" / ("state" + std::to_string(s));
    auto name = read_text(dir / "name");
    if (!name) break;
    IdleState st;
    st.name = trim(*name);
    if (auto lat = read_text(dir / "latency")) st.exit_latency_us = std::atoi(lat->c_str());
    f.idle_states.push_back(st);
  }
  if (auto info = read_text(roots.proc / "cpuinfo")) {
    for (std::size_t at = info->find("flags"); at != std::string::npos; at = info->find("flags", at + 1)) {
      const std::size_t eol = info->find('\n', at);
      if (has_word(std::string_view(*info).substr(at, eol == std::string::npos ? std::string::npos : eol - at),
                   "hypervisor")) {
        f.hypervisor = true;
        break;
      }
    }
  }
  if (auto r = read_text(roots.proc / "sys/kernel/sched_rt_runtime_us")) f.rt_runtime_us = std::atol(r->c_str());

  if (roots.try_permissions) {
    rlimit rl{};
    if (getrlimit(RLIMIT_RTPRIO, &rl) == 0) {
      if (rl.rlim_cur != RLIM_INFINITY) f.rtprio_soft = rl.rlim_cur;
      if (rl.rlim_max != RLIM_INFINITY) f.rtprio_hard = rl.rlim_max;
    }
    try_fifo(f, fifo_priority);
    try_mlock(f);
    CpuLatencyRequest qos(0, roots.cpu_dma_latency);
    f.cpu_dma_latency_ok = qos.held();
    f.cpu_dma_latency_error = qos.note();
  }
  return f;
}

Readiness assess(const SystemFacts& f, const LoopMeasurement& m, int fifo_priority) {
  using L = Finding::Level;
  Readiness r;
  auto add = [&](L level, std::string topic, std::string text) {
    r.findings.push_back({level, std::move(topic), std::move(text)});
  };

  // Kernel.
  const std::string kernel = f.kernel_release.empty() ? std::string("kernel") : "kernel " + f.kernel_release;
  if (f.preempt == PreemptModel::rt) {
    add(L::ok, "kernel", kernel + ", preemption " + to_string(f.preempt) + " (from " + f.preempt_source + ")");
  } else {
    add(L::info, "kernel",
        kernel + ", preemption " + to_string(f.preempt) +
            (f.preempt_source.empty() ? "" : " (from " + f.preempt_source + ")") + ", not PREEMPT_RT");
    r.advice.push_back(
        "for the shortest tails install Debian's PREEMPT_RT kernel (apt install linux-image-rt-amd64) and boot it");
    if (f.preempt == PreemptModel::dynamic || f.preempt == PreemptModel::none || f.preempt == PreemptModel::voluntary)
      r.advice.push_back(
          "on this kernel, boot with preempt=full on the kernel command line for lower latency than the default");
  }
  // Scheduling and memory.
  std::string limit = "rtprio limit ";
  limit += f.rtprio_soft ? std::to_string(*f.rtprio_soft) : "unlimited";
  limit += " (hard ";
  limit += f.rtprio_hard ? std::to_string(*f.rtprio_hard) : "unlimited";
  limit += ")";
  if (f.fifo_permitted) {
    const bool by_limit = !f.rtprio_soft || *f.rtprio_soft >= std::uint64_t(fifo_priority);
    add(L::ok, "scheduling",
        "SCHED_FIFO " + std::to_string(fifo_priority) + " permitted; " + limit +
            (by_limit ? "" : ", so through CAP_SYS_NICE (root)"));
  } else {
    add(L::warn, "scheduling",
        "SCHED_FIFO " + std::to_string(fifo_priority) + " refused (" + f.fifo_error + "); " + limit);
    r.advice.push_back(
        "add the user to a group with rtprio 95 in /etc/security/limits.d (e.g. a file realtime.conf with "
        "\"@realtime - rtprio 95\"), or grant CAP_SYS_NICE, then log in again");
  }
  if (f.mlock_permitted) {
    add(L::ok, "memory", "mlockall permitted");
  } else {
    add(L::warn, "memory", "mlockall refused (" + f.mlock_error + ")");
    r.advice.push_back(
        "allow locked memory: \"@realtime - memlock unlimited\" in /etc/security/limits.d, then log in again");
  }
  if (f.rt_runtime_us >= 0)
    add(L::info, "scheduling",
        "real-time throttling: FIFO threads get at most " + std::to_string(f.rt_runtime_us / 1000) +
            " ms per second (kernel.sched_rt_runtime_us); a runaway loop cannot freeze the machine");
  // Idle states and the PM QoS request.
  std::string idle = f.idle_driver.empty() ? std::string("no cpuidle driver") : "cpuidle driver " + f.idle_driver;
  int deepest_us = 0;
  for (const auto& s : f.idle_states) deepest_us = std::max(deepest_us, s.exit_latency_us);
  if (!f.idle_states.empty()) idle += ", deepest state exit latency " + std::to_string(deepest_us) + " us";
  if (f.cpu_dma_latency_ok) {
    add(L::ok, "idle", "/dev/cpu_dma_latency writable: the loop holds the CPUs out of deep idle; " + idle);
  } else {
    add(L::warn, "idle", "/dev/cpu_dma_latency not usable (" + f.cpu_dma_latency_error + "); " + idle);
    r.advice.push_back(
        "let the loop keep the CPUs out of deep idle: a udev rule KERNEL==\"cpu_dma_latency\", GROUP=\"realtime\", "
        "MODE=\"0660\" in /etc/udev/rules.d, or boot with processor.max_cstate=1 intel_idle.max_cstate=0");
  }
  // Frequency.
  if (f.governors.empty()) {
    add(L::info, "frequency", "no cpufreq (fixed frequency or a virtual machine)");
  } else {
    const bool all_perf =
        std::all_of(f.governors.begin(), f.governors.end(), [](const std::string& g) { return g == "performance"; });
    std::string list;
    for (const auto& g : f.governors) list += (list.empty() ? "" : ",") + g;
    if (all_perf) {
      add(L::ok, "frequency", "governor performance on every CPU");
    } else {
      add(L::warn, "frequency", "CPU frequency governor " + list + " (frequency changes stretch ticks)");
      r.advice.push_back(
          "set the governor to performance: cpupower frequency-set -g performance (package linux-cpupower)");
    }
  }
  if (f.hypervisor)
    add(L::info, "machine",
        "a virtual machine: the hypervisor can stall the guest for milliseconds; a lab PC runs on bare metal");
  // Isolation.
  if (f.isolated_cpus.empty()) {
    add(L::info, "isolation", "no isolated CPUs (" + std::to_string(f.cpus_online) + " online)");
    if (f.cpus_online >= 4)
      r.advice.push_back(
          "optionally isolate one CPU for the loop: isolcpus=N nohz_full=N on the kernel command line, then "
          "palprig run --cpu N");
  } else {
    std::string list;
    for (int c : f.isolated_cpus) list += (list.empty() ? "" : ",") + std::to_string(c);
    add(L::ok, "isolation",
        "isolated CPUs " + list + ": run the loop there with --cpu " + std::to_string(f.isolated_cpus.front()));
  }

  // The measured loop: the verdict.
  r.budget_us = m.rate_hz > 0 ? 1e6 / m.rate_hz : 0;
  r.needed_us = m.wake.p999_us + m.tick.p999_us;
  const std::uint64_t allowed = std::max<std::uint64_t>(1, m.ticks / 10000);
  const bool fits = r.needed_us < r.budget_us;
  const bool few_overruns = m.overruns <= allowed;
  r.ready = m.ticks > 0 && fits && few_overruns;
  char line[400];
  std::snprintf(
      line, sizeof line,
      "%.1f s at %.0f Hz: %llu ticks, %llu overruns (%llu periods skipped); wake-up latency p50/p99/p99.9/max "
      "%s/%s/%s/%s; tick p99.9 %s",
      m.seconds, m.rate_hz, static_cast<unsigned long long>(m.ticks), static_cast<unsigned long long>(m.overruns),
      static_cast<unsigned long long>(m.missed_periods), us_text(m.wake.p50_us).c_str(), us_text(m.wake.p99_us).c_str(),
      us_text(m.wake.p999_us).c_str(), us_text(m.wake.max_us).c_str(), us_text(m.tick.p999_us).c_str());
  add(r.ready ? L::ok : L::fail, "loop", line);
  std::snprintf(
      line, sizeof line,
      "needs wake-up + tick under one period (%s at %.0f Hz) and at most %llu overrun(s): p99.9 %s + %s = %s, %s",
      us_text(r.budget_us).c_str(), m.rate_hz, static_cast<unsigned long long>(allowed),
      us_text(m.wake.p999_us).c_str(), us_text(m.tick.p999_us).c_str(), us_text(r.needed_us).c_str(),
      r.ready ? "holds the rate" : "does NOT hold the rate");
  add(r.ready ? L::ok : L::fail, "loop", line);
  if (!r.ready) {
    r.advice.push_back(
        "the loop missed its budget: follow the advice above, stop other work on the machine, or lower --rate-hz");
    if (f.hypervisor)
      r.advice.push_back(
          "on a virtual machine the hypervisor's stalls show up as millisecond tails no setting inside the guest "
          "removes");
  }
  if (!m.practices.empty()) add(L::info, "loop", "measured with " + m.practices);
  return r;
}

}  // namespace palprig
