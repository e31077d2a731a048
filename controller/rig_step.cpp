#include "controller/rig_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "runtime/monotonic_clock.hpp"

namespace palprig {

namespace {

TickConfig with_period(TickConfig config, double rate_hz) {
  if (rate_hz > 0 && std::isfinite(rate_hz)) config.period_s = 1.0 / rate_hz;
  return config;
}

}  // namespace

RigStep::RigStep(const TickConfig& config, RigBackend& backend, const RigStepOptions& options)
    : config_(with_period(config, options.rate_hz)), backend_(backend), state_(make_tick_state(config_)) {
  // Asked once here: capabilities() builds strings, which the loop thread must not.
  read_sensors_ = options.read_sensors && backend.capabilities().has_sensor;
  result_.sensor.fill(std::numeric_limits<double>::quiet_NaN());
  seen_forced_vents_ = backend.forced_vents();
}

void RigStep::enter_fault(FaultCode why, const char* detail) noexcept {
  if (faulted() || state_.fault != FaultCode::none) return;  // the first reason wins
  state_.enter_fault(why);
  fault_.latch(why, last_t_s_, detail);
}

BackendStatus RigStep::arm() noexcept {
  if (faulted()) return BackendStatus::failure(to_string(fault_.code));  // a faulted step never moves air again
  if (const BackendStatus armed = backend_.arm(); armed == BackendStatus::error) {
    enter_fault(FaultCode::backend_error, armed.reason());
    backend_.vent();
    return armed;
  }
  // Pressure rises from the vented state under the slew limit after every arm; what the backend
  // vented on its own while disarmed held no pressure.
  state_.restart_from_vented();
  seen_forced_vents_ = backend_.forced_vents();
  return BackendStatus::ok;
}

void RigStep::disarm() noexcept {
  vent_and_disarm();
  state_.restart_from_vented();
}

void RigStep::vent_and_disarm() noexcept {
  // disarm() vents an armed backend; one that is not armed is vented all the same.
  if (backend_.armed())
    backend_.disarm();
  else
    backend_.vent();
}

TouchSample RigStep::with_load_cell_force(const TouchSample& sample, double t_s) noexcept {
  TouchSample s = sample;
  std::array<double, kFingerCount> depth_mm{};
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const FingerTouch& f = s.fingers[i];
    // z < 0 is below the surface; a vented finger's position is not to be trusted.
    depth_mm[i] = f.vent == FingerVent::none && std::isfinite(f.z_mm) && f.z_mm < 0 ? -f.z_mm : 0.0;
  }
  backend_.feel_press(depth_mm);
  LoadCellReading& cells = result_.load_cells;
  if (const BackendStatus read = backend_.read_load_cells(cells, t_s); read == BackendStatus::error) {
    last_t_s_ = t_s;
    enter_fault(FaultCode::backend_error, read.reason());
    s.force_N = std::numeric_limits<double>::quiet_NaN();  // and the tick vents on it too
    return s;
  }
  auto newtons = [](double f) { return std::isfinite(f) ? std::max(f, 0.0) : f; };  // NaN stays: the tick faults
  if (cells.count == kFingerCount) {
    s.per_finger_force = true;
    s.force_N = 0;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      s.fingers[i].force_N = newtons(cells.force_N[i]);
      s.force_N =
          std::isfinite(s.fingers[i].force_N) ? std::max(s.force_N, s.fingers[i].force_N) : s.fingers[i].force_N;
    }
  } else {
    s.force_N = newtons(cells.force_N[0]);
  }
  return s;
}

const StepResult& RigStep::step(const Scene& scene, const TouchSample& sample, double t_s,
                                const TickInputs& inputs) noexcept {
  const bool linked = backend_.linked();
  const std::int64_t tick_start = mono_ns();
  result_.load_cells.count = 0;
  if (sample.force_from_load_cells) {
    result_.tick = tick(state_, config_, scene, with_load_cell_force(sample, t_s), t_s, inputs);
    finish(tick_start, linked, t_s);
    return result_;
  }
  result_.tick = tick(state_, config_, scene, sample, t_s, inputs);
  finish(tick_start, linked, t_s);
  return result_;
}

