// rt-check's parts: the parsers of the kernel's text, probe_system() on fixture /sys and /proc
// trees, and assess()'s verdict and advice.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>

#include "core/error.hpp"
#include "diagnostics/rt_readiness.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

void put(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

void put_gzip(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  gzFile f = gzopen(p.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(gzwrite(f, text.data(), unsigned(text.size())), int(text.size()));
  gzclose(f);
}

// A Debian 12 lab PC as /sys and /proc show it: 4 CPUs, 2-3 isolated, intel_idle with a deep
// C6, one CPU left on powersave.
ProbeRoots lab_pc(const TempDir& d, const std::string& uname_v) {
  const auto sys = d.path() / "sys", proc = d.path() / "proc";
  put(proc / "sys/kernel/osrelease", "6.1.0-13-amd64\n");
  put(proc / "sys/kernel/version", uname_v + "\n");
  put(proc / "sys/kernel/sched_rt_runtime_us", "950000\n");
  put(proc / "cpuinfo",
      "processor\t: 0\nflags\t\t: fpu vme de pse tsc msr\n\nprocessor\t: 1\nflags\t\t: fpu vme de pse tsc msr\n");
  const auto cpu = sys / "devices/system/cpu";
  put(cpu / "online", "0-3\n");
  put(cpu / "isolated", "2-3\n");
  for (int c = 0; c < 4; ++c)
    put(cpu / ("cpu" + std::to_string(c)) / "cpufreq/scaling_governor", c == 1 ? "powersave\n" : "performance\n");
  put(cpu / "cpuidle/current_driver", "intel_idle\n");
  const char* names[] = {"POLL", "C1", "C1E", "C6"};
  const int lat[] = {0, 2, 10, 133};
  for (int s = 0; s < 4; ++s) {
    put(cpu / "cpu0/cpuidle" / ("state" + std::to_string(s)) / "name", std::string(names[s]) + "\n");
    put(cpu / "cpu0/cpuidle" / ("state" + std::to_string(s)) / "latency", std::to_string(lat[s]) + "\n");
  }
  ProbeRoots roots;
  roots.sys = sys;
  roots.proc = proc;
  roots.boot = d.path() / "boot";
  roots.try_permissions = false;
  return roots;
}

LoopMeasurement measured(double p999_us, std::uint64_t overruns, std::uint64_t ticks = 10000) {
  LoopMeasurement m;
  m.rate_hz = 1000;
  m.seconds = double(ticks) / 1000;
  m.ticks = ticks;
  m.overruns = overruns;
  m.wake = {40, 60, p999_us, p999_us + 50, ticks};
  m.tick = {3, 5, 8, 20, ticks};
  return m;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& what) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.find(what) != std::string::npos; });
}

}  // namespace

TEST(RtReadiness, PreemptionModelFromUname) {
  EXPECT_EQ(preempt_model_from_uname("#1 SMP PREEMPT_DYNAMIC @0"), PreemptModel::dynamic);  // this development VM
  EXPECT_EQ(preempt_model_from_uname("#1 SMP PREEMPT_RT Debian 6.1.55-1 (2023-09-29)"), PreemptModel::rt);
  EXPECT_EQ(preempt_model_from_uname("#1 SMP PREEMPT Tue Oct 3 12:00:00 UTC 2023"), PreemptModel::full);
  EXPECT_EQ(preempt_model_from_uname("#1 SMP Debian 6.1.55-1 (2023-09-29)"), PreemptModel::unknown);
  EXPECT_EQ(preempt_model_from_uname("#1 SMP PREEMPT_RTX"), PreemptModel::unknown);  // a word, not a prefix
}

