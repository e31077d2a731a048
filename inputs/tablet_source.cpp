// Over 400 lines: the two pen sources (a live evdev device, an evemu recording) share the event
// decoding and the checks of a recording's lines, which stay beside the source they guard.
#include "inputs/tablet_source.hpp"
#include "runtime/monotonic_clock.hpp"

#include <evemu.h>
#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <set>

#include "core/input_error.hpp"
#include "io/regular_file.hpp"

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
        throw InputError("input", "tablet:" + path,
                         std::string("a readable event device (") + std::strerror(errno) +
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
    throw InputError("input", "tablet",
                     "a pen tablet under /dev/input (none of " + std::to_string(candidates.size()) +
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
      while ((rc = libevdev_next_event(dev_, LIBEVDEV_READ_FLAG_SYNC, &ev)) == LIBEVDEV_READ_STATUS_SYNC) {}
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

PenRecordingLimits PenRecordingLimits::unbounded() {
  const double inf = std::numeric_limits<double>::infinity();
  return {inf, inf};
}

namespace {

constexpr std::size_t kMaxRecordingBytes = kMaxRecordingFileBytes;  // ~10 hours of a busy pen; also if it grows

std::string duration_text(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

// libevemu reports a description line it cannot parse on stderr by itself (FATAL: ..., WARNING:
// ...) and has no way to turn that off. So every line is checked here first, against the
// formats libevemu 2.7 reads (sscanf "%02x" fields, A: lines with 6 numbers from format 1.2 on),
// and in its order (N:, I:, then P:, B:, A:, L:, S: lines); a line it would complain about is
// refused with palprig's one line and libevemu never sees it. Returns what was expected, or "".
std::string description_problem(const std::string& line, int format_minor, char& last_tag) {
  const char tag = line[0];
  static const std::string order = "NIPBALS";
  const auto rank = order.find(tag);
  const auto last = last_tag ? order.find(last_tag) : std::string::npos;
  if (last_tag == 0 && tag != 'N') return "the device name first ('N: <name>')";
  if (last_tag == 'N' && tag != 'I')
    return "the device id after the name ('I: <bus> <vendor> <product> <version>' in hex)";
  if (last_tag != 0 && last_tag != 'N' && (tag == 'N' || tag == 'I' || rank < last))
    return "description lines in evemu-record's order (N:, I:, P:, B:, A:, L:, S:)";
  last_tag = tag;
  if (tag == 'N') return line.size() > 3 ? "" : "a device name after 'N: '";
  std::istringstream in(line.substr(2));
  std::vector<std::string> fields;
  for (std::string f; in >> f;) fields.push_back(f);
  auto hex = [](const std::string& f, unsigned max) {
    unsigned v = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v, 16);
    return ec == std::errc() && end == f.data() + f.size() && v <= max;
  };
  auto integer = [](const std::string& f) {
    int v = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v, 10);
    return ec == std::errc() && end == f.data() + f.size();
  };
  auto all = [&](std::size_t from, auto&& ok) {
    for (std::size_t i = from; i < fields.size(); ++i)
      if (!ok(fields[i])) return false;
    return true;
  };
  switch (tag) {
    case 'I':
      return fields.size() == 4 && all(0, [&](const std::string& f) { return f.size() <= 4 && hex(f, 0xffff); })
                 ? ""
                 : "'I: <bus> <vendor> <product> <version>' (4 hex numbers)";
    case 'P':
      return fields.size() == 8 && all(0, [&](const std::string& f) { return f.size() <= 2 && hex(f, 0xff); })
                 ? ""
                 : "'P: ' and 8 hex bytes";
    case 'B':
      return fields.size() == 9 && hex(fields[0], EV_MAX) &&
                     all(0, [&](const std::string& f) { return f.size() <= 2 && hex(f, 0xff); })
                 ? ""
                 : "'B: <event type> ' and 8 hex bytes";
    case 'A': {
      const std::size_t numbers = format_minor >= 2 ? 6 : 5;
      return fields.size() == numbers && fields[0].size() <= 2 && hex(fields[0], ABS_MAX) && all(1, integer)
                 ? ""
                 : "'A: <axis> <min> <max> <fuzz> <flat>" + std::string(numbers == 6 ? " <resolution>'" : "'");
    }
    default:  // L:, S:
      return fields.size() == 2 && fields[0].size() <= 2 && hex(fields[0], 0xff) && integer(fields[1])
                 ? ""
                 : std::string("'") + tag + ": <code> <state>'";
  }
}

bool is_description_line(const std::string& line) {
  // What evemu-record writes before the events: N: name, I: id, P: properties, B: bit masks,
  // A: axes, L: LEDs, S: switches, and '#' comments.
  if (line.empty() || line[0] == '#') return true;
  static const char* tags[] = {"N:", "I:", "P:", "B:", "A:", "L:", "S:"};
  for (const char* t : tags)
    if (line.rfind(t, 0) == 0) return true;
  return false;
}

// "E: <sec>.<usec> <type hex> <code hex> <value>" with an optional "# comment" after it.
bool parse_event_line(std::string line, input_event& ev) {
  if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
  std::istringstream in(line.substr(2));
  std::string time, type, code, value, extra;
  if (!(in >> time >> type >> code >> value) || (in >> extra)) return false;
  const auto dot = time.find('.');
  if (dot == std::string::npos || dot == 0 || time.size() - dot - 1 == 0 || time.size() - dot - 1 > 6) return false;
  auto whole = [](std::string_view t, auto& out, int base) {
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), out, base);
    return ec == std::errc() && end == t.data() + t.size() && !t.empty();
  };
  std::uint64_t sec = 0;
  std::uint32_t usec = 0, type_v = 0, code_v = 0;
  std::int32_t value_v = 0;
  std::string usec_text = time.substr(dot + 1);
  usec_text.append(6 - usec_text.size(), '0');
  if (!whole(std::string_view(time).substr(0, dot), sec, 10) || !whole(usec_text, usec, 10) ||
      !whole(type, type_v, 16) || !whole(code, code_v, 16) || !whole(value, value_v, 10))
    return false;
  if (sec > std::uint64_t(std::numeric_limits<std::int32_t>::max()) || type_v > EV_MAX || code_v > 0x2ff) return false;
  ev = {};
  ev.input_event_sec = static_cast<decltype(ev.input_event_sec)>(sec);
  ev.input_event_usec = static_cast<decltype(ev.input_event_usec)>(usec);
  ev.type = static_cast<std::uint16_t>(type_v);
  ev.code = static_cast<std::uint16_t>(code_v);
  ev.value = value_v;
  return true;
}

}  // namespace