const StepResult& RigStep::step_direct(const ChannelPressures& target_kPa, double t_s) noexcept {
  const bool linked = backend_.linked();
  const std::int64_t tick_start = mono_ns();
  result_.tick = tick_direct(state_, config_, target_kPa, t_s);
  finish(tick_start, linked, t_s);
  return result_;
}

void RigStep::finish(std::int64_t tick_start, bool linked, double t_s) noexcept {
  last_t_s_ = t_s;
  // A fault the tick latched (a bad sample, a non-finite target) is the step's, with its time.
  if (state_.fault != FaultCode::none) fault_.latch(state_.fault, t_s);
  TickResult& r = result_.tick;
  TelemetryRecord& rec = r.record;
  const bool armed = backend_.armed();
  result_.linked = linked;
  result_.armed = armed;
  if (!linked) {
    ++unlinked_steps_;
    if (was_linked_) ++link_outages_;
  }
  was_linked_ = linked;
  // Vented without a fault (the link is down and reconnecting, or the operator disarmed): 0 kPa
  // goes out, and the slew limiter starts again from the vented state when pressure may flow.
  if (!linked || !armed) {
    r.setpoint_kPa = {};
    for (float& p : rec.setpoint_kPa) p = 0.0f;
    state_.restart_from_vented();
  }

  const std::int64_t io_start = mono_ns();
  // While armed the vented setpoints of a down link still go through write(): a backend that
  // bounds its outages (Modbus max_outage_s) reports an outage that lasts too long there.
  BackendStatus io = BackendStatus::ok;
  if (armed)
    io = backend_.write(r.setpoint_kPa, t_s);
  else
    (void)backend_.vent();  // a disarmed rig: the reads below say whether its link holds
  if (io == BackendStatus::ok) io = backend_.read_monitors(result_.monitor_kPa, t_s);
  // The backend vented on its own since the last step (forced_vents(): an outage over before
  // linked() could show it, or a bus that vented a loop silent past its setpoint timeout): the
  // plant emptied, and the backend ramps it up again from 0 kPa. The result says this step is
  // not linked, so a caller that records the plant's response (a calibration hold) knows that
  // what it reads is not the response to its commands; the slew limiter starts again from the
  // vented state. The run's link outages and alarm rows stay what linked() showed.
  if (const std::uint64_t vents = backend_.forced_vents(); vents != seen_forced_vents_) {
    seen_forced_vents_ = vents;
    if (result_.linked) {
      result_.linked = false;
      ++vents_between_steps_;
      state_.restart_from_vented();
    }
  }
  // A tick that began with the link down has no reading it can vouch for: the bus thread may
  // publish the first fresh monitors of a reconnect between our linked() and read_monitors(),
  // and an alarm row must not carry them (they belong to the next, linked tick).
  if (!linked) result_.monitor_kPa.fill(std::numeric_limits<double>::quiet_NaN());
  if (io == BackendStatus::ok && read_sensors_) io = backend_.read_sensors(result_.sensor, t_s);
  const std::int64_t io_end = mono_ns();
  if (io == BackendStatus::error) enter_fault(FaultCode::backend_error, io.reason());

  result_.tick_us = double(io_start - tick_start) / 1000.0;
  result_.io_us = double(io_end - io_start) / 1000.0;
  rec.io_us = float(result_.io_us);
  for (std::size_t i = 0; i < kFingerCount; ++i) rec.monitor_kPa[i] = float(result_.monitor_kPa[i]);
  rec.fault = state_.fault;
  if (state_.fault == FaultCode::none && !linked) {
    // The alarm: not latched, the run goes on vented and resumes when the link returns.
    rec.fault = FaultCode::backend_error;
    rec.flags |= kVented;
  }
  if (!armed) rec.flags |= kVented | kDisarmed;
  if (state_.fault != FaultCode::none) {
    // Any fault vents every channel and leaves the backend disarmed: nothing moves again
    // without a new step and an explicit arm.
    vent_and_disarm();
    rec.flags |= kVented;
  }
  recorder_.record(rec);
}

}  // namespace palprig