TEST(RtReadiness, PreemptionModelFromKernelConfig) {
  // This machine's /proc/config.gz: a dynamic kernel whose build-time default is none.
  EXPECT_EQ(
      preempt_model_from_config("CONFIG_PREEMPT_BUILD=y\nCONFIG_PREEMPT_NONE=y\n# CONFIG_PREEMPT_VOLUNTARY is not set\n"
                                "# CONFIG_PREEMPT is not set\nCONFIG_PREEMPT_DYNAMIC=y\nCONFIG_PREEMPT_RCU=y\n"),
      PreemptModel::dynamic);
  EXPECT_EQ(preempt_model_from_config("# CONFIG_PREEMPT_NONE is not set\nCONFIG_PREEMPT_RT=y\n"), PreemptModel::rt);
  EXPECT_EQ(preempt_model_from_config("# CONFIG_PREEMPT_RT is not set\nCONFIG_PREEMPT_VOLUNTARY=y\n"),
            PreemptModel::voluntary);
  EXPECT_EQ(preempt_model_from_config("CONFIG_PREEMPT=y\nCONFIG_PREEMPT_COUNT=y\n"), PreemptModel::full);
  EXPECT_EQ(preempt_model_from_config("CONFIG_PREEMPT_NONE=y\n"), PreemptModel::none);
  EXPECT_EQ(preempt_model_from_config("CONFIG_PREEMPT_COUNT=y\n"), PreemptModel::unknown);
}

TEST(RtReadiness, PreemptionModelFromDebugfs) {
  EXPECT_EQ(preempt_model_from_debugfs("none voluntary (full) lazy\n"), PreemptModel::full);
  EXPECT_EQ(preempt_model_from_debugfs("(none) voluntary full\n"), PreemptModel::none);
  EXPECT_EQ(preempt_model_from_debugfs("none voluntary full\n"), PreemptModel::unknown);
}

TEST(RtReadiness, CpuLists) {
  EXPECT_TRUE(parse_cpu_list("\n").empty());
  EXPECT_EQ(parse_cpu_list("3\n"), (std::vector<int>{3}));
  EXPECT_EQ(parse_cpu_list("1-3,6"), (std::vector<int>{1, 2, 3, 6}));
  EXPECT_THROW(parse_cpu_list("a-b"), palprig::BadInput);
  EXPECT_THROW(parse_cpu_list("3-1"), palprig::BadInput);
  EXPECT_THROW(parse_cpu_list("1,,2"), palprig::BadInput);
}

TEST(RtReadiness, ProbeReadsAFixtureLabPc) {
  TempDir d;
  const ProbeRoots roots = lab_pc(d, "#1 SMP PREEMPT_DYNAMIC Debian 6.1.55-1");
  const SystemFacts f = probe_system(roots);
  EXPECT_EQ(f.kernel_release, "6.1.0-13-amd64");
  EXPECT_EQ(f.preempt, PreemptModel::dynamic);
  EXPECT_EQ(f.preempt_source, "uname -v");  // no config, no debugfs, no /sys/kernel/realtime
  EXPECT_EQ(f.cpus_online, 4);
  EXPECT_EQ(f.isolated_cpus, (std::vector<int>{2, 3}));
  EXPECT_EQ(f.governors, (std::vector<std::string>{"performance", "powersave", "performance", "performance"}));
  EXPECT_EQ(f.idle_driver, "intel_idle");
  ASSERT_EQ(f.idle_states.size(), 4u);
  EXPECT_EQ(f.idle_states[3].name, "C6");
  EXPECT_EQ(f.idle_states[3].exit_latency_us, 133);
  EXPECT_EQ(f.rt_runtime_us, 950000);
  EXPECT_FALSE(f.hypervisor);
  EXPECT_FALSE(f.fifo_permitted);  // not tried
}

