#pragma once
// LiveRun: the GUI's one adapter to the controller library. It loads and checks the files
// exactly as `palprig run` does (the same library calls, refusing with the same InputError
// line before anything moves), opens the backend, and runs controller/loop_runner's run_loop
// on its own thread in real time, for as long as the window is open.
//
// The window's opened rig (controller/rig_lease.hpp) lives here; the live loop holds a yielding
// lease on it, so a study session, a calibration sweep or an evaluation takes the rig by
// leasing it (the loop gives way and ends, vented) and the window starts the loop again once the
// rig is free (resume_when_free, from its poll timer). Operator controls reach the loop through
// the window's RunControl (the process's, which SIGINT/SIGTERM also write: VENT, Arm) and its
// OperatorSwitches (lag compensation, each artery's rate and amplitude), which the loop reads
// every tick into the tick's inputs; pen samples through WindowPenInput's latest-value handoff; telemetry
// leaves through TelemetryFeed's wait-free queue. The loop thread never emits a Qt signal and
// never takes a lock the GUI holds.
//
// Lifecycle shown by the rig panel: connected (loop running, reading monitors, every setpoint 0)
// -> armed (setpoints flow) -> vented (VENT pressed: 0 kPa, Arm again to resume); lent (another
// holder drives the rig); any latched fault ends the run, vents, and shows as fault until
// acknowledged, after which the loop restarts vented.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "controller/loop_runner.hpp"
#include "controller/rig_lease.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "formats/tracking_file.hpp"
#include "gui/telemetry_feed.hpp"
#include "gui/window_pen_input.hpp"
#include "inputs/igtl_input.hpp"
#include "models/calibration_models.hpp"

namespace palprig::gui {

struct LiveRunFiles {
  std::string scene_path;             // empty: the bundled phantom
  std::string rig_path;               // empty: the default simulated rig
  std::string cal_path;               // empty: paper 002's models
  std::string input_spec = "window";  // window, trace:FILE, sweep, tablet[:DEV or FILE.evemu], igtl:HOST:PORT
  std::string tracking_path;          // with igtl: the tracking file (tools -> fingers)
  std::filesystem::path data_dir;     // where the bundled scene and rig live
};

struct LiveRunOptions {
  double rate_hz = 1000.0;
  bool want_fifo = true;
  std::filesystem::path telemetry_path;  // every tick, as `palprig run --telemetry`
  // The window's operator handle (the process's: SIGINT/SIGTERM vent and end the loop). Never
  // null in a window; a LiveRun made without one keeps its own.
  RunControl* control = nullptr;
  bool arm_at_start = true;  // honoured for the simulated rig only; hardware waits for Arm
};

enum class RigLifecycle { connected, armed, vented, fault, lent, stopped };
const char* to_string(RigLifecycle s) noexcept;

// Files loaded and checked, nothing opened: what `palprig run` loads (controller's run set-up
// replaces this when it lands).
struct LiveRunSetup {
  RigConfig rig;
  CalibrationModels cal;
  SceneFile scene;
  TickConfig config;
  std::string input_spec;
  std::optional<TrackingConfig> tracking;  // an igtl input's
};
// Throws InputError (one line: file, field, what was expected) before anything moves.
LiveRunSetup load_live_run(const LiveRunFiles& files);

class LiveRun {
 public:
  // Opens the rig (open_rig: Error with one line when it cannot, RigBusy when another program
  // has its device) and starts the loop.
  LiveRun(LiveRunSetup setup, const LiveRunOptions& options);
  ~LiveRun();  // stops the loop (vents) and closes the rig
  LiveRun(const LiveRun&) = delete;
  LiveRun& operator=(const LiveRun&) = delete;

  // GUI thread.
  void arm();     // setpoints flow (from 0 under the slew limit)
  void vent();    // every setpoint 0 kPa from the loop's next tick
  void disarm();  // the same on the loop's side; shown as connected rather than vented
  // Loop time of the last tick finished when VENT was last pressed: every tick after the next
  // one sends 0 kPa (the next may have been under way).
  double vent_pressed_after_t_s() const noexcept { return vent_pressed_after_t_s_; }
  void acknowledge_fault();  // clears the banner; the loop restarts vented
  void stop();               // ends the loop (vented) for good; idempotent
  // The window's opened rig: a session, a sweep or an evaluation leases it (the loop gives way).
  Rig& rig() noexcept { return *rig_; }
  // From the poll timer: a loop that gave the rig away starts again once the rig is free, as on
  // opening (hardware vented, the simulated rig armed when arm_at_start). True when it started.
  bool resume_when_free();
  // Another holder drives the rig now (the live loop gave way).
  bool lent() const;
  RigLifecycle state() const noexcept;
  bool fault_pending() const noexcept { return fault_pending_; }
  FaultCode fault() const noexcept { return last_summary_.fault.code; }
  std::string fault_text() const;  // "pen input stale at t=1.234 s" with the backend's words
  // Call from the GUI poll: notices a loop that ended (fault or signal) and collects its summary.
  bool poll_finished();
  const RunSummary& last_summary() const noexcept { return last_summary_; }
  bool stopped_by_signal() const noexcept { return last_summary_.fault == FaultCode::signal; }

  // The pulse panel's switches: the loop reads them every tick into the tick's inputs.
  OperatorSwitches& switches() noexcept { return switches_; }
  void set_lag_compensation(bool on) noexcept { switches_.set_lag_compensation(on); }
  bool lag_compensation() const noexcept { return switches_.lag_compensation(); }

  WindowPenInput* window_pen() noexcept { return window_pen_; }  // null when the input is not the window
  TelemetryFeed& feed() noexcept { return feed_; }
  const LiveRunSetup& setup() const noexcept { return setup_; }
  const Scene& scene() const noexcept { return *setup_.scene.scene; }
  std::string backend_text() const;  // "simulated (in-process)", "modbus tcp 10.0.0.5:502"
  bool linked() const noexcept { return rig_->backend().linked(); }
  std::string input_text() const { return input_->describe(); }
  // A tracker input's state (connected, tools seen, their poses' age); empty for other inputs.
  // GUI thread only (one reader of the tracker's status hand-off).
  std::optional<TrackerStatus> tracker_status() noexcept;
  const TrackingConfig* tracking() const noexcept { return setup_.tracking ? &*setup_.tracking : nullptr; }
  std::string realtime_note() const { return last_summary_.realtime_note; }
  // Where the loop records every tick now (empty without --telemetry): never an earlier file.
  const std::filesystem::path& telemetry_file() const noexcept { return telemetry_file_; }

 private:
  void start_loop();
  void join_loop();

  LiveRunSetup setup_;
  LiveRunOptions options_;
  std::unique_ptr<InputSource> input_;
  WindowPenInput* window_pen_ = nullptr;
  IgtlInput* tracker_ = nullptr;
  std::unique_ptr<Rig> rig_;
  std::optional<RigLease> lease_;  // the loop's: taken on the GUI thread, given back by the loop's thread as it ends
  RunControl own_control_;         // when the options give none
  RunControl* control_;
  TelemetryFeed feed_;
  OperatorSwitches switches_;
  std::atomic<bool> loop_done_{false};
  std::thread loop_;
  bool loop_running_ = false;
  std::filesystem::path telemetry_file_;
  bool fault_pending_ = false;
  bool vented_by_operator_ = false;
  double vent_pressed_after_t_s_ = 0;
  bool stopped_ = false;
  int runs_ = 0;
  RunSummary loop_summary_;  // written by the loop thread, read after loop_done_
  RunSummary last_summary_;
};

}  // namespace palprig::gui
