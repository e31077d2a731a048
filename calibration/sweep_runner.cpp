#include "calibration/sweep_runner.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

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

}  // namespace

SweepOutcome run_calibration_sweep(RigBackend& backend, const SweepSchedule& schedule, const SweepRunOptions& o,
                                   SweepSink& sink, const SweepProgress& progress) {
  if (!(o.settle_window_s > 0) || !(o.settle_band_kPa > 0) || !(o.average_s > 0) || !(o.min_hold_s >= 0) ||
      !(o.max_hold_s > o.min_hold_s) || !(o.max_hold_s >= o.settle_window_s + o.average_s) || !(o.max_hold_s <= 3600) ||
      !(o.rate_hz > 0) || !(o.rate_hz <= 10000) || !(o.slew_kPa_per_s > 0))
    throw std::invalid_argument(
        "sweep: need settle window, band and averaging window > 0, a max hold above min hold and both windows (at "
        "most an hour), a rate in (0, 10000] Hz and a slew rate > 0");
  bool any = false;
  for (bool on : o.channels) any = any || on;
  if (!any) throw std::invalid_argument("sweep: no channel selected");

  // Every setpoint passes the controller's safety stage through a rig step (tick_direct without
  // a hysteresis inverse): clamped to the rig's p_max, slew-limited at the rig's own rate
  // (o.slew_kPa_per_s, from the rig file), vented on any fault. No exemption: a staircase step
  // of 10 kPa at 100 Hz passes in one tick at the default 2000 kPa/s; larger steps ramp at the
  // rate the regulators slew at anyway, and the settle test waits the ramp out.
  TickConfig direct;
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
  if (rig.arm() != BackendStatus::ok) {
    out.faulted = true;
    out.fault = rig.fault_detail();
    return out;
  }
  // A sink or progress callback that throws (a full disk) must not leave pressure on.
  try {
    for (std::size_t h = 0; h < schedule.holds.size() && !out.stopped && !out.faulted; ++h) {
      const SweepHold& hold = schedule.holds[h];
      ChannelPressures target{};
      for (std::size_t c = 0; c < kFingerCount; ++c) target[c] = o.channels[c] ? hold.level_kPa : 0.0;
      hold_samples.clear();
      HoldOutcome result;
      std::size_t averaging_from = 0;  // index of the first averaged sample, once settled
      bool averaging = false;
      const double hold_start_s = pacer.period_s() * double(k);
      for (;;) {
        t_s = pacer.wait_for_tick(k++);
        if (o.stop_signal && o.stop_signal->load(std::memory_order_relaxed) != 0) {
          out.stopped = true;
          out.stop_signal = o.stop_signal->load();
          break;
        }
        const StepResult& step = rig.step_direct(target, t_s);
        if (rig.faulted()) {
          out.faulted = true;
          out.fault = rig.fault() == FaultCode::backend_error ? std::string(rig.fault_detail())
                                                              : std::string("safety stage: ") + to_string(rig.fault());
          break;
        }
        SweepSample s;
        s.t_s = t_s;
        s.command_kPa = hold.level_kPa;
        s.monitor_kPa = step.monitor_kPa;
        s.sensor = step.sensor;  // NaN when the rig has no sensor
        hold_samples.push_back(s);
        result.hold_s = t_s - hold_start_s;
        if (!averaging && result.hold_s >= o.min_hold_s &&
            monitors_settled(hold_samples, window, o.channels, o.settle_band_kPa)) {
          averaging = true;
          averaging_from = hold_samples.size();
        } else if (averaging && hold_samples.size() - averaging_from >= average) {
          result.settled = true;
          for (std::size_t j = averaging_from; j < hold_samples.size(); ++j) hold_samples[j].settled = true;
          break;
        }
        if (result.hold_s >= o.max_hold_s) break;  // recorded, but marked unsettled
      }
      if (!hold_samples.empty()) {
        sink.on_hold(h, hold, hold_samples, result);
        ++out.holds_done;
        if (!result.settled) ++out.holds_unsettled;
      }
      if (progress && !out.stopped && !out.faulted) progress(h + 1, schedule.holds.size(), hold, result);
    }
  } catch (...) {
    rig.disarm();
    throw;
  }
  rig.disarm();
  out.duration_s = t_s;
  return out;
}

}  // namespace palprig
