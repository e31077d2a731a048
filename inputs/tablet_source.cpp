#include "inputs/tablet_source.hpp"
#include "runtime/monotonic_clock.hpp"

#include <evemu.h>
#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "models/parse_error.hpp"

namespace palprig {

namespace {

bool is_pen_tablet(const libevdev* d) {
  return libevdev_has_event_code(d, EV_ABS, ABS_X) && libevdev_has_event_code(d, EV_ABS, ABS_Y) &&
         libevdev_has_event_code(d, EV_ABS, ABS_PRESSURE) &&
         (libevdev_has_event_code(d, EV_KEY, BTN_TOOL_PEN) || libevdev_has_event_code(d, EV_KEY, BTN_STYLUS));
}

}  // namespace

EvdevPenSource::EvdevPenSource(const std::string& path, bool grab) {
  std::vector<std::string> candidates;
  if (path == "auto") {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator("/dev/input", ec))
      if (entry.path().filename().string().rfind("event", 0) == 0) candidates.push_back(entry.path().string());
    std::sort(candidates.begin(), candidates.end());
  } else {
    candidates.push_back(path);
  }
  std::string refused;
  for (const auto& p : candidates) {
    const int fd = ::open(p.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
      if (path != "auto")
        throw InputError("input", "tablet:" + path, std::string("a readable event device (") + std::strerror(errno) +
                                                          (errno == EACCES ? "; join the 'input' group or add a udev rule" : "") + ")");
      if (errno == EACCES) refused += " " + p;
      continue;
    }
    libevdev* d = nullptr;
    if (libevdev_new_from_fd(fd, &d) < 0 || !is_pen_tablet(d)) {
      if (d) libevdev_free(d);
      ::close(fd);
      if (path != "auto")
        throw InputError("input", "tablet:" + path, "a pen tablet (ABS_X, ABS_Y, ABS_PRESSURE and a pen tool key)");
      continue;
    }
    fd_ = fd;
    dev_ = d;
    path_ = p;
    break;
  }
  if (!dev_)
    throw InputError("input", "tablet", "a pen tablet under /dev/input (none of " + std::to_string(candidates.size()) +
                                              " event devices has ABS_X, ABS_Y, ABS_PRESSURE and a pen tool" +
                                              (refused.empty() ? std::string() : "; no permission to read" + refused) + ")");
  name_ = libevdev_get_name(dev_) ? libevdev_get_name(dev_) : "unnamed";
  // Event times on the loop's clock, so ages compare directly.
  libevdev_set_clock_id(dev_, CLOCK_MONOTONIC);
  if (grab && libevdev_grab(dev_, LIBEVDEV_GRAB) < 0)
    throw InputError("input", "tablet:" + path_, "a device palprig may grab (another program holds it)");
  const input_absinfo* x = libevdev_get_abs_info(dev_, ABS_X);
  const input_absinfo* y = libevdev_get_abs_info(dev_, ABS_Y);
  const input_absinfo* p = libevdev_get_abs_info(dev_, ABS_PRESSURE);
  axes_.x_min = x->minimum, axes_.x_max = x->maximum, axes_.x_resolution = x->resolution;
  axes_.y_min = y->minimum, axes_.y_max = y->maximum, axes_.y_resolution = y->resolution;
  axes_.pressure_min = p->minimum, axes_.pressure_max = p->maximum;
  axes_.has_touch_key = libevdev_has_event_code(dev_, EV_KEY, BTN_TOUCH);
}

EvdevPenSource::~EvdevPenSource() {
  if (dev_) libevdev_free(dev_);
  if (fd_ >= 0) ::close(fd_);
}

PenEventSource::Status EvdevPenSource::next(std::vector<input_event>& out, int timeout_ms, PenState& resynced) {
  pollfd p{fd_, POLLIN, 0};
  const int ready = poll(&p, 1, timeout_ms);
  if (ready < 0 && errno != EINTR) {
    why_ = std::string("poll on ") + path_ + ": " + std::strerror(errno);
    return Status::ended;
  }
  if (ready <= 0) return Status::idle;
  if (p.revents & (POLLERR | POLLHUP | POLLNVAL)) {
    why_ = path_ + " is gone (unplugged?)";
    return Status::ended;
  }
  bool did_resync = false;
  for (;;) {
    input_event ev;
    int rc = libevdev_next_event(dev_, LIBEVDEV_READ_FLAG_NORMAL, &ev);
    if (rc == LIBEVDEV_READ_STATUS_SYNC) {
      // Kernel buffer overflow: hand the decoder the SYN_DROPPED, let libevdev resynchronise
      // its view of the device, and pass on the state it ends with.
      out.push_back(ev);
      while ((rc = libevdev_next_event(dev_, LIBEVDEV_READ_FLAG_SYNC, &ev)) == LIBEVDEV_READ_STATUS_SYNC) {
      }
      resynced.x = libevdev_get_event_value(dev_, EV_ABS, ABS_X);
      resynced.y = libevdev_get_event_value(dev_, EV_ABS, ABS_Y);
      resynced.pressure = libevdev_get_event_value(dev_, EV_ABS, ABS_PRESSURE);
      resynced.touch = libevdev_get_event_value(dev_, EV_KEY, BTN_TOUCH) != 0;
      resynced.tool = libevdev_get_event_value(dev_, EV_KEY, BTN_TOOL_PEN) != 0 ||
                      libevdev_get_event_value(dev_, EV_KEY, BTN_TOOL_RUBBER) != 0;
      did_resync = true;
      continue;
    }
    if (rc == LIBEVDEV_READ_STATUS_SUCCESS) {
      out.push_back(ev);
      continue;
    }
    if (rc == -EAGAIN) break;
    why_ = path_ + ": " + std::strerror(-rc) + (rc == -ENODEV ? " (unplugged?)" : "");
    return Status::ended;
  }
  return did_resync ? Status::resynced : Status::events;
}

