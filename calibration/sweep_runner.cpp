#include "calibration/sweep_runner.hpp"

#include "controller/fault_recorder.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/error.hpp"
#include "calibration/pacer.hpp"
#include "controller/rig_step.hpp"

namespace palprig {

namespace {

// Whether the newest `window` samples of every selected channel have stopped moving.
bool monitors_settled(const std::vector<SweepSample>& s, std::size_t window, const std::array<bool, kFingerCount>& on,
                      double band_kPa) {
  if (s.size() < window || window < 2) return false;
  const std::size_t half = window / 2, first = s.size() - window;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!on[c]) continue;
    double older = 0, newer = 0;
    for (std::size_t k = 0; k < half; ++k) older += s[first + k].monitor_kPa[c];
    for (std::size_t k = window - half; k < window; ++k) newer += s[first + k].monitor_kPa[c];
    if (std::abs(newer - older) / double(half) > band_kPa) return false;
  }
  return true;
}

// Tries at one hold before a failing link ends the sweep.
constexpr int kMaxHoldAttempts = 3;

}  // namespace

SweepOutcome run_calibration_sweep(RigLease& lease, const SweepSchedule& schedule, const SweepRunOptions& o,
                                   SweepSink& sink, const SweepProgress& progress) {
  if (!(o.settle_window_s > 0) || !(o.settle_band_kPa > 0) || !(o.average_s > 0) || !(o.min_hold_s >= 0) ||
      !(o.max_hold_s > o.min_hold_s) || !(o.max_hold_s >= o.settle_window_s + o.average_s) || !(o.max_hold_s <= 3600) ||
      !(o.rate_hz > 0) || !(o.rate_hz <= 10000) || !(o.slew_kPa_per_s > 0) || !(o.dynamics_rate_hz > 0) ||
      !(o.dynamics_rate_hz <= 10000))
    throw BadInput(
        "sweep: need settle window, band and averaging window > 0, a max hold above min hold and both windows (at "
        "most an hour), rates in (0, 10000] Hz and a slew rate > 0");
  bool any = false;
  for (bool on : o.channels) any = any || on;
  if (!any) throw BadInput("sweep: no channel selected");

  // Every setpoint passes the controller's safety stage through a rig step (tick_direct without
  // a hysteresis inverse): clamped to the rig's p_max, slew-limited at the rig's own rate
  // (o.slew_kPa_per_s, from the rig file), vented on any fault. No exemption: a staircase step
  // of 10 kPa at 100 Hz passes in one tick at the default 2000 kPa/s; larger steps ramp at the
  // rate the regulators slew at anyway, and the settle test waits the ramp out.
  TickConfig direct;
  RigBackend& backend = lease.backend();
  direct.safety.p_max_kPa = backend.p_max_kPa();
  direct.safety.slew_kPa_per_s = o.slew_kPa_per_s;
  RigStep rig(direct, backend, RigStepOptions{o.rate_hz, true});

  Pacer pacer(o.rate_hz, o.realtime);
  const auto window = static_cast<std::size_t>(std::max(2.0, std::round(o.settle_window_s * o.rate_hz)));
  const auto average = static_cast<std::size_t>(std::max(1.0, std::round(o.average_s * o.rate_hz)));
  std::vector<SweepSample> hold_samples;
  hold_samples.reserve(static_cast<std::size_t>(o.max_hold_s * o.rate_hz) + 2);

  SweepOutcome out;
  out.holds_planned = schedule.holds.size();
  std::uint64_t k = 0;
  double t_s = 0;
  ExcursionWatch excursions(o.tolerance_kPa);
  // Progress by the holds' expected rig time: a timed hold its duration, a held level about the
  // settle test and the averaging window.
  std::vector<double> expected_s(schedule.holds.size());
  double total_s = 0;
  int repeats = 0;
  for (std::size_t h = 0; h < schedule.holds.size(); ++h) {
    const SweepHold& hold = schedule.holds[h];
    expected_s[h] = hold.duration_s > 0 ? hold.duration_s : o.settle_window_s + o.average_s;
    total_s += expected_s[h];
    repeats = std::max(repeats, hold.repeat);
  }
  double done_s = 0, current_expected_s = 0, current_start_s = 0;
  ProgressMeter meter("sweep", o.progress_report);
  auto tick_progress = [&] {
    meter.update((done_s + std::min(t_s - current_start_s, current_expected_s)) / std::max(total_s, 1e-9));
  };
  if (rig.arm() != BackendStatus::ok) {
    out.faulted = true;
    out.fault = rig.fault().detail();
    return out;
  }
  // A step is usable only when its setpoints reached the regulators and every selected monitor
  // has a reading: during a link outage (Modbus reconnecting) the rig step vents and monitors
  // read NaN, so such samples are not the response to the hold's level.
  auto usable = [&](const StepResult& step) {
    if (!step.linked || !step.armed) return false;
    for (std::size_t c = 0; c < kFingerCount; ++c)
      if (o.channels[c] && !std::isfinite(step.monitor_kPa[c])) return false;
    return true;
  };
  enum class HoldEnd { settled, unsettled, interrupted, ended };  // ended: stop or fault
  // One hold at `level` from the rig's present state: the settle test, then the averaging window
  // (recorded holds) or nothing more (approach holds). Samples go to hold_samples.
  // A timed hold (step, chirp): its own pacer at the dynamics rate, continuing the time base;
  // the main pacer resumes after it.
  auto run_timed_hold = [&](const SweepHold& hold, HoldOutcome& result) {
    hold_samples.clear();
    result = HoldOutcome{};
    result.timed = true;
    Pacer fast(o.dynamics_rate_hz, o.realtime);
    const double t0 = t_s + fast.period_s();
    const auto n = static_cast<std::uint64_t>(std::ceil(hold.duration_s * o.dynamics_rate_hz));
    std::size_t first = kFingerCount;
    for (std::size_t c = 0; c < kFingerCount; ++c)
      if (o.channels[c] && first == kFingerCount) first = c;
    HoldEnd end = HoldEnd::settled;
    for (std::uint64_t j = 0; j < n; ++j) {
      const double t = t0 + fast.wait_for_tick(j);
      t_s = t;
      tick_progress();
      if (o.control && o.control->stop_requested()) {
        out.stopped = true;
        out.stop_signal = o.control->stop_signal();
        end = HoldEnd::ended;
        break;
      }
      const double level = hold.command_at(t - t0);
      ChannelPressures target{};
      for (std::size_t c = 0; c < kFingerCount; ++c) target[c] = o.channels[c] ? level : 0.0;
      const StepResult& step = rig.step_direct(target, t);
      if (rig.faulted()) {
        out.faulted = true;
        out.fault = rig.fault() == FaultCode::backend_error ? rig.fault().detail()
                                                            : std::string("safety stage: ") + to_string(rig.fault());
        end = HoldEnd::ended;
        break;
      }
      if (!usable(step)) {
        end = HoldEnd::interrupted;
        break;
      }
      SweepSample s;
      s.t_s = t;
      s.command_kPa = step.tick.setpoint_kPa[first];  // what the regulators were sent
      s.monitor_kPa = step.monitor_kPa;
      s.sensor = step.sensor;
      hold_samples.push_back(s);
      result.hold_s = t - t0;
    }
    // The main pacer goes on from the first of its ticks after this hold.
    k = std::max<std::uint64_t>(k, static_cast<std::uint64_t>(std::ceil(t_s / pacer.period_s() + 1e-9)));
    return end;
  };
  auto run_hold = [&](double level, bool record, HoldOutcome& result) {
    ChannelPressures target{};
    for (std::size_t c = 0; c < kFingerCount; ++c) target[c] = o.channels[c] ? level : 0.0;
    hold_samples.clear();
    result = HoldOutcome{};
    std::size_t averaging_from = 0;  // index of the first averaged sample, once settled
    bool averaging = false;
    const double hold_start_s = pacer.period_s() * double(k);
    for (;;) {
      t_s = pacer.wait_for_tick(k++);
      tick_progress();
      if (o.control && o.control->stop_requested()) {
        out.stopped = true;
        out.stop_signal = o.control->stop_signal();
        return HoldEnd::ended;
      }
      const StepResult& step = rig.step_direct(target, t_s);
      if (rig.faulted()) {
        out.faulted = true;
        out.fault = rig.fault() == FaultCode::backend_error ? rig.fault().detail()
                                                            : std::string("safety stage: ") + to_string(rig.fault());
        return HoldEnd::ended;
      }
      if (!usable(step)) return HoldEnd::interrupted;
      SweepSample s;
      s.t_s = t_s;
      s.command_kPa = level;
      s.monitor_kPa = step.monitor_kPa;
      s.sensor = step.sensor;  // NaN when the rig has no sensor
      hold_samples.push_back(s);
      result.hold_s = t_s - hold_start_s;
      if (!averaging && result.hold_s >= o.min_hold_s &&
          monitors_settled(hold_samples, window, o.channels, o.settle_band_kPa)) {
        if (!record) {
          result.settled = true;
          return HoldEnd::settled;
        }
        averaging = true;
        averaging_from = hold_samples.size();
      } else if (averaging) {
        for (std::size_t c = 0; c < kFingerCount; ++c)
          if (o.channels[c]) excursions.add(c, t_s, level, step.monitor_kPa[c]);
      }
      if (averaging && hold_samples.size() - averaging_from >= average) {
        result.settled = true;
        for (std::size_t j = averaging_from; j < hold_samples.size(); ++j) hold_samples[j].settled = true;
        return HoldEnd::settled;
      }
      if (result.hold_s >= o.max_hold_s) return HoldEnd::unsettled;  // recorded, but marked unsettled
    }
  };
  // After an outage the rig was vented: wait (vented) until steps are usable again, at most
  // max_hold_s. Returns false when the sweep ends (stop, fault, or the link stays down).
  auto wait_for_link = [&] {
    const double since = t_s;
    const ChannelPressures vented{};
    for (;;) {
      t_s = pacer.wait_for_tick(k++);
      tick_progress();
      if (o.control && o.control->stop_requested()) {
        out.stopped = true;
        out.stop_signal = o.control->stop_signal();
        return false;
      }
      const StepResult& step = rig.step_direct(vented, t_s);
      if (rig.faulted()) {
        out.faulted = true;
        out.fault = rig.fault().detail();
        return false;
      }
      if (usable(step)) return true;
      if (t_s - since > o.max_hold_s) {
        out.faulted = true;
        out.fault =
            "the rig's link stayed down for more than the longest hold (" + std::to_string(o.max_hold_s) + " s)";
        return false;
      }
    }
  };
  // A sink or progress callback that throws (a full disk) must not leave pressure on.
  try {
    for (std::size_t h = 0; h < schedule.holds.size() && !out.stopped && !out.faulted; ++h) {
      const SweepHold& hold = schedule.holds[h];
      current_start_s = t_s;
      current_expected_s = expected_s[h];
      if (hold.segment != SweepSegment::vent)
        meter.phase(std::string(to_string(hold.segment)) +
                        (hold.segment == SweepSegment::staircase && repeats > 0
                             ? " repeat " + std::to_string(hold.repeat) + "/" + std::to_string(repeats)
                             : std::string()),
                    done_s / std::max(total_s, 1e-9));
      HoldOutcome result;
      bool history_lost = false;  // the plant was vented by an outage since the last vent hold
      HoldEnd end = HoldEnd::interrupted;
      for (int attempt = 0; attempt < kMaxHoldAttempts && end == HoldEnd::interrupted; ++attempt) {
        if (attempt > 0) ++out.holds_redone;
        if (history_lost && !wait_for_link()) break;
        if (history_lost && hold.level_kPa > 0) {
          // Hysteresis remembers the path: bring the plant back to this hold's branch by
          // replaying, unrecorded, the levels commanded since the last vent (the outage vented
          // it too), then hold the level again from there.
          std::size_t from = h;
          while (from > 0 && schedule.holds[from - 1].level_kPa > 0) --from;
          HoldOutcome approach;
          HoldEnd a = HoldEnd::settled;
          for (std::size_t j = from; j < h && a != HoldEnd::interrupted && a != HoldEnd::ended; ++j)
            a = run_hold(schedule.holds[j].level_kPa, false, approach);
          if (a == HoldEnd::ended) break;
          if (a == HoldEnd::interrupted) continue;  // lost again on the way: another attempt
        }
        end = hold.duration_s > 0 ? run_timed_hold(hold, result) : run_hold(hold.level_kPa, true, result);
        if (end == HoldEnd::interrupted) {
          history_lost = true;
          hold_samples.clear();
        }
      }
      if (end == HoldEnd::interrupted && !out.stopped && !out.faulted) {
        // The link failed on every attempt: nothing of this hold is recorded, and the sweep
        // ends (a file of whole holds, fittable) rather than guessing at the plant's state.
        out.faulted = true;
        out.fault = "the rig's link failed during " + std::to_string(kMaxHoldAttempts) + " attempts at hold " +
                    std::to_string(h) + "; the sweep stops with the holds recorded so far";
        break;
      }
      // A stop or a fault mid-hold keeps its settled-so-far samples (unsettled); an outage's
      // samples never reach the file.
      if (!hold_samples.empty() && end != HoldEnd::interrupted) {
        sink.on_hold(h, hold, hold_samples, result);
        ++out.holds_done;
        if (!result.settled && !result.timed) ++out.holds_unsettled;
      }
      done_s += expected_s[h];
      excursions.close();  // an excursion does not run on into the next hold
      if (progress && !out.stopped && !out.faulted) progress(h + 1, schedule.holds.size(), hold, result);
    }
  } catch (...) {
    rig.disarm();
    throw;
  }
  rig.disarm();
  out.duration_s = t_s;
  if (rig.faulted())
    out.fault_record =
        save_fault_record(rig.recorder(), rig.fault(), "the calibration sweep", {},
                          o.fault_record_folder.empty() ? std::filesystem::current_path() : o.fault_record_folder);
  excursions.close();
  out.excursions = excursions.excursions();
  if (!out.stopped && !out.faulted) meter.finish();
  return out;
}

}  // namespace palprig
