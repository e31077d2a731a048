// Loop wake-up latency at 1 kHz: how late the real-time loop (run_loop in realtime mode, the
// same code `palprig run --realtime` runs) wakes after each absolute CLOCK_MONOTONIC deadline,
// on an idle machine and with every core kept busy by ordinary-priority threads, with each of
// the real-time practices of runtime/realtime.hpp on or off, so each one's effect is measured:
//   practices bits: 1 PM QoS request (/dev/cpu_dma_latency at 0), 2 timer slack 1 ns,
//                   4 prefaulted stack, 8 loop pinned to CPU 1
//   (fifo=1 also locks memory.) Percentiles come from the loop's own latency histogram.
//   build/bin/bench_wakeup                     (5 s per case; run as root or with an rtprio
//                                               limit, else the FIFO cases say it was refused)
#include <benchmark/benchmark.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <atomic>
#include <thread>
#include <vector>

#include "controller/loop_runner.hpp"
#include "formats/rig_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "controller/rig_lease.hpp"

using namespace palprig;

namespace {

class StillPen final : public InputSource {
 public:
  TouchSample latest(double t) noexcept override { return {t, 50, 50, 2.0, true}; }
  double duration_s() const noexcept override { return 0; }
  std::string describe() const override { return "still pen"; }
};

// Ordinary-priority threads spinning on every core while the loop runs.
class CpuLoad {
 public:
  explicit CpuLoad(bool on) {
    if (!on) return;
    const unsigned n = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned i = 0; i < n; ++i)
      threads_.emplace_back([this] {
        volatile std::uint64_t x = 0;
        while (!stop_.load(std::memory_order_relaxed)) x = x + 1;
      });
  }
  ~CpuLoad() {
    stop_ = true;
    for (auto& t : threads_) t.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

void BM_LoopWakeup1kHz(benchmark::State& state) {
  const bool fifo = state.range(0) != 0;
  const bool loaded = state.range(1) != 0;
  const auto practices = state.range(2);
  const RigConfig rig = default_rig();
  const MapScene scene(StiffnessMap(11, 11, 100, 100, std::vector<float>(121, 0.5f)), MapSampling::nearest);
  StillPen pen;
  RunSummary s;
  for (auto _ : state) {
    SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
    backend.open();
    RunOptions opt;
    opt.mode = LoopMode::realtime;
    opt.rate_hz = 1000;
    opt.duration_s = 5.0;
    opt.want_fifo = fifo;
    opt.realtime.fifo = fifo;
    opt.realtime.lock_memory = fifo;
    opt.realtime.pm_qos = (practices & 1) != 0;
    opt.realtime.timer_slack_ns = (practices & 2) ? 1 : 0;
    opt.realtime.prefault_stack_bytes = (practices & 4) ? 256 * 1024 : 0;
    opt.realtime.cpu = (practices & 8) ? 1 : -1;
    CpuLoad load(loaded);
    TickConfig config;
    config.safety.max_lost_time_s = 1e9;  // a measurement: the lost-time fault must not end it
    Rig bench_rig(backend, "the benchmark's simulated rig");
    RigLease lease = bench_rig.lease("the wake-up benchmark");
    s = run_loop(config, scene, pen, lease, opt);
  }
  // Back to ordinary scheduling, every CPU and the default slack for the next case.
  sched_param sp{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
  cpu_set_t all;
  CPU_ZERO(&all);
  for (unsigned c = 0; c < std::thread::hardware_concurrency(); ++c) CPU_SET(c, &all);
  pthread_setaffinity_np(pthread_self(), sizeof all, &all);
  prctl(PR_SET_TIMERSLACK, 0, 0, 0, 0);  // 0: back to the default (50 us)
  munlockall();
  state.counters["p50_us"] = s.wake_latency.p50_us;
  state.counters["p99_us"] = s.wake_latency.p99_us;
  state.counters["p999_us"] = s.wake_latency.p999_us;
  state.counters["max_us"] = s.wake_latency.max_us;
  state.counters["overruns"] = double(s.overruns);
  state.SetLabel(std::string(fifo ? "SCHED_FIFO" : "SCHED_OTHER") + (loaded ? ", all cores busy" : ", idle") + ": " +
                 s.realtime_practices + (s.realtime_note.empty() ? "" : " [" + s.realtime_note + "]"));
}
BENCHMARK(BM_LoopWakeup1kHz)
    ->ArgsProduct({{0}, {0, 1}, {0, 2}})               // SCHED_OTHER: default slack, then slack 1 ns
    ->ArgsProduct({{1}, {0, 1}, {0, 1, 2, 4, 7, 15}})  // FIFO: none, each practice, all, all + pinned
    ->ArgNames({"fifo", "loaded", "practices"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