PenRecording read_pen_recording(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> fp(std::fopen(file.c_str(), "r"), std::fclose);
  if (!fp) throw InputError(file, "file", std::string("a readable evemu recording (") + std::strerror(errno) + ")");
  std::unique_ptr<evemu_device, void (*)(evemu_device*)> dev(evemu_new(nullptr), evemu_delete);
  if (!dev || evemu_read(dev.get(), fp.get()) <= 0)
    throw InputError(file, "device description", "an evemu recording (N:, I:, P:, B:, A: lines as evemu-record writes)");
  if (!evemu_has_event(dev.get(), EV_ABS, ABS_X) || !evemu_has_event(dev.get(), EV_ABS, ABS_Y) ||
      !evemu_has_event(dev.get(), EV_ABS, ABS_PRESSURE))
    throw InputError(file, "device description", "a pen tablet (ABS_X, ABS_Y and ABS_PRESSURE)");
  PenRecording r;
  r.device_name = evemu_get_name(dev.get()) ? evemu_get_name(dev.get()) : "";
  r.axes.x_min = evemu_get_abs_minimum(dev.get(), ABS_X);
  r.axes.x_max = evemu_get_abs_maximum(dev.get(), ABS_X);
  r.axes.x_resolution = evemu_get_abs_resolution(dev.get(), ABS_X);
  r.axes.y_min = evemu_get_abs_minimum(dev.get(), ABS_Y);
  r.axes.y_max = evemu_get_abs_maximum(dev.get(), ABS_Y);
  r.axes.y_resolution = evemu_get_abs_resolution(dev.get(), ABS_Y);
  r.axes.pressure_min = evemu_get_abs_minimum(dev.get(), ABS_PRESSURE);
  r.axes.pressure_max = evemu_get_abs_maximum(dev.get(), ABS_PRESSURE);
  r.axes.has_touch_key = evemu_has_event(dev.get(), EV_KEY, BTN_TOUCH);
  input_event ev;
  while (evemu_read_event(fp.get(), &ev) > 0) {
    if (!r.events.empty() && event_time_s(ev) < event_time_s(r.events.back()))
      throw InputError(file, "event " + std::to_string(r.events.size() + 1), "event times that never go back");
    r.events.push_back(ev);
  }
  if (r.events.empty()) throw InputError(file, "events", "at least one E: event line");
  return r;
}

EvemuPenSource::EvemuPenSource(const std::filesystem::path& path) : path_(path.string()) {
  PenRecording r = read_pen_recording(path);
  axes_ = r.axes;
  events_ = std::move(r.events);
}

double EvemuPenSource::duration_s() const noexcept {
  return events_.empty() ? 0 : event_time_s(events_.back()) - event_time_s(events_.front());
}

PenEventSource::Status EvemuPenSource::next(std::vector<input_event>& out, int timeout_ms, PenState&) {
  const std::int64_t now = mono_ns();
  if (start_ns_ == 0) start_ns_ = now;
  if (cursor_ >= events_.size()) return Status::ended;
  const double t0 = event_time_s(events_.front());
  auto due_ns = [&](std::size_t i) { return start_ns_ + std::int64_t((event_time_s(events_[i]) - t0) * 1e9); };
  std::int64_t wake = std::min(due_ns(cursor_), now + std::int64_t(timeout_ms) * 1'000'000);
  if (wake > now) {
    sleep_until_ns(wake);
  }
  const std::int64_t after = mono_ns();
  const std::size_t before = cursor_;
  while (cursor_ < events_.size() && due_ns(cursor_) <= after) out.push_back(events_[cursor_++]);
  return cursor_ > before ? Status::events : Status::idle;
}

}  // namespace palprig
