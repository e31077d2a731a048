#pragma once
// One reading of the pen on the touchpad, already in physical units; or, from a tracker, the
// tracked fingertips (each finger at its own position, with its own force).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "models/finger_layout.hpp"

namespace palprig {

// Why a tracked finger is vented (0 kPa) this tick; none while it is placed. Stored in telemetry
// (values kept as they are: add new reasons at the end).
enum class FingerVent : std::uint8_t {
  none = 0,
  no_tool,           // the tracking file maps no tool to this finger
  tool_not_seen,     // its tool has not been seen since the tracker connected
  tool_stale,        // no pose of its tool for safety.max_input_age_s (out of view, or the tracker stopped)
  tool_invalid,      // the tracker sent a pose that is no rigid transform (a lost tool, e.g. all zeros)
  tool_no_rotation,  // POSITION without orientation, and the tracking file gives a tip offset
};

constexpr const char* to_string(FingerVent v) noexcept {
  switch (v) {
    case FingerVent::none: return "placed";
    case FingerVent::no_tool: return "no tool mapped to this finger";
    case FingerVent::tool_not_seen: return "tool not seen yet";
    case FingerVent::tool_stale:
      return "no pose of the tool within safety.max_input_age_s (out of view or tracker stopped)";
    case FingerVent::tool_invalid: return "the tracker sent an invalid pose (tool lost)";
    case FingerVent::tool_no_rotation: return "POSITION without orientation cannot place a tip offset";
  }
  return "unknown";
}

// One finger placed by a tracker, in scene coordinates (mm; z = 0 on the tissue surface, up
// positive, so a fingertip pressing in has z < 0).
struct FingerTouch {
  double x_mm = 0, y_mm = 0, z_mm = 0;
  double force_N = 0;  // its own load cell (TouchSample::per_finger_force)
  FingerVent vent = FingerVent::none;
  // When its position was taken, on the loop's clock (s): a tracker's pose is older than the
  // sample that carries it, and several samples carry the same pose. NaN: taken with the sample
  // (TouchSample::t_s). The lag compensation extrapolates the position from this time.
  double pose_t_s = std::numeric_limits<double>::quiet_NaN();
};

struct TouchSample {
  double t_s = 0;  // when it was taken, on the loop's clock (seconds since run start)
  double x_mm = 0, y_mm = 0;
  double force_N = 0;  // pressing force, >= 0 (with per-finger forces: the largest)
  bool in_contact = false;

  // Tracked fingers. The pen leaves all of these at their defaults, and the tick then
  // places the three fingers in FingerLayout's triangle around (x_mm, y_mm), as it always did.
  bool own_positions = false;                       // each finger at fingers[i] (no triangle)
  bool per_finger_force = false;                    // each finger pressed with fingers[i].force_N
  bool force_from_load_cells = false;               // the rig's load cells give the force: RigStep fills it in
  std::array<FingerTouch, kFingerCount> fingers{};  // vent applies in either placement
};

// When finger i's position was taken: its pose time, else the sample's.
inline double position_time_s(const TouchSample& s, std::size_t i) noexcept {
  const double t = s.fingers[i].pose_t_s;
  return std::isfinite(t) ? t : s.t_s;
}

}  // namespace palprig
