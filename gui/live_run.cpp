#include "gui/live_run.hpp"
#include "gui/free_file_name.hpp"

#include <stdexcept>

#include <sstream>

#include "controller/run_setup.hpp"
#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "inputs/tablet_input.hpp"
#include "core/input_error.hpp"

namespace palprig::gui {

const char* to_string(RigLifecycle s) noexcept {
  switch (s) {
    case RigLifecycle::connected: return "connected, reading (vented)";
    case RigLifecycle::armed: return "armed";
    case RigLifecycle::vented: return "vented";
    case RigLifecycle::fault: return "fault (vented)";
    case RigLifecycle::lent: return "lent (a session or a calibration drives the rig)";
    case RigLifecycle::stopped: return "stopped";
  }
  return "?";
}

LiveRunSetup load_live_run(const LiveRunFiles& f) {
  // The library's run set-up, as `palprig run` calls it (controller/run_setup.hpp); only the
  // window pen is the GUI's own input.
  RunFiles files;
  files.rig = f.rig_path.empty() ? f.data_dir / "rigs" / "simulated.json" : std::filesystem::path(f.rig_path);
  files.calibration = f.cal_path;
  files.scene = f.scene_path.empty() ? f.data_dir / "scenes" / "phantom_abc.json" : std::filesystem::path(f.scene_path);
  files.input = f.input_spec.empty() ? "window" : f.input_spec;
  files.tracking = f.tracking_path;
  LoadedRun run = load_run_files(files);
  LiveRunSetup s;
  s.rig = std::move(run.rig);
  s.cal = std::move(run.cal);
  s.scene = std::move(run.scene);
  s.config = run.config;
  s.input_spec = files.input;
  s.tracking = std::move(run.tracking);
  const std::string& in = s.input_spec;
  if (!(in == "window" || in == "sweep" || in == "raster" || in == "tablet" || in.rfind("tablet:", 0) == 0 ||
        in.rfind("trace:", 0) == 0 || is_igtl_input(in)))
    throw InputError(
        "input", in,
        "window, trace:FILE, sweep, tablet, tablet:/dev/input/eventN, tablet:FILE.evemu or igtl:HOST:PORT");
  return s;
}

namespace {

std::unique_ptr<InputSource> make_live_input(const LiveRunSetup& s) {
  if (s.input_spec == "window") return std::make_unique<WindowPenInput>();
  // Every other input is the library's, with the same bounds as `palprig run`.
  TraceLimits limits;
  limits.max_gap_s = s.rig.safety.max_input_age_s;
  return make_input(s.input_spec, *s.scene.scene, s.rig.contact_force_N, s.rig.tablet, limits,
                    s.tracking ? &*s.tracking : nullptr, s.rig.safety.max_input_age_s);
}

}  // namespace

LiveRun::LiveRun(LiveRunSetup setup, const LiveRunOptions& options)
    : setup_(std::move(setup)), options_(options), control_(options.control ? options.control : &own_control_) {
  switches_.set_lag_compensation(setup_.config.pulse.compensate_lag);
  input_ = make_live_input(setup_);
  window_pen_ = dynamic_cast<WindowPenInput*>(input_.get());
  tracker_ = dynamic_cast<IgtlInput*>(input_.get());
  rig_ = open_rig(setup_.rig);
  start_loop();
}

LiveRun::~LiveRun() {
  stop();
  rig_.reset();  // vented and closed; its device lock goes with it
}

void LiveRun::start_loop() {
  // The rig may be lent (a session, a sweep): the loop starts when it comes back.
  if (rig_->leased()) return;
  try {
    lease_.emplace(rig_->lease("the window's live loop", LeaseKind::yielding));
  } catch (const RigBusy&) {
    return;  // a session or a sweep took it (or waits for it) since: the loop starts when it comes back
  }
  // As on opening: hardware starts connected and vented, and the operator arms it; the
  // in-process simulation needs no such care and starts ready to press.
  control_->restart();
  control_->hold_vent(!(options_.arm_at_start && setup_.rig.backend == "simulated"));
  vented_by_operator_ = false;
  RunOptions opt;
  opt.rate_hz = options_.rate_hz;
  opt.duration_s = 30.0 * 24 * 3600;  // as long as the window stays open
  opt.mode = LoopMode::realtime;
  opt.want_fifo = options_.want_fifo;
  if (!options_.telemetry_path.empty()) {
    // A recording is never overwritten: a restart after a fault or after the rig was lent, a
    // scene or rig opened from the File menu (a new LiveRun) or a window started again with the
    // same --telemetry each write the first free NAME-N.EXT beside the earlier ones; the status
    // bar says which.
    const std::filesystem::path p = first_free_file(options_.telemetry_path);
    telemetry_file_ = p;
    opt.telemetry_path = p;
  }
  opt.control = control_;
  opt.switches = &switches_;
  opt.observer = &feed_;
  ++runs_;
  loop_done_.store(false);
  feed_.reset_statistics();
  if (window_pen_) window_pen_->restart_clock();
  if (tracker_) tracker_->restart_clock();
  loop_running_ = true;
  loop_ = std::thread([this, opt] {
    try {
      loop_summary_ = run_loop(setup_.config, *setup_.scene.scene, *input_, *lease_, opt);
    } catch (const std::exception& e) {
      lease_->backend().vent();
      loop_summary_ = RunSummary{};
      loop_summary_.fault.latch(FaultCode::thread_exception, 0, e.what());
    }
    // Given back here, on the loop's own thread, not at the GUI thread's join: a session or a
    // sweep that asked for the rig waits for it on the GUI thread (Rig::lease), which then
    // cannot get to the join.
    lease_->release();
    loop_done_.store(true, std::memory_order_release);
  });
}

void LiveRun::join_loop() {
  if (loop_.joinable()) loop_.join();
  lease_.reset();  // already given back by the loop's thread (vented)
  if (loop_running_) {
    last_summary_ = loop_summary_;
    loop_running_ = false;
  }
}

bool LiveRun::poll_finished() {
  if (!loop_running_ || !loop_done_.load(std::memory_order_acquire)) return false;
  join_loop();
  if (last_summary_.fault != FaultCode::none) fault_pending_ = true;
  return true;
}

bool LiveRun::resume_when_free() {
  poll_finished();
  if (stopped_ || fault_pending_ || loop_running_ || rig_->leased()) return false;
  start_loop();
  return loop_running_;
}

bool LiveRun::lent() const { return !loop_running_ && !stopped_ && rig_->leased(); }

void LiveRun::arm() {
  if (stopped_ || fault_pending_) return;  // a fault is acknowledged first
  if (!loop_running_) start_loop();
  vented_by_operator_ = false;
  control_->hold_vent(false);
}

void LiveRun::vent() {
  // Only the handle: the backend belongs to the loop thread while it runs (a second caller would
  // race the loop's own writes); the loop sends 0 kPa from its next tick.
  vent_pressed_after_t_s_ = feed_.last_t_s();
  control_->hold_vent(true);
  vented_by_operator_ = true;
}

void LiveRun::disarm() {
  control_->hold_vent(true);
  vented_by_operator_ = false;
}

void LiveRun::acknowledge_fault() {
  if (!fault_pending_) return;
  fault_pending_ = false;
  if (!stopped_ && !loop_running_) start_loop();
  control_->hold_vent(true);  // the loop restarts vented after a fault, whatever the rig
  vented_by_operator_ = false;
}

void LiveRun::stop() {
  if (loop_running_) rig_->request_release();  // the loop ends at its next tick, vented
  join_loop();
  stopped_ = true;
}

RigLifecycle LiveRun::state() const noexcept {
  if (fault_pending_) return RigLifecycle::fault;
  if (stopped_) return RigLifecycle::stopped;
  // A loop that gave way has ended (and given the rig back from its thread) before the GUI
  // thread's poll joins it: it no longer drives the rig.
  if (!loop_running_ || loop_done_.load(std::memory_order_acquire))
    return rig_->leased() ? RigLifecycle::lent : RigLifecycle::stopped;
  if (!control_->vent_held()) return RigLifecycle::armed;
  return vented_by_operator_ ? RigLifecycle::vented : RigLifecycle::connected;
}

std::string LiveRun::fault_text() const {
  std::ostringstream s;
  s << last_summary_.fault.describe() << "; every channel vented";
  return s.str();
}

std::string LiveRun::backend_text() const { return rig_->backend().describe(); }

std::optional<TrackerStatus> LiveRun::tracker_status() noexcept {
  if (!tracker_) return std::nullopt;
  return tracker_->status();
}

}  // namespace palprig::gui
