#pragma once
// Pen tablet decoding: a pure function over evdev input_event streams (what the kernel, libevdev
// and evemu recordings all carry), so it is tested on recorded traces without a device.
//
// State follows the evdev protocol: ABS_X/ABS_Y/ABS_PRESSURE and the tool keys change the
// state; each SYN_REPORT closes a frame. The pen is in proximity while a tool key (BTN_TOOL_PEN,
// _RUBBER, ...) is down, and touches while BTN_TOUCH is down (or, on a device without BTN_TOUCH,
// while the pressure is above its minimum). Position converts to mm with the device resolution
// (units/mm) and the rig's origin; pressure to newtons with the rig's pressure curve. A lifted
// pen, or one out of proximity, presses with 0 N.
//
// SYN_DROPPED (the kernel's buffer overflowed): everything up to and including the next
// SYN_REPORT is discarded and the state is unknown. Until it is known again the decoder reports
// a lifted pen (never a stale press): either the reader supplies the device's full state
// (resync(), what libevdev gives after its own resynchronisation), or, in a raw stream, X, Y
// and the pressure have all been reported again (the pen is then in proximity, and touching if
// BTN_TOUCH was reported down again or, when it was not, if the pressure is above its minimum).
#include <linux/input.h>

#include <cstdint>
#include <vector>

#include "formats/tablet_config.hpp"

namespace palprig {

// The device's axes (struct input_absinfo of ABS_X, ABS_Y, ABS_PRESSURE).
struct TabletAxes {
  int x_min = 0, x_max = 0, x_resolution = 0;  // resolution in units per mm (0: unknown)
  int y_min = 0, y_max = 0, y_resolution = 0;
  int pressure_min = 0, pressure_max = 0;
  bool has_touch_key = true;  // BTN_TOUCH
};

// The raw state of the pen, as a device reports it after a resynchronisation.
struct PenState {
  int x = 0, y = 0, pressure = 0;
  bool tool = false, touch = false;
};

struct PenFrame {
  double t_s = 0;             // event time of the SYN_REPORT
  double x_mm = 0, y_mm = 0;  // scene coordinates (tablet mm minus the origin)
  double force_N = 0;
  bool in_proximity = false;
  bool in_contact = false;
  bool synced = true;  // false while the state is unknown after SYN_DROPPED
};

class TabletDecoder {
 public:
  // Throws BadInput when the axes cannot be converted (no resolution and no
  // size_mm, empty ranges).
  TabletDecoder(const TabletAxes& axes, const TabletConfig& config);

  // Feed one event; true when it completed a frame (SYN_REPORT), then see frame().
  bool feed(const input_event& ev) noexcept;
  // The device's state after a resynchronisation; makes the state known and emits a frame.
  void resync(const PenState& state, double t_s) noexcept;
  const PenFrame& frame() const noexcept { return frame_; }
  bool synced() const noexcept { return !dropping_ && !unknown_; }

 private:
  void close_frame(double t_s) noexcept;

  TabletAxes axes_;
  TabletConfig config_;
  double x_units_per_mm_, y_units_per_mm_;
  PenState state_;
  bool tool_keys_seen_ = false;   // the device reports tool keys at all
  bool dropping_ = false;         // discarding until SYN_REPORT
  bool unknown_ = false;          // after a drop, until the state is known again
  unsigned seen_since_drop_ = 0;  // bits: x, y, pressure, touch, tool
  PenFrame frame_;
};

double event_time_s(const input_event& ev) noexcept;

// Decode a whole stream: one frame per SYN_REPORT.
std::vector<PenFrame> decode_pen_events(const TabletAxes& axes, const TabletConfig& config,
                                        const std::vector<input_event>& events);

}  // namespace palprig
