#include "inputs/tablet_input.hpp"
#include "runtime/monotonic_clock.hpp"

#include <sys/stat.h>
#include <time.h>

#include <cmath>
#include <vector>

#include "runtime/realtime.hpp"
#include "runtime/worker_fault.hpp"
#include "core/input_error.hpp"

namespace palprig {

namespace {

constexpr int kHeartbeatMs = 10;

}  // namespace

TabletInput::TabletInput(std::unique_ptr<PenEventSource> source, const TabletConfig& config)
    : source_(std::move(source)),
      decoder_(source_->axes(), config),
      description_(source_->describe()),
      duration_s_(source_->duration_s()),
      reader_fifo_priority_(config.reader_fifo_priority) {
  Published first;
  first.frame = decoder_.frame();
  first.heartbeat_ns = mono_ns();
  published_.publish(first);
  reader_ = std::thread([this] { reader_main(); });
}

TabletInput::~TabletInput() {
  stop_.store(true, std::memory_order_release);
  if (reader_.joinable()) reader_.join();
}

void TabletInput::reader_main() noexcept {
  try {
    // Below the loop and the bus thread (runtime/thread_priorities.hpp). Refused quietly when
    // the system does not permit it: the loop's own note says so once.
    (void)set_thread_fifo(reader_fifo_priority_);
    std::vector<input_event> events;
    events.reserve(256);
    PenState resynced;
    Published out;
    out.frame = decoder_.frame();
    while (!stop_.load(std::memory_order_acquire)) {
      events.clear();
      if (duration_s_ > 0 && !started_.load(std::memory_order_acquire)) {
        // A recording starts playing with the loop, not when it was loaded.
        timespec pause{0, long{kHeartbeatMs} * 1'000'000};
        nanosleep(&pause, nullptr);
        out.heartbeat_ns = mono_ns();
        published_.publish(out);
        continue;
      }
      const auto status = source_->next(events, kHeartbeatMs, resynced);
      if (status == PenEventSource::Status::ended) {
        // No more heartbeats: the loop's input-age check vents within max_input_age_s. A
        // recording that ran out is expected; a device that vanished is a fault with a reason.
        if (source_->duration_s() == 0) report_worker_fault("pen tablet reader", source_->why().c_str());
        return;
      }
      for (const auto& ev : events) {
        if (decoder_.feed(ev)) {
          out.frame = decoder_.frame();
          frames_.fetch_add(1, std::memory_order_relaxed);
        }
      }
      if (status == PenEventSource::Status::resynced) {
        decoder_.resync(resynced, events.empty() ? 0.0 : event_time_s(events.back()));
        out.frame = decoder_.frame();
      }
      out.heartbeat_ns = mono_ns();
      published_.publish(out);
    }
  } catch (const std::exception& e) {
    report_worker_fault("pen tablet reader", e.what());
  } catch (...) {
    report_worker_fault("pen tablet reader", "unknown exception");
  }
}

TouchSample TabletInput::latest(double t_s) noexcept {
  const std::int64_t now = mono_ns();
  if (epoch_ns_ == 0) {
    epoch_ns_ = now - static_cast<std::int64_t>(std::llround(t_s * 1e9));
    started_.store(true, std::memory_order_release);
  }
  const Published& p = published_.latest();
  TouchSample s;
  s.t_s = std::min(t_s, double(p.heartbeat_ns - epoch_ns_) * 1e-9);
  s.x_mm = p.frame.x_mm;
  s.y_mm = p.frame.y_mm;
  s.force_N = p.frame.force_N;
  s.in_contact = p.frame.in_contact;
  return s;
}

std::unique_ptr<TabletInput> make_tablet_input(const std::string& spec, const TabletConfig& config,
                                               const PenRecordingLimits& recording_limits) {
  std::string path = config.device;
  if (spec.rfind("tablet:", 0) == 0)
    path = spec.substr(7);
  else if (spec != "tablet")
    throw InputError("input", spec, "tablet, tablet:/dev/input/eventN or tablet:FILE.evemu");
  std::unique_ptr<PenEventSource> source;
  struct stat st {};
  if (path != "auto" && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode))
    source = std::make_unique<EvemuPenSource>(path, recording_limits);
  else
    source = std::make_unique<EvdevPenSource>(path, config.grab);
  try {
    return std::make_unique<TabletInput>(std::move(source), config);
  } catch (const InputError&) {
    throw;  // a recording refused: it names its file and line already
  } catch (const BadInput& e) {
    throw InputError("input", spec, std::string("a tablet palprig can convert to mm and newtons (") + e.what() + ")");
  }
}

}  // namespace palprig
