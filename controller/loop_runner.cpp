#include "controller/loop_runner.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "runtime/monotonic_clock.hpp"
#include "runtime/realtime.hpp"
#include "controller/telemetry_writer.hpp"
#include "runtime/worker_fault.hpp"

namespace palprig {

namespace {

using Clock = std::chrono::steady_clock;  // CLOCK_MONOTONIC on Linux

}  // namespace

RunSummary run_loop(const TickConfig& config, const Scene& scene, InputSource& input, RigBackend& backend,
                    const RunOptions& opt) {
  if (!(opt.rate_hz > 0) || opt.rate_hz > 100000) throw std::invalid_argument("rate must be in (0, 100000] Hz");
  if (!(opt.duration_s > 0) || !std::isfinite(opt.duration_s)) throw std::invalid_argument("duration must be > 0 s");

  RunSummary sum;
  std::unique_ptr<TelemetryWriter> telemetry;
  if (!opt.telemetry_path.empty()) {
    telemetry = std::make_unique<TelemetryWriter>(opt.telemetry_path, telemetry_format_for(opt.telemetry_path));
    sum.telemetry_path = opt.telemetry_path.string();
  }
  // Everything the loop touches is allocated here, before the first tick.
  LatencyHistogram wake_hist, io_hist, tick_hist;
  TickState state = make_tick_state(config);
  const bool realtime = opt.mode == LoopMode::realtime;
  const double period_s = 1.0 / opt.rate_hz;
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / opt.rate_hz));
  const auto total_ticks = static_cast<std::uint64_t>(std::llround(opt.duration_s * opt.rate_hz));
  RealtimeSetup rt;  // held until the loop has vented: the PM QoS request lives in it
  if (realtime) {
    RealtimeOptions ro = opt.realtime;
    ro.fifo = ro.fifo && opt.want_fifo;
    rt = enter_realtime(ro);
    sum.realtime_note = rt.note;
    sum.realtime_practices = describe_practices(rt, ro);
  }
  char fault_detail[256] = {0};
  int consecutive_overruns = 0;
  bool was_linked = true;

  const auto wall_start = Clock::now();
  const std::int64_t start_ns = mono_ns() + period_ns;  // first deadline one period from now
  std::uint64_t k = 0;
  while (k < total_ticks) {
    const double t_s = double(k) * period_s;
    float wake_us = 0;
    if (realtime) {
      const std::int64_t deadline = start_ns + std::int64_t(k) * period_ns;
      sleep_until_ns(deadline);
      wake_us = float(double(mono_ns() - deadline) / 1000.0);
      wake_hist.record(wake_us);
    }
    if (opt.stop_signal && opt.stop_signal->load(std::memory_order_relaxed) != 0) state.enter_fault(FaultCode::signal);
    if (telemetry && telemetry->failed()) state.enter_fault(FaultCode::thread_exception);
    if (state.fault == FaultCode::none && worker_fault_pending(fault_detail, sizeof fault_detail))
      state.enter_fault(FaultCode::thread_exception);
    // A backend whose link dropped is vented and reconnecting (an alarm, not a latched fault):
    // the loop sends 0 kPa and restarts the tick's slew limiter from 0, so pressure rises again
    // under the slew limit when the link is back.
    const bool linked = backend.linked();
    if (!linked) {
      ++sum.unlinked_ticks;
      if (was_linked) ++sum.link_outages;
    }
    was_linked = linked;

    if (opt.stop_request && opt.stop_request->load(std::memory_order_relaxed)) break;
    const bool vent_held = opt.vent_request && opt.vent_request->load(std::memory_order_relaxed);

    const std::int64_t tick_start = mono_ns();
    const TouchSample sample = input.latest(t_s);
    TickResult r = tick(state, config, scene, sample, t_s);
    if (vent_held) r.record.flags |= kVented;
    if (!linked || vent_held) {
      r.setpoint_kPa = {};
      state.last_setpoint_kPa = {};
      for (int i = 0; i < kFingerCount; ++i) r.record.setpoint_kPa[i] = 0.0f;
    }

    const std::int64_t io_start = mono_ns();
    ChannelPressures monitor{};
    bool io_ok = backend.write(r.setpoint_kPa, t_s) == BackendStatus::ok;
    io_ok = io_ok && backend.read_monitors(monitor, t_s) == BackendStatus::ok;
    const std::int64_t io_end = mono_ns();
    if (!io_ok && state.fault == FaultCode::none) {
      state.enter_fault(FaultCode::backend_error);
      std::snprintf(fault_detail, sizeof fault_detail, "%s", backend.last_error());
    }
    io_hist.record(double(io_end - io_start) / 1000.0);
    tick_hist.record(double(io_start - tick_start) / 1000.0);

    r.record.wake_latency_us = wake_us;
    r.record.io_us = float(double(io_end - io_start) / 1000.0);
    for (int i = 0; i < kFingerCount; ++i) {
      r.record.monitor_kPa[i] = float(monitor[i]);
      sum.target_kPa[i].add(r.record.target_kPa[i]);
      sum.setpoint_kPa[i].add(r.setpoint_kPa[i]);
      sum.monitor_kPa[i].add(monitor[i]);
    }
    r.record.fault = state.fault;
    if (!linked && state.fault == FaultCode::none) {
      // The alarm: not latched, the run goes on vented and resumes when the link returns.
      r.record.fault = FaultCode::backend_error;
      r.record.flags |= kVented;
    }
    ++sum.ticks;
    ++k;

    if (realtime) {
      const std::int64_t now = mono_ns();
      const std::int64_t next = start_ns + std::int64_t(k) * period_ns;
      if (now > next) {
        r.record.flags |= kOverrun;
        ++sum.overruns;
        if (++consecutive_overruns > config.safety.max_consecutive_overruns) state.enter_fault(FaultCode::overrun_limit);
        // Resynchronise to the next period still in the future: missed periods are skipped,
        // never run late in a burst, and the schedule keeps its original phase (no drift).
        const auto resume =
            std::min(total_ticks, static_cast<std::uint64_t>((now - start_ns) / period_ns) + 1);
        sum.missed_periods += resume - k;
        k = resume;
      } else {
        consecutive_overruns = 0;
      }
    }
    if (opt.observer) opt.observer->on_tick(r.record);
    if (telemetry) {
      if (realtime) telemetry->try_push(r.record);
      else telemetry->push_wait(r.record);
    }
    if (state.fault != FaultCode::none) {
      backend.vent();
      sum.fault = state.fault;
      sum.fault_t_s = t_s;
      break;
    }
  }
  backend.vent();  // a run always ends with every channel at 0 kPa
  rt.pm_qos.release();  // the CPUs may sleep deeply again
  sum.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  sum.sim_time_s = double(k) * period_s;
  sum.wake_latency = wake_hist.summary();
  sum.io_time = io_hist.summary();
  sum.tick_time = tick_hist.summary();
  sum.fault_detail = fault_detail;
  if (telemetry) {
    sum.telemetry_dropped = telemetry->dropped();
    try {
      telemetry->finish();
    } catch (const std::exception& e) {
      if (sum.fault == FaultCode::none) sum.fault = FaultCode::thread_exception;
      sum.fault_detail = e.what();
    }
  }
  return sum;
}

}  // namespace palprig
