#pragma once
// RigStep: the one path from a target to the regulators. Every caller that moves air (the loop
// runner, experiments' RigStimulus, calibration's sweep and compensation evaluation) makes one
// step per period:
//
//   tick (pen on a scene) or tick_direct (per-finger targets)
//     -> backend write (only while armed and linked; vented otherwise)
//     -> read monitors (-> sensors, when asked)
//     -> fault check (backend errors latch a fault, with the backend's own words)
//     -> vent on fault
//     -> the telemetry record, monitors and I/O time filled in
//
// It owns the tick state and holds the backend, so no caller edits tick state or writes a
// setpoint by hand: no setpoint reaches a backend except through the tick's safety stage.
// A link outage (Modbus reconnecting) or a disarmed backend is not a fault: the channels are
// vented, the record says so, and the slew limiter restarts from 0 kPa when pressure may flow
// again. A vent the backend did on its own between two steps (RigBackend::forced_vents(): an
// outage over before linked() showed it, or a bus that vented a loop silent beyond its setpoint
// timeout) makes that step's result not linked and restarts the slew limiter from 0 kPa. Runs
// on the loop thread: no allocation, no locks, no exceptions.
#include <array>
#include <cstdint>

#include "controller/fault_recorder.hpp"
#include "controller/tick.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig {

struct RigStepOptions {
  double rate_hz = 1000.0;    // nominal step rate: the first tick rises one slew step of 1 / rate_hz
  bool read_sensors = false;  // also read the sensor channels (calibration sweeps), when the rig has them
};

// What one step did.
struct StepResult {
  TickResult tick;                 // setpoints, pulse and the telemetry record (monitors, I/O time filled in)
  ChannelPressures monitor_kPa{};  // NaN where the backend has no reading (link down)
  std::array<double, kFingerCount> sensor{};  // NaN unless sensors were read
  LoadCellReading load_cells;                 // count 0 unless the sample's force came from the load cells
  // The backend's link carried this step's setpoints, and it vented nothing on its own since
  // the last step.
  bool linked = true;
  bool armed = true;              // the backend was armed (setpoints flowed)
  double tick_us = 0, io_us = 0;  // time in the tick, time in the backend
};

class RigStep {
 public:
  // The backend must be open and outlive the step. The configuration is copied (its period
  // set from options.rate_hz).
  RigStep(const TickConfig& config, RigBackend& backend, const RigStepOptions& options = {});
  RigStep(const RigStep&) = delete;
  RigStep& operator=(const RigStep&) = delete;

  // Arm the backend; the next step rises from the vented state under the slew limit. Refused
  // after a fault (a faulted step never moves air again) and on a closed backend: the reason is
  // in fault() and, for the backend's refusal, the step faults (backend_error).
  BackendStatus arm() noexcept;
  // Vent and disarm; later steps keep reading monitors until arm().
  void disarm() noexcept;

  // Latch a fault found outside the step (signal, worker thread, deadline overruns) at the last
  // step's time; the next step vents. The first reason wins; `detail` (copied) is its words.
  void enter_fault(FaultCode why, const char* detail = nullptr) noexcept;

  // One step with the pen on a scene. A sample whose force comes from the rig's load cells
  // (tracked fingers: TouchSample::force_from_load_cells) gets it here, read before
  // the tick: the fingertips' press is handed to the backend (a simulated rig's cells feel it),
  // the cells are read, and their forces (clipped at 0 N: below the tare is noise) go in.
  // `inputs`: the operator's switches this tick (controller/operator_switches.hpp).
  const StepResult& step(const Scene& scene, const TouchSample& sample, double t_s,
                         const TickInputs& inputs = {}) noexcept;
  // One step with direct per-finger targets (hysteresis inverse and safety stage only).
  const StepResult& step_direct(const ChannelPressures& target_kPa, double t_s) noexcept;

  // Why the step vented for good: the code, when, and the words of whoever found it (the
  // backend's, a worker's, the loop's); for a refused arm() after a fault, that fault.
  const Fault& fault() const noexcept { return fault_; }
  // The last steps' records (kFaultRecordTicks), kept for the record of a fault.
  const FaultRecorder& recorder() const noexcept { return recorder_; }
  bool faulted() const noexcept { return fault_.active(); }
  const TickState& tick_state() const noexcept { return state_; }
  const TickConfig& config() const noexcept { return config_; }
  const StepResult& last() const noexcept { return result_; }
  RigBackend& backend() noexcept { return backend_; }
  const RigBackend& backend() const noexcept { return backend_; }
  std::uint64_t link_outages() const noexcept { return link_outages_; }
  std::uint64_t unlinked_steps() const noexcept { return unlinked_steps_; }
  // Steps that found the backend had vented on its own since the last one while its link
  // looked up (RigBackend::forced_vents()); such a step's result is not linked.
  std::uint64_t vents_between_steps() const noexcept { return vents_between_steps_; }

 private:
  void vent_and_disarm() noexcept;
  // Everything after the tick: write (or vent), read, fault check, vent on fault, record.
  void finish(std::int64_t tick_start_ns, bool linked, double t_s) noexcept;
  // The sample with its force from the load cells (see step()).
  TouchSample with_load_cell_force(const TouchSample& sample, double t_s) noexcept;

  TickConfig config_;
  RigBackend& backend_;
  bool read_sensors_ = false;
  TickState state_;
  StepResult result_;
  bool was_linked_ = true;
  std::uint64_t link_outages_ = 0, unlinked_steps_ = 0;
  std::uint64_t seen_forced_vents_ = 0;  // the backend's forced_vents() at the last step
  std::uint64_t vents_between_steps_ = 0;
  Fault fault_;
  FaultRecorder recorder_;
  double last_t_s_ = 0;  // the last step's time: when a fault found outside a step is latched
};

}  // namespace palprig
