#pragma once
// The loop runner: schedules one RigStep (controller/rig_step.hpp: tick, backend write, monitors,
// faults, vent) per period against a backend and an input source, and keeps the run's
// statistics and telemetry. The backend (open) is armed at the start and disarmed at the end.
//   realtime: absolute deadlines on CLOCK_MONOTONIC (no drift), overruns counted and the
//             schedule resynchronised to the next free period; SCHED_FIFO/mlockall if allowed.
//   replay:   simulated time, as fast as the machine goes, same tick and same backend calls.
// Lost time: periods skipped after overruns (realtime), or a tick's CPU time beyond its period
// (replay), add up and drain by 1 % of the time run; beyond safety.max_lost_time_s the loop
// cannot hold its rate and faults (lost_time_limit), in real time and in a replay alike.
// Stop requests, worker-thread exceptions, telemetry failures, deadline overruns beyond the
// limit and lost time beyond its limit latch a fault in the rig step; any fault vents every channel and ends the run
// with the reason.
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "inputs/input_source.hpp"
#include "runtime/latency_histogram.hpp"
#include "runtime/realtime.hpp"
#include "runtime/run_control.hpp"
#include "rigs/rig_backend.hpp"
#include "controller/operator_switches.hpp"
#include "controller/rig_lease.hpp"
#include "controller/rig_step.hpp"
#include "controller/tick.hpp"

namespace palprig {

enum class LoopMode { realtime, replay };

// Sees every tick's record on the loop thread (the demo's per-tumor table, tests). Must be
// quick, and must not allocate, lock or throw.
class TickObserver {
 public:
  virtual ~TickObserver() = default;
  virtual void on_tick(const TelemetryRecord& record) noexcept = 0;
};

struct RunOptions {
  double rate_hz = 1000.0;
  double duration_s = 10.0;
  LoopMode mode = LoopMode::replay;
  std::filesystem::path telemetry_path;  // empty: no telemetry file
  bool want_fifo = true;
  // Realtime mode only: FIFO priority, PM QoS request, timer slack, stack prefault, CPU pinning
  // (runtime/realtime.hpp). FIFO is used when both want_fifo and realtime.fifo are true.
  RealtimeOptions realtime;
  // The operator's handle (runtime/run_control.hpp), read once per tick, never waited on: a
  // stop request ends the run (vented; a stop by signal is a fault of the run, FaultCode::signal);
  // while the vent is held every setpoint is 0 kPa from that very tick on, the backend is
  // disarmed and the loop keeps running (telemetry flag vented); when it is released, the rig is
  // armed again and pressure rises from 0 under the slew limit. Null: nothing steers the run.
  const RunControl* control = nullptr;
  TickObserver* observer = nullptr;
  // The operator's switches (lag compensation, each artery's rate and amplitude), read once per
  // tick into the tick's inputs. Null: the configuration's own behaviour.
  const OperatorSwitches* switches = nullptr;
  // Where the fault record goes when the run ends on a fault (controller/fault_recorder.hpp):
  // beside the telemetry file when there is one, else in this folder (empty: the working one).
  std::filesystem::path fault_record_folder;
};

struct RangeStats {
  double min = 0, max = 0, sum = 0;
  std::uint64_t n = 0;
  void add(double v) noexcept {
    if (!std::isfinite(v)) return;  // a monitor with no reading (link down) is not a value
    if (n == 0 || v < min) min = v;
    if (n == 0 || v > max) max = v;
    sum += v;
    ++n;
  }
  double mean() const noexcept { return n ? sum / double(n) : 0.0; }
};

struct RunSummary {
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;        // ticks that finished after the next deadline
  std::uint64_t missed_periods = 0;  // periods skipped to resynchronise after overruns
  std::uint64_t telemetry_dropped = 0;
  std::uint64_t link_outages = 0;                     // times the backend's link dropped (alarm, vented, reconnecting)
  std::uint64_t unlinked_ticks = 0;                   // ticks run while it was down
  std::array<RangeStats, kFingerCount> target_kPa{};  // what the models asked for
  std::array<RangeStats, kFingerCount> setpoint_kPa{};  // what went to the backend
  std::array<RangeStats, kFingerCount> monitor_kPa{};   // what the regulators reported
  std::array<RangeStats, kFingerCount> force_N{};       // each finger's pressing force (pen or load cell)
  // Ticks each finger spent vented for a reason of its own (tracked fingers: FingerVent), by reason.
  static constexpr std::size_t kVentReasons = 6;
  std::array<std::array<std::uint64_t, kVentReasons>, kFingerCount> finger_vent_ticks{};
  Fault fault;  // none, or why the run vented: code, loop time and the finder's own words
  // After a fault: the sentence naming the file that holds the ticks before it ("the last 2000
  // ticks before it: FILE"), or why it could not be written; empty without a fault.
  std::string fault_record;
  std::filesystem::path fault_record_file;
  LatencySummary wake_latency;  // realtime only
  LatencySummary io_time;
  LatencySummary tick_time;
  double sim_time_s = 0, wall_time_s = 0;
  std::string realtime_note;
  std::string realtime_practices;  // what was in effect, e.g. "SCHED_FIFO 80, mlockall, PM QoS 0 us"
  std::string telemetry_path;
};

// Drives the rig through `lease` (controller/rig_lease.hpp): the run ends cleanly, vented, when
// the lease is asked to give the rig back.
RunSummary run_loop(const TickConfig& config, const Scene& scene, InputSource& input, RigLease& lease,
                    const RunOptions& options);

}  // namespace palprig
