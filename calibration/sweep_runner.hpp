#pragma once
// Runs a calibration sweep on any RigBackend: each hold commands its level on the selected
// channels (the others stay vented), waits until every selected monitor has settled (the mean
// of the newest half of a window differs from the older half by at most a band), then keeps
// holding for an averaging window whose samples are the hold's reading. Averaging only after
// the settle test keeps the tail of the regulator's lag out of the reading (it would look
// like extra hysteresis). A hold that does not settle within a time limit is kept, unmarked.
// A hold that a link outage interrupts (the rig step vented, monitors NaN) is redone: nothing
// of it is recorded, and once the link is back the levels since the last vent are replayed
// unrecorded, so the plant is on the hold's hysteresis branch again; after 3 failed attempts,
// or a link down longer than max_hold_s, the sweep ends faulted with whole holds recorded.
// Step and chirp holds (timed: SweepHold::duration_s) are held for their duration at
// dynamics_rate_hz, their command following SweepHold::command_at, every sample recorded with
// the setpoint actually sent (after the safety stage's slew limit) as its command.
// Every sample goes to a sink hold by hold, so a stop keeps what was recorded. Ctrl-C (the
// stop flag), a backend error, an exception from the sink or the end all vent every channel.
// Setpoints go through the controller's rig step and safety stage like every other path.
#include <array>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "calibration/excursions.hpp"
#include "calibration/progress_meter.hpp"
#include "calibration/sweep_plan.hpp"
#include "models/safety_limits.hpp"
#include "controller/rig_lease.hpp"
#include "rigs/rig_backend.hpp"
#include "runtime/run_control.hpp"

namespace palprig {

struct SweepSample {
  double t_s = 0;
  double command_kPa = 0;
  ChannelPressures monitor_kPa{};
  std::array<double, kFingerCount> sensor{};  // NaN when the rig has no sensor
  bool settled = false;                       // in the averaging window after settling
};

struct HoldOutcome {
  bool settled = false;
  bool timed = false;  // a step or chirp hold: held for its duration, every sample recorded
  double hold_s = 0;
};

class SweepSink {
 public:
  virtual ~SweepSink() = default;
  virtual void on_hold(std::size_t index, const SweepHold& hold, std::span<const SweepSample> samples,
                       const HoldOutcome& outcome) = 0;
};

struct SweepRunOptions {
  double rate_hz = 100.0;
  bool realtime = true;  // false: simulated time, as fast as possible
  double settle_window_s = 0.3;
  double settle_band_kPa = 0.2;
  double average_s = 0.3;  // averaging window once settled
  double min_hold_s = 0.2;
  double max_hold_s = 10.0;
  std::array<bool, kFingerCount> channels{true, true, true};
  const RunControl* control = nullptr;  // the operator's handle: a stop request vents and ends the sweep
  // Where the ticks before a rig fault are written (controller/fault_recorder.hpp); empty: the
  // working folder.
  std::filesystem::path fault_record_folder;
  // The rig file's safety.slew_kPa_per_s: every setpoint passes the tick's safety stage, so a
  // step between holds rises at most this fast (p_max is the backend's).
  double slew_kPa_per_s = SafetyLimits{}.slew_kPa_per_s;
  // Step and chirp holds (the dynamics fit's excitations) run and record at this rate: the
  // loop's, so the identified dead time and lag are what the tick sees.
  double dynamics_rate_hz = 1000.0;
  // A settled reading further than this from the hold's command is an excursion (reported in
  // SweepOutcome::excursions with its time; steps and chirps are not watched: they are meant to
  // be away from their command while the regulator follows).
  double tolerance_kPa = kDefaultRegulatorTolerance_kPa;
  // Progress (phase: the segment, "staircase repeat 2/5"; share: the holds' expected rig time),
  // at each segment and at least every 5 s of wall time.
  ProgressSink progress_report;
};

struct SweepOutcome {
  std::size_t holds_planned = 0, holds_done = 0, holds_unsettled = 0;
  std::size_t holds_redone = 0;  // holds started again after a link outage spoiled them
  bool stopped = false;          // by a stop request (RunControl)
  int stop_signal = 0;           // the signal that asked, 0 for an operator's stop
  bool faulted = false;          // a backend error; `fault` says which
  std::string fault;
  std::string fault_record;           // after a rig fault: "the last N ticks before it: FILE"
  double duration_s = 0;              // rig time
  std::vector<Excursion> excursions;  // settled readings beyond the tolerance, rig time
};

using SweepProgress = std::function<void(std::size_t done, std::size_t total, const SweepHold&, const HoldOutcome&)>;

// Throws BadInput for options that make no sweep (before anything is written).
SweepOutcome run_calibration_sweep(RigLease& lease, const SweepSchedule& schedule, const SweepRunOptions& options,
                                   SweepSink& sink, const SweepProgress& progress = {});

}  // namespace palprig
