#pragma once
// Calibrating a tracker to the rig, from poses a live OpenIGTLink server streams:
//
//   registration: fiducials on the phantom with known scene coordinates (a CSV) are touched in
//     turn with a tracked tip; each touch is taken when the tip rests (models/pose_hold.hpp);
//     Umeyama's least-squares rigid fit (models/point_registration.hpp) maps tracker space to
//     scene space, with its fiducial registration error (FRE).
//   pivot calibration: the tip rests in a divot while the tool pivots about it for a while; the
//     tip offset in the tool's frame and its RMS residual (models/tip_calibration.hpp).
//   static digitization (paper 003): a digitizer's tip (e.g. PLUS's "StylusTipToTracker")
//     touches the fingertip; the fingertip in the finger sensor's frame is taken when the two
//     rest together, p_local = R^-1 (p_digitizer - o).
//
// Each returns a result the command prints and writes into the tracking file.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "formats/tracking_file.hpp"
#include "inputs/igtl_pose_reader.hpp"
#include "models/point_registration.hpp"
#include "models/tip_calibration.hpp"

namespace palprig {

// Fiducials CSV, header `name,x_mm,y_mm,z_mm` (scene coordinates), optionally followed by
// `tracker_x_mm,tracker_y_mm,tracker_z_mm`: where the tip touched each one (then no tracker is
// needed). Throws InputError naming the file and line.
struct Fiducial {
  std::string name;
  Vec3_mm scene_mm{};
  std::optional<Vec3_mm> touched_mm;  // in tracker space
};
std::vector<Fiducial> load_fiducials(const std::filesystem::path& path);

// How a touch is taken: the tip within radius_mm for hold_s; before the next fiducial the tip
// must leave the last touch by leave_mm; a step that sees no pose of the tool for timeout_s
// (or waits for a touch longer than that) is refused with what the tracker did send.
struct TouchRules {
  double hold_s = 1.0;
  double radius_mm = 1.0;
  double leave_mm = 5.0;
  double timeout_s = 60.0;
};

using Say = std::function<void(const std::string&)>;

// The tip of `tool` (its tip offset applied) in tracker space at each fiducial, in order.
// Throws Error (the tracker closed, the tool never came, a timeout).
std::vector<Vec3_mm> touch_fiducials(IgtlPoseReader& tracker, const TrackedTool& tool,
                                     const std::vector<Fiducial>& fiducials, const TouchRules& rules, const Say& say);

// Tracker -> scene from the touched points. Throws InputError (file: the fiducials file) when
// the points cannot determine a rigid transform.
PointRegistration register_fiducials(const std::vector<Fiducial>& fiducials, const std::vector<Vec3_mm>& touched,
                                     const std::string& fiducials_file);

// Poses of `tool` for `seconds` (only those at least min_step_deg apart from the last kept, so
// a tool held still is not counted many times), then the pivot fit. Throws Error.
PivotCalibration pivot_from_tracker(IgtlPoseReader& tracker, const std::string& tool, double seconds, double timeout_s,
                                    const Say& say, double min_step_deg = 1.0);

// Static digitization of `finger_tool`'s fingertip with `digitizer_tool`'s tip (its own tip
// offset digitizer_tip_mm). Throws Error.
Vec3_mm digitize_from_tracker(IgtlPoseReader& tracker, const std::string& finger_tool,
                              const std::string& digitizer_tool, const Vec3_mm& digitizer_tip_mm,
                              const TouchRules& rules, const Say& say);

}  // namespace palprig
