// palprig rt-check: is this machine ready to run the real-time loop at the configured rate?
// Reports the kernel's preemption model, whether SCHED_FIFO, mlockall and the PM QoS request
// are permitted, the CPU frequency governor, isolated CPUs, and a measured run of palprig's
// own loop beside the period it must fit in, with advice lines; and what the user running it
// lacks to drive the rig without root (the palprig group, its limits, the devices). Exit 0 when the machine held
// the rate, 1 when it did not, 2 on a bad argument.
#include <iomanip>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "diagnostics/loop_probe.hpp"
#include "core/input_error.hpp"
#include "diagnostics/rig_user_access.hpp"
#include "diagnostics/rt_readiness.hpp"

using namespace palprig;

namespace {

nlohmann::json to_json(const SystemFacts& f, const LoopMeasurement& m, const Readiness& r) {
  using nlohmann::json;
  auto lat = [](const LatencySummary& l) {
    return json{{"p50_us", l.p50_us}, {"p99_us", l.p99_us}, {"p999_us", l.p999_us}, {"max_us", l.max_us}};
  };
  auto opt_limit = [](const std::optional<std::uint64_t>& v) { return v ? json(*v) : json("unlimited"); };
  json idle = json::array();
  for (const auto& s : f.idle_states) idle.push_back({{"name", s.name}, {"exit_latency_us", s.exit_latency_us}});
  json findings = json::array();
  for (const auto& x : r.findings)
    findings.push_back({{"level", to_string(x.level)}, {"topic", x.topic}, {"text", x.text}});
  return json{
      {"ready", r.ready},
      {"kernel",
       {{"release", f.kernel_release},
        {"version", f.kernel_version},
        {"preemption", to_string(f.preempt)},
        {"preempt_rt", f.preempt == PreemptModel::rt},
        {"preemption_source", f.preempt_source}}},
      {"virtual_machine", f.hypervisor},
      {"sched_fifo",
       {{"permitted", f.fifo_permitted},
        {"error", f.fifo_error},
        {"rtprio_soft", opt_limit(f.rtprio_soft)},
        {"rtprio_hard", opt_limit(f.rtprio_hard)},
        {"rt_runtime_us", f.rt_runtime_us}}},
      {"mlockall", {{"permitted", f.mlock_permitted}, {"error", f.mlock_error}}},
      {"cpu_dma_latency", {{"available", f.cpu_dma_latency_ok}, {"error", f.cpu_dma_latency_error}}},
      {"governors", f.governors},
      {"cpuidle", {{"driver", f.idle_driver}, {"states", idle}}},
      {"cpus_online", f.cpus_online},
      {"isolated_cpus", f.isolated_cpus},
      {"loop",
       {{"rate_hz", m.rate_hz},
        {"seconds", m.seconds},
        {"ticks", m.ticks},
        {"overruns", m.overruns},
        {"missed_periods", m.missed_periods},
        {"wake_latency", lat(m.wake)},
        {"tick_time", lat(m.tick)},
        {"budget_us", r.budget_us},
        {"needed_us", r.needed_us},
        {"practices", m.practices},
        {"note", m.note}}},
      {"findings", findings},
      {"advice", r.advice},
  };
}

}  // namespace

void register_rt_check_command(CLI::App& app) {
  struct Options {
    double rate_hz = 1000, seconds = 10;
    RealtimeOptions rt;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "rt-check",
      "Readiness of this machine for the real-time loop: kernel, permissions, idle states, and a measured run");
  sub->add_option("--rate-hz", o->rate_hz, "The loop rate the rig will run at")
      ->default_val(1000.0)
      ->check(CLI::Range(1.0, 100000.0));
  sub->add_option("--seconds", o->seconds, "Length of the measured run of the loop")
      ->default_val(10.0)
      ->check(CLI::Range(0.1, 3600.0));
  sub->add_option("--priority", o->rt.fifo_priority, "SCHED_FIFO priority of the loop, as for palprig run")
      ->default_val(80)
      ->check(CLI::Range(1, 98));
  sub->add_option("--cpu", o->rt.cpu, "Pin the measured loop to this CPU, as for palprig run")
      ->check(CLI::Range(0, 1023));
  sub->add_flag(
      "--no-pm-qos", [o](std::int64_t) { o->rt.pm_qos = false; },
      "Measure without the PM QoS request, as for palprig run");
  sub->add_flag("--json", o->json, "Print the report as one JSON object");
  sub->callback([o]() {
    if (o->rt.cpu >= 0 && !cpu_allowed(o->rt.cpu))
      throw InputError("--cpu", std::to_string(o->rt.cpu),
                       "a CPU this process may run on (" + allowed_cpus_text() + ")");
    const SystemFacts facts = probe_system(ProbeRoots{}, o->rt.fifo_priority);
    if (!o->json)
      std::cout << "palprig rt-check: measuring the loop at " << o->rate_hz << " Hz for " << o->seconds << " s ..."
                << std::endl;
    const LoopMeasurement m = measure_loop(o->rate_hz, o->seconds, o->rt);
    const Readiness r = assess(facts, m, o->rt.fifo_priority);
    const RigUserAccess access = check_rig_user_access(this_process_probe());
    if (o->json) {
      nlohmann::json j = to_json(facts, m, r);
      for (const auto& f : access.findings)
        j["user_access"].push_back({{"level", to_string(f.level)}, {"topic", f.topic}, {"text", f.text}});
      for (const auto& advice : access.advice) j["advice"].push_back(advice);
      std::cout << j.dump(2) << "\n";
    } else {
      for (const auto& f : access.findings)
        std::cout << "  " << std::left << std::setw(5) << to_string(f.level) << " " << std::setw(11) << f.topic
                  << f.text << "\n";
      for (const auto& a : access.advice) std::cout << "  advice: " << a << "\n";
      for (const auto& f : r.findings)
        std::cout << "  " << std::left << std::setw(5) << to_string(f.level) << " " << std::setw(11) << f.topic
                  << f.text << "\n";
      for (const auto& a : r.advice) std::cout << "  advice: " << a << "\n";
      std::cout << "palprig rt-check: " << (r.ready ? "ready" : "NOT ready") << " for " << o->rate_hz << " Hz\n";
    }
    if (!r.ready) cli::finish(cli::kExitFault);
  });
}
