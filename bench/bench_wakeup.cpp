// Loop wake-up latency at 1 kHz: how late the real-time loop (run_loop in realtime mode, the
// same code `palprig run --realtime` runs) wakes after each absolute CLOCK_MONOTONIC deadline,
// with and without SCHED_FIFO (+ mlockall), on an idle machine and with every core kept busy by
// ordinary-priority threads. Percentiles come from the loop's own latency histogram.
//   build/bin/bench_wakeup                     (5 s per case; run as root or with an rtprio
//                                               limit, else the FIFO cases say it was refused)
#include <benchmark/benchmark.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <thread>
#include <vector>

#include "controller/loop_runner.hpp"
#include "formats/rig_file.hpp"
#include "rigs/simulated_rig.hpp"

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
    CpuLoad load(loaded);
    s = run_loop(TickConfig{}, scene, pen, backend, opt);
  }
  // Back to ordinary scheduling for the next case (run_loop raised this thread to FIFO).
  sched_param sp{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
  state.counters["p50_us"] = s.wake_latency.p50_us;
  state.counters["p99_us"] = s.wake_latency.p99_us;
  state.counters["p999_us"] = s.wake_latency.p999_us;
  state.counters["max_us"] = s.wake_latency.max_us;
  state.counters["overruns"] = double(s.overruns);
  state.SetLabel(std::string(fifo ? "SCHED_FIFO" : "SCHED_OTHER") + (loaded ? ", all cores busy" : ", idle") +
                 (s.realtime_note.empty() ? "" : " [" + s.realtime_note + "]"));
}
BENCHMARK(BM_LoopWakeup1kHz)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"fifo", "loaded"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