TEST(RtReadiness, KernelConfigOutranksUnameAndRealtimeFileOutranksBoth) {
  TempDir d;
  ProbeRoots roots = lab_pc(d, "#1 SMP PREEMPT_DYNAMIC Debian");
  put_gzip(roots.proc / "config.gz", "# CONFIG_PREEMPT_RT is not set\nCONFIG_PREEMPT_VOLUNTARY=y\n");
  SystemFacts f = probe_system(roots);
  EXPECT_EQ(f.preempt, PreemptModel::voluntary);
  EXPECT_EQ(f.preempt_source, (roots.proc / "config.gz").string());

  std::filesystem::remove(roots.proc / "config.gz");  // then /boot/config-<release>
  put(roots.boot / "config-6.1.0-13-amd64", "CONFIG_PREEMPT=y\n");
  EXPECT_EQ(probe_system(roots).preempt, PreemptModel::full);

  put(roots.sys / "kernel/realtime", "1\n");
  f = probe_system(roots);
  EXPECT_EQ(f.preempt, PreemptModel::rt);
  EXPECT_EQ(f.preempt_source, (roots.sys / "kernel/realtime").string());
}

TEST(RtReadiness, ProbeOfAnEmptyTreeKnowsNothingAndDoesNotThrow) {
  TempDir d;
  ProbeRoots roots;
  roots.sys = d.path() / "sys";
  roots.proc = d.path() / "proc";
  roots.boot = d.path() / "boot";
  roots.try_permissions = false;
  const SystemFacts f = probe_system(roots);
  EXPECT_EQ(f.preempt, PreemptModel::unknown);
  EXPECT_EQ(f.cpus_online, 0);
  EXPECT_TRUE(f.governors.empty());
  EXPECT_TRUE(f.idle_states.empty());
}

TEST(RtReadiness, VerdictFollowsTheMeasuredLoop) {
  SystemFacts f;
  f.fifo_permitted = f.mlock_permitted = f.cpu_dma_latency_ok = true;
  Readiness r = assess(f, measured(300, 0));
  EXPECT_TRUE(r.ready);
  EXPECT_DOUBLE_EQ(r.budget_us, 1000);
  EXPECT_DOUBLE_EQ(r.needed_us, 308);
  EXPECT_TRUE(assess(f, measured(300, 1)).ready);      // one in 10,000 is allowed
  EXPECT_FALSE(assess(f, measured(300, 2)).ready);     // two are not
  EXPECT_FALSE(assess(f, measured(995, 0)).ready);     // 995 + 8 us does not fit in 1 ms
  EXPECT_FALSE(assess(f, measured(300, 0, 0)).ready);  // nothing measured
  const Readiness bad = assess(f, measured(2500, 40));
  EXPECT_TRUE(any_contains(bad.advice, "lower --rate-hz"));
  ASSERT_FALSE(bad.findings.empty());
  EXPECT_EQ(bad.findings.back().level == Finding::Level::info ? bad.findings[bad.findings.size() - 2].level
                                                              : bad.findings.back().level,
            Finding::Level::fail);
}

TEST(RtReadiness, AdviceNamesTheFixForEachRefusal) {
  TempDir d;
  SystemFacts f = probe_system(lab_pc(d, "#1 SMP PREEMPT_DYNAMIC Debian"));
  f.fifo_error = "Operation not permitted";
  f.mlock_error = "Cannot allocate memory";
  f.cpu_dma_latency_error = "cannot open /dev/cpu_dma_latency (Permission denied)";
  const Readiness r = assess(f, measured(300, 0));
  EXPECT_TRUE(r.ready);  // the facts advise; the measured loop decides
  EXPECT_TRUE(any_contains(r.advice, "rtprio 95 in /etc/security/limits.d"));
  EXPECT_TRUE(any_contains(r.advice, "memlock unlimited"));
  EXPECT_TRUE(any_contains(r.advice, "cpu_dma_latency"));
  EXPECT_TRUE(any_contains(r.advice, "governor to performance"));  // cpu1 on powersave
  EXPECT_TRUE(any_contains(r.advice, "linux-image-rt-amd64"));
  EXPECT_TRUE(any_contains(r.advice, "preempt=full"));

  f.fifo_permitted = f.mlock_permitted = f.cpu_dma_latency_ok = true;
  f.governors.assign(4, "performance");
  f.preempt = PreemptModel::rt;
  EXPECT_TRUE(assess(f, measured(300, 0)).advice.empty());  // isolated CPUs already: nothing to advise
}
