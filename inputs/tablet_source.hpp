#pragma once
// Where the tablet reader gets its events: a live evdev device (libevdev) or an evemu
// recording replayed with its original timing (libevemu), behind one small interface so the
// reader thread, its heartbeat and its failure paths are the same for both.
#include <linux/input.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "inputs/tablet_decoder.hpp"
#include "core/input_error.hpp"

struct libevdev;

namespace palprig {

class PenEventSource {
 public:
  enum class Status { events, idle, resynced, ended };
  virtual ~PenEventSource() = default;
  virtual const TabletAxes& axes() const noexcept = 0;
  virtual std::string describe() const = 0;
  // Wait up to timeout_ms for events and append them to `out`. `resynced` gets the device's
  // full state after a SYN_DROPPED (status resynced). ended: the device is gone or the
  // recording is over; why() says which.
  virtual Status next(std::vector<input_event>& out, int timeout_ms, PenState& resynced) = 0;
  virtual std::string why() const = 0;
  // Length of a recording; 0 for a live device.
  virtual double duration_s() const noexcept { return 0; }
};

// A live pen tablet. `path` "auto" picks the first /dev/input/event* with ABS_X, ABS_Y,
// ABS_PRESSURE and a pen tool key. Throws InputError (the command line exits 2) when there is
// none or it cannot be opened.
class EvdevPenSource final : public PenEventSource {
 public:
  EvdevPenSource(const std::string& path, bool grab);
  ~EvdevPenSource() override;
  const TabletAxes& axes() const noexcept override { return axes_; }
  std::string describe() const override { return "pen tablet " + path_ + " (" + name_ + ")"; }
  Status next(std::vector<input_event>& out, int timeout_ms, PenState& resynced) override;
  std::string why() const override { return why_; }

 private:
  std::string path_, name_, why_;
  int fd_ = -1;
  libevdev* dev_ = nullptr;
  TabletAxes axes_;
};

// What a recording may hold before it is refused: it replays in real time, so a gap of days (a
// clock jump, an edited file) would hold a run and its telemetry for days. A pen lifted for a
// while is silent, so gaps up to 30 s are normal. unbounded() lifts both for a run whose length
// is given explicitly.
struct PenRecordingLimits {
  double max_length_s = 3600.0;
  double max_gap_s = 30.0;
  static PenRecordingLimits unbounded();
};

class PenRecordingBoundError : public InputError {
 public:
  using InputError::InputError;
};

// An evemu recording (evemu-record's format: device description, then "E:" event lines). The
// whole file is read and checked at construction (InputError on a bad one); next() hands out
// the events as their recorded times come due, measured from the first next() call.
class EvemuPenSource final : public PenEventSource {
 public:
  explicit EvemuPenSource(const std::filesystem::path& path, const PenRecordingLimits& limits = {});
  const TabletAxes& axes() const noexcept override { return axes_; }
  std::string describe() const override { return "pen recording " + path_; }
  Status next(std::vector<input_event>& out, int timeout_ms, PenState& resynced) override;
  std::string why() const override { return "end of the recording " + path_; }
  double duration_s() const noexcept override;
  const std::vector<input_event>& events() const noexcept { return events_; }
  // CLOCK_MONOTONIC when playback started (0 before the first next()): event i came due at
  // start_ns() + (its time - the first event's time), what a kernel would stamp on a live one.
  std::int64_t start_ns() const noexcept { return start_ns_; }

 private:
  std::string path_;
  TabletAxes axes_;
  std::vector<input_event> events_;
  std::size_t cursor_ = 0;
  std::int64_t start_ns_ = 0;
};

// Read an evemu recording: the axes from its device description and all its events.
// Throws InputError naming the file when it is not a pen tablet recording.
struct PenRecording {
  TabletAxes axes;
  std::string device_name;
  std::vector<input_event> events;
};
PenRecording read_pen_recording(const std::filesystem::path& path, const PenRecordingLimits& limits = {});

}  // namespace palprig
