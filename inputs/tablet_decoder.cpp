#include "inputs/tablet_decoder.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/error.hpp"

namespace palprig {

namespace {
enum SeenBit : unsigned { kSeenX = 1, kSeenY = 2, kSeenPressure = 4, kSeenTouch = 8, kSeenTool = 16 };

bool is_tool_key(int code) noexcept {
  switch (code) {
    case BTN_TOOL_PEN:
    case BTN_TOOL_RUBBER:
    case BTN_TOOL_BRUSH:
    case BTN_TOOL_PENCIL:
    case BTN_TOOL_AIRBRUSH: return true;
    default: return false;
  }
}
}  // namespace

double event_time_s(const input_event& ev) noexcept {
  return double(ev.input_event_sec) + double(ev.input_event_usec) * 1e-6;
}

TabletDecoder::TabletDecoder(const TabletAxes& axes, const TabletConfig& config) : axes_(axes), config_(config) {
  if (axes.x_max <= axes.x_min || axes.y_max <= axes.y_min) throw BadInput("the tablet reports an empty X or Y range");
  if (axes.pressure_max <= axes.pressure_min) throw BadInput("the tablet reports no pressure range");
  auto units_per_mm = [](int resolution, int lo, int hi, double size_mm, const char* axis) {
    if (size_mm > 0) return double(hi - lo) / size_mm;  // the rig file's size wins
    if (resolution > 0) return double(resolution);
    throw BadInput(std::string("the tablet reports no resolution on ") + axis +
                   "; give tablet.size_mm [width, height] in the rig file");
  };
  x_units_per_mm_ = units_per_mm(axes.x_resolution, axes.x_min, axes.x_max, config.size_mm[0], "X");
  y_units_per_mm_ = units_per_mm(axes.y_resolution, axes.y_min, axes.y_max, config.size_mm[1], "Y");
  state_.x = axes.x_min;
  state_.y = axes.y_min;
  state_.pressure = axes.pressure_min;
  frame_.x_mm = -config.origin_mm[0];
  frame_.y_mm = -config.origin_mm[1];
}

bool TabletDecoder::feed(const input_event& ev) noexcept {
  if (ev.type == EV_SYN && ev.code == SYN_DROPPED) {
    dropping_ = true;
    unknown_ = true;
    seen_since_drop_ = 0;
    return false;
  }
  if (dropping_) {
    if (ev.type == EV_SYN && ev.code == SYN_REPORT) {
      dropping_ = false;  // the next events describe changes we can use; the state is still unknown
      close_frame(event_time_s(ev));
      return true;
    }
    return false;
  }
  if (ev.type == EV_ABS) {
    switch (ev.code) {
      case ABS_X:
        state_.x = ev.value;
        seen_since_drop_ |= kSeenX;
        break;
      case ABS_Y:
        state_.y = ev.value;
        seen_since_drop_ |= kSeenY;
        break;
      case ABS_PRESSURE:
        state_.pressure = ev.value;
        seen_since_drop_ |= kSeenPressure;
        break;
      default: break;  // tilt, distance, misc: not used
    }
  } else if (ev.type == EV_KEY) {
    if (ev.code == BTN_TOUCH) {
      state_.touch = ev.value != 0;
      seen_since_drop_ |= kSeenTouch;
    } else if (is_tool_key(ev.code)) {
      state_.tool = ev.value != 0;
      tool_keys_seen_ = true;
      seen_since_drop_ |= kSeenTool;
    }
  } else if (ev.type == EV_SYN && ev.code == SYN_REPORT) {
    if (unknown_ && (seen_since_drop_ & (kSeenX | kSeenY | kSeenPressure)) == (kSeenX | kSeenY | kSeenPressure)) {
      // Axes flow again: the pen is in proximity; keys not re-reported are inferred.
      if (!(seen_since_drop_ & kSeenTool)) state_.tool = true;
      if (!(seen_since_drop_ & kSeenTouch)) state_.touch = state_.pressure > axes_.pressure_min;
      unknown_ = false;
    }
    close_frame(event_time_s(ev));
    return true;
  }
  return false;
}

void TabletDecoder::resync(const PenState& state, double t_s) noexcept {
  state_ = state;
  tool_keys_seen_ = true;
  dropping_ = false;
  unknown_ = false;
  close_frame(t_s);
}

void TabletDecoder::close_frame(double t_s) noexcept {
  PenFrame f;
  f.t_s = t_s;
  f.synced = synced();
  f.x_mm = double(state_.x - axes_.x_min) / x_units_per_mm_ - config_.origin_mm[0];
  f.y_mm = double(state_.y - axes_.y_min) / y_units_per_mm_ - config_.origin_mm[1];
  // A device without tool keys is in proximity whenever it reports.
  f.in_proximity = f.synced && (state_.tool || !tool_keys_seen_);
  const bool pressed = axes_.has_touch_key ? state_.touch : state_.pressure > axes_.pressure_min;
  f.in_contact = f.in_proximity && pressed;
  const double normalised = std::clamp(
      double(state_.pressure - axes_.pressure_min) / double(axes_.pressure_max - axes_.pressure_min), 0.0, 1.0);
  f.force_N = f.in_contact ? config_.pressure.force_N(normalised) : 0.0;
  frame_ = f;
}

std::vector<PenFrame> decode_pen_events(const TabletAxes& axes, const TabletConfig& config,
                                        const std::vector<input_event>& events) {
  TabletDecoder decoder(axes, config);
  std::vector<PenFrame> frames;
  for (const auto& ev : events)
    if (decoder.feed(ev)) frames.push_back(decoder.frame());
  return frames;
}

}  // namespace palprig
