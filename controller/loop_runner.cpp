#include "controller/loop_runner.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "core/error.hpp"
#include "runtime/monotonic_clock.hpp"
#include "runtime/realtime.hpp"
#include "controller/fault_recorder.hpp"
#include "controller/rig_step.hpp"
#include "controller/telemetry_writer.hpp"
#include "runtime/worker_fault.hpp"

namespace palprig {

namespace {

using Clock = std::chrono::steady_clock;  // CLOCK_MONOTONIC on Linux

// CPU time of the calling thread: a replay's tick cost, blind to the time the thread waited
// for a CPU on a loaded machine. A system call (about 2 us in a gVisor sandbox), so a replay
// reads it only every kCpuMarkTicks ticks and after a tick whose wall time exceeded the period.
std::int64_t thread_cpu_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

// The part of the lost time each period run forgives: a loop may lose 1 period in 100 for
// ever, but not a burst of max_lost_time_s.
constexpr double kLostTimeDrain = 0.01;
constexpr std::uint32_t kCpuMarkTicks = 64;

}  // namespace

RunSummary run_loop(const TickConfig& config, const Scene& scene, InputSource& input, RigLease& lease,
                    const RunOptions& opt) {
  if (!(opt.rate_hz > 0) || opt.rate_hz > 100000) throw BadInput("rate must be in (0, 100000] Hz");
  if (!(opt.duration_s > 0) || !std::isfinite(opt.duration_s)) throw BadInput("duration must be > 0 s");

  RunSummary sum;
  std::unique_ptr<TelemetryWriter> telemetry;
  if (!opt.telemetry_path.empty()) {
    telemetry = std::make_unique<TelemetryWriter>(opt.telemetry_path, telemetry_format_for(opt.telemetry_path));
    sum.telemetry_path = opt.telemetry_path.string();
  }
  // Everything the loop touches is allocated here, before the first tick.
  LatencyHistogram wake_hist, io_hist, tick_hist;
  RigStep rig(config, lease.backend(), RigStepOptions{opt.rate_hz, false});
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
  char worker_detail[256] = {0};
  int consecutive_overruns = 0;
  // Lost time (SafetyLimits::max_lost_time_s): periods not run in time, as seconds.
  double lost_s = 0;
  const double max_lost_s = config.safety.max_lost_time_s;
  char lost_detail[160] = {0};
  auto add_lost = [&](std::uint64_t periods) noexcept {
    lost_s = std::max(0.0, lost_s - kLostTimeDrain * period_s) + double(periods) * period_s;
    if (lost_s > max_lost_s && !rig.faulted()) {
      std::snprintf(lost_detail, sizeof lost_detail,
                    "lost %.3f s of %.0f Hz periods (safety.max_lost_time_s = %.3f s): the loop cannot hold its rate",
                    lost_s, opt.rate_hz, max_lost_s);
      rig.enter_fault(FaultCode::lost_time_limit, lost_detail);
    }
  };
  // Replay: a CPU-time mark and the wall time it was taken at (see thread_cpu_ns).
  std::int64_t cpu_mark = 0, wall_mark = 0;
  std::uint32_t ticks_since_mark = kCpuMarkTicks;
  bool vent_was_held = false;
  // Armed for the run, disarmed (vented) at its end. A backend that refuses (closed) ends the
  // run before the first tick with the reason.
  rig.arm();

  const auto wall_start = Clock::now();
  const std::int64_t start_ns = mono_ns() + period_ns;  // first deadline one period from now
  std::uint64_t k = 0;
  bool stopping = false;  // a stop was asked for: this tick is the last, vented
  while (k < total_ticks && !rig.faulted() && !stopping) {
    const double t_s = double(k) * period_s;
    float wake_us = 0;
    if (realtime) {
      const std::int64_t deadline = start_ns + std::int64_t(k) * period_ns;
      sleep_until_ns(deadline);
      wake_us = float(double(mono_ns() - deadline) / 1000.0);
      wake_hist.record(wake_us);
    }
    if (opt.control && opt.control->stop_signal() != 0) rig.enter_fault(FaultCode::signal);
    if (telemetry && telemetry->failed()) rig.enter_fault(FaultCode::thread_exception);
    if (!rig.faulted() && worker_fault_pending(worker_detail, sizeof worker_detail))
      rig.enter_fault(FaultCode::thread_exception, worker_detail);

    if (!rig.faulted() && ((opt.control && opt.control->stopped_by_operator()) || lease.release_requested())) {
      // A stop asked for from another thread (the window closing, the rig wanted elsewhere),
      // perhaps because a signal came: the signal is looked at again, so a stop it caused is
      // recorded as the signal's fault. Either way this tick is the last: vented, and its
      // record is always written (below).
      if (opt.control && opt.control->stop_signal() != 0)
        rig.enter_fault(FaultCode::signal);
      else
        rig.disarm();
      stopping = true;
    }
    // The operator's VENT (held from another thread) disarms: 0 kPa from this very tick, the
    // loop runs on reading monitors; released, the rig is armed again and pressure rises from
    // 0 kPa under the slew limit.
    const bool vent_held = opt.control && opt.control->vent_held();
    if (!stopping && vent_held != vent_was_held) {
      if (vent_held)
        rig.disarm();
      else
        rig.arm();
      vent_was_held = vent_held;
    }

    if (!realtime && ticks_since_mark >= kCpuMarkTicks) {
      cpu_mark = thread_cpu_ns();
      wall_mark = mono_ns();
      ticks_since_mark = 0;
    }
    const std::int64_t tick_start_ns = realtime ? 0 : mono_ns();
    const TickInputs inputs = opt.switches ? opt.switches->read() : TickInputs{};
    const StepResult& step = rig.step(scene, input.latest(t_s), t_s, inputs);
    if (!realtime) {
      // A replay has no deadlines, but a tick that costs more than its period could not run
      // in real time: its excess counts as lost periods, so a replay of a scene too slow for
      // the rate faults within max_lost_time_s instead of running for hours. A tick within
      // its period of wall time used less CPU than that; a longer one is judged by CPU time
      // (a preempted replay loses nothing): the CPU since the mark less the wall time from the
      // mark to this tick, which the ticks in between cannot have exceeded.
      ++ticks_since_mark;
      const std::int64_t wall_end = mono_ns();
      std::uint64_t lost = 0;
      if (wall_end - tick_start_ns > period_ns) {
        const std::int64_t cpu_now = thread_cpu_ns();
        const std::int64_t cpu = (cpu_now - cpu_mark) - (tick_start_ns - wall_mark);
        if (cpu > period_ns) lost = static_cast<std::uint64_t>((cpu - 1) / period_ns);
        cpu_mark = cpu_now;
        wall_mark = mono_ns();
        ticks_since_mark = 0;
      }
      add_lost(lost);
    }
    io_hist.record(step.io_us);
    tick_hist.record(step.tick_us);

    TelemetryRecord rec = step.tick.record;
    rec.wake_latency_us = wake_us;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      sum.target_kPa[i].add(rec.target_kPa[i]);
      sum.setpoint_kPa[i].add(step.tick.setpoint_kPa[i]);
      sum.monitor_kPa[i].add(step.monitor_kPa[i]);
      sum.force_N[i].add(rec.finger_force_N[i]);
      const auto why = static_cast<std::size_t>(rec.finger_vent[i]);
      if (why > 0 && why < RunSummary::kVentReasons) ++sum.finger_vent_ticks[i][why];
    }
    ++sum.ticks;
    ++k;

    if (realtime) {
      const std::int64_t now = mono_ns();
      const std::int64_t next = start_ns + std::int64_t(k) * period_ns;
      if (now > next) {
        rec.flags |= kOverrun;
        ++sum.overruns;
        // Latched: the loop ends below and disarm() vents at once.
        if (++consecutive_overruns > config.safety.max_consecutive_overruns) rig.enter_fault(FaultCode::overrun_limit);
        // Resynchronise to the next period still in the future: missed periods are skipped,
        // never run late in a burst, and the schedule keeps its original phase (no drift).
        const auto resume = std::min(total_ticks, static_cast<std::uint64_t>((now - start_ns) / period_ns) + 1);
        sum.missed_periods += resume - k;
        add_lost(resume - k);  // skipped periods are time the rig went uncontrolled
        k = resume;
      } else {
        consecutive_overruns = 0;
        add_lost(0);
      }
    }
    if (opt.observer) opt.observer->on_tick(rec);
    if (telemetry) {
      // In real time a full queue drops a record rather than make the rig wait for the disk;
      // the last record of a run that faulted or was stopped (vented, with the reason) is
      // waited for: why the rig vented is always written.
      if (realtime && !rig.faulted() && !stopping)
        telemetry->try_push(rec);
      else
        telemetry->push_wait(rec);
    }
  }
  rig.disarm();  // a run always ends with every channel at 0 kPa
  sum.fault = rig.fault();
  sum.link_outages = rig.link_outages();
  sum.unlinked_ticks = rig.unlinked_steps();
  rt.pm_qos.release();  // the CPUs may sleep deeply again
  sum.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  sum.sim_time_s = double(k) * period_s;
  sum.wake_latency = wake_hist.summary();
  sum.io_time = io_hist.summary();
  sum.tick_time = tick_hist.summary();
  if (telemetry) {
    sum.telemetry_dropped = telemetry->dropped();
    try {
      telemetry->finish();
    } catch (const std::exception& e) {
      sum.fault.latch(FaultCode::thread_exception, sum.sim_time_s, e.what());
    }
  }
  if (sum.fault.active()) {
    const std::filesystem::path folder =
        opt.fault_record_folder.empty() ? std::filesystem::current_path() : opt.fault_record_folder;
    sum.fault_record = save_fault_record(rig.recorder(), sum.fault, lease.rig().holder() + " on " + lease.rig().name(),
                                         opt.telemetry_path, folder, &sum.fault_record_file);
  }
  return sum;
}

}  // namespace palprig
