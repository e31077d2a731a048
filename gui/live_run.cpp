#include "gui/live_run.hpp"
#include "gui/free_file_name.hpp"

#include <stdexcept>

#include <sstream>

#include "controller/backend_factory.hpp"
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

LiveRun::LiveRun(LiveRunSetup setup, const LiveRunOptions& options) : setup_(std::move(setup)), options_(options) {
  setup_.config.pulse.compensate_lag_switch = &lag_compensation_;
  lag_compensation_.store(setup_.config.pulse.compensate_lag);
  input_ = make_live_input(setup_);
  window_pen_ = dynamic_cast<WindowPenInput*>(input_.get());
  tracker_ = dynamic_cast<IgtlInput*>(input_.get());
  backend_ = make_backend(setup_.rig);
  backend_->open();
  // Hardware starts connected and vented; the operator arms it. The in-process simulation
  // needs no such care and starts ready to press.
  vent_request_.store(!(options_.arm_at_start && setup_.rig.backend == "simulated"));
  start_loop();
}

LiveRun::~LiveRun() {
  stop();
  backend_->vent();
  backend_->close();
}

void LiveRun::start_loop() {
  RunOptions opt;
  opt.rate_hz = options_.rate_hz;
  opt.duration_s = 30.0 * 24 * 3600;  // as long as the window stays open
  opt.mode = LoopMode::realtime;
  opt.want_fifo = options_.want_fifo;
  if (!options_.telemetry_path.empty()) {
    // A recording is never overwritten: a restart after a fault, a scene or rig opened from the
    // File menu (a new LiveRun) or a window started again with the same --telemetry each write
    // the first free NAME-N.EXT beside the earlier ones; the status bar says which.
    const std::filesystem::path p = first_free_file(options_.telemetry_path);
    telemetry_file_ = p;
    opt.telemetry_path = p;
  }
  opt.stop_signal = options_.stop_signal;
  opt.vent_request = &vent_request_;
  opt.stop_request = &stop_request_;
  opt.observer = &feed_;
  ++runs_;
  stop_request_.store(false);
  loop_done_.store(false);
  feed_.reset_statistics();
  if (window_pen_) window_pen_->restart_clock();
  if (tracker_) tracker_->restart_clock();
  loop_running_ = true;
  loop_ = std::thread([this, opt] {
    try {
      loop_summary_ = run_loop(setup_.config, *setup_.scene.scene, *input_, *backend_, opt);
    } catch (const std::exception& e) {
      backend_->vent();
      loop_summary_ = RunSummary{};
      loop_summary_.fault = FaultCode::thread_exception;
      loop_summary_.fault_detail = e.what();
    }
    loop_done_.store(true, std::memory_order_release);
  });
}

void LiveRun::join_loop() {
  if (loop_.joinable()) loop_.join();
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

void LiveRun::arm() {
  if (stopped_ || fault_pending_) return;  // a fault is acknowledged first
  if (!loop_running_) start_loop();
  vented_by_operator_ = false;
  vent_request_.store(false);
}

void LiveRun::vent() {
  // Only the flag: the backend belongs to the loop thread while it runs (a second caller would
  // race the loop's own writes); the loop sends 0 kPa from its next tick.
  vent_pressed_after_t_s_ = feed_.last_t_s();
  vent_request_.store(true);
  vented_by_operator_ = true;
}

void LiveRun::disarm() {
  vent_request_.store(true);
  vented_by_operator_ = false;
}

void LiveRun::acknowledge_fault() {
  if (!fault_pending_) return;
  fault_pending_ = false;
  vented_by_operator_ = false;
  vent_request_.store(true);
  if (!stopped_ && !loop_running_) start_loop();
}

void LiveRun::stop() {
  stop_request_.store(true);
  vent_request_.store(true);
  join_loop();
  stopped_ = true;
}

RigBackend& LiveRun::backend_when_stopped() {
  if (!stopped_ || loop_running_) throw std::logic_error("LiveRun::backend_when_stopped before stop()");
  return *backend_;
}

RigLifecycle LiveRun::state() const noexcept {
  if (fault_pending_) return RigLifecycle::fault;
  if (stopped_ || !loop_running_) return RigLifecycle::stopped;
  if (!vent_request_.load()) return RigLifecycle::armed;
  return vented_by_operator_ ? RigLifecycle::vented : RigLifecycle::connected;
}

std::string LiveRun::fault_text() const {
  std::ostringstream s;
  s << to_string(last_summary_.fault) << " at t=" << last_summary_.fault_t_s << " s";
  if (!last_summary_.fault_detail.empty()) s << " (" << last_summary_.fault_detail << ")";
  s << "; every channel vented";
  return s.str();
}

std::string LiveRun::backend_text() const { return backend_->describe(); }

std::optional<TrackerStatus> LiveRun::tracker_status() noexcept {
  if (!tracker_) return std::nullopt;
  return tracker_->status();
}

}  // namespace palprig::gui