PenRecording read_pen_recording(const std::filesystem::path& path, const PenRecordingLimits& limits) {
  const std::string file = path.string();
  std::ifstream in = open_regular_file(path, kMaxRecordingFileBytes, "an evemu recording");
  // The description goes to libevemu; the event lines are read here, line by line, so a bad one
  // is refused with its line number (libevemu's own reader stops at it silently and prints its
  // own FATAL/WARNING line beside ours).
  std::string description, line;
  std::vector<std::pair<std::size_t, std::string>> event_lines;
  std::size_t line_no = 0, bytes = 0;
  int format_minor = 0;  // "# EVEMU 1.3" on the first line; libevemu takes a missing one as 1.0
  char last_tag = 0;
  std::set<unsigned long> ranged_axes;  // axes with an 'A:' line (libevemu gives the others 0..1)
  while (std::getline(in, line)) {
    ++line_no;
    bytes += line.size() + 1;
    if (bytes > kMaxRecordingBytes)
      throw InputError(file, "file", "a recording of at most " + std::to_string(kMaxRecordingBytes >> 20) + " MiB");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (event_lines.empty() && is_description_line(line)) {
      if (line_no == 1 && line.rfind("# EVEMU ", 0) == 0) {
        unsigned major = 0, minor = 0;
        if (std::sscanf(line.c_str(), "# EVEMU %u.%u", &major, &minor) == 2) {
          if (major != 1 || minor > 3)
            throw InputError(file, "line 1", "an evemu recording of format 1.3 or older, got " + line.substr(8));
          format_minor = static_cast<int>(minor);
        }
      }
      if (!line.empty() && line[0] != '#') {
        if (const std::string problem = description_problem(line, format_minor, last_tag); !problem.empty())
          throw InputError(file, "line " + std::to_string(line_no),
                           std::string(problem).append(", got '").append(line).append("'"));
        if (line[0] == 'A') ranged_axes.insert(std::stoul(line.substr(2), nullptr, 16));  // checked hex above
      }
      description += line + "\n";
      continue;
    }
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("E:", 0) != 0)
      throw InputError(file, "line " + std::to_string(line_no),
                       (event_lines.empty() ? "a device description line (N:, I:, P:, B:, A:) or an event line "
                                            : "an event line ") +
                           std::string("'E: <sec>.<usec> <type> <code> <value>', got '") + line + "'");
    event_lines.emplace_back(line_no, line);
  }
  // libevemu reads the description from memory. Its parser reports problems on stderr by
  // itself; given only lines that look like a description, what it can still refuse is
  // reported below as palprig's one line.
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> fp(fmemopen(description.data(), description.size(), "r"),
                                                     std::fclose);
  std::unique_ptr<evemu_device, void (*)(evemu_device*)> dev(evemu_new(nullptr), evemu_delete);
  if (!fp || !dev || description.find("N:") == std::string::npos || evemu_read(dev.get(), fp.get()) <= 0)
    throw InputError(file, "device description",
                     "an evemu recording (N:, I:, P:, B:, A: lines as evemu-record writes)");
  if (!evemu_has_event(dev.get(), EV_ABS, ABS_X) || !evemu_has_event(dev.get(), EV_ABS, ABS_Y))
    throw InputError(file, "device description", "a pen tablet (ABS_X and ABS_Y axes)");
  // Without a pressure axis every touch would read as full force: refused, not guessed. An
  // axis whose bit is set but that has no 'A:' line gets the range 0..1 from libevemu, so any
  // pressure reads as the top of the curve: its range line is required, as X's and Y's are.
  for (const auto& [axis, name] :
       {std::pair{ABS_X, "ABS_X"}, std::pair{ABS_Y, "ABS_Y"}, std::pair{ABS_PRESSURE, "ABS_PRESSURE"}}) {
    if (evemu_has_event(dev.get(), EV_ABS, axis) && !ranged_axes.count(static_cast<unsigned long>(axis))) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "%02x", axis);
      throw InputError(file, "device description",
                       std::string("a range line for every pen axis ('A: ") + hex +
                           " <min> <max> <fuzz> <flat> <resolution>'), got none for " + name);
    }
  }
  if (!evemu_has_event(dev.get(), EV_ABS, ABS_PRESSURE) ||
      evemu_get_abs_maximum(dev.get(), ABS_PRESSURE) <= evemu_get_abs_minimum(dev.get(), ABS_PRESSURE))
    throw InputError(file, "device description",
                     "a pen tablet with a pressure axis (ABS_PRESSURE with a range, an 'A: 18 min max ...' line)");
  // A pen's tool key (in proximity) and BTN_TOUCH (down) are what tell hovering from pressing:
  // a recording without them cannot say when the pen touches.
  const bool tool_key =
      evemu_has_event(dev.get(), EV_KEY, BTN_TOOL_PEN) || evemu_has_event(dev.get(), EV_KEY, BTN_TOOL_RUBBER) ||
      evemu_has_event(dev.get(), EV_KEY, BTN_TOOL_BRUSH) || evemu_has_event(dev.get(), EV_KEY, BTN_TOOL_PENCIL) ||
      evemu_has_event(dev.get(), EV_KEY, BTN_TOOL_AIRBRUSH);
  const bool touch_key = evemu_has_event(dev.get(), EV_KEY, BTN_TOUCH);
  if (!tool_key || !touch_key)
    throw InputError(
        file, "device description",
        "a pen tablet with a pen tool key (BTN_TOOL_PEN, RUBBER, BRUSH, PENCIL or AIRBRUSH) and BTN_TOUCH in its "
        "'B: 01' lines, got " +
            std::string(!tool_key && !touch_key ? "neither"
                        : !tool_key             ? "no tool key"
                                                : "no BTN_TOUCH"));
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
  bool pressure_seen = false, touch_seen = false;
  for (const auto& [number, text] : event_lines) {
    const std::string where = "line " + std::to_string(number);
    input_event ev;
    if (!parse_event_line(text, ev))
      throw InputError(file, where,
                       "an event line 'E: <sec>.<usec> <type hex> <code hex> <value>', got '" + text + "'");
    if (!r.events.empty()) {
      const double gap_s = event_time_s(ev) - event_time_s(r.events.back());
      if (gap_s < 0) throw InputError(file, where, "event times that never go back");
      if (gap_s > limits.max_gap_s)
        throw PenRecordingBoundError(
            file, where,
            "events at most " + duration_text(limits.max_gap_s) + " apart, got a gap of " + duration_text(gap_s));
      const double length_s = event_time_s(ev) - event_time_s(r.events.front());
      if (length_s > limits.max_length_s)
        throw PenRecordingBoundError(file, where,
                                     "a recording at most " + duration_text(limits.max_length_s) +
                                         " long (times count from the first event), got " + duration_text(length_s));
    }
    pressure_seen = pressure_seen || (ev.type == EV_ABS && ev.code == ABS_PRESSURE);
    touch_seen = touch_seen || (ev.type == EV_KEY && ev.code == BTN_TOUCH && ev.value != 0);
    r.events.push_back(ev);
  }
  if (r.events.empty()) throw InputError(file, "events", "at least one E: event line");
  if (touch_seen && !pressure_seen)  // touches without a force: no way to know how hard
    throw InputError(file, "events", "touches that report their pressure (ABS_PRESSURE events), got none");
  return r;
}

EvemuPenSource::EvemuPenSource(const std::filesystem::path& path, const PenRecordingLimits& limits)
    : path_(path.string()) {
  PenRecording r = read_pen_recording(path, limits);
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
