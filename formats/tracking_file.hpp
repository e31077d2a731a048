#pragma once
// The tracking file (JSON, versioned): how a tracker's tools become fingers. Which
// OpenIGTLink device names (PLUS's "StylusToTracker", "Finger1ToTracker") are which finger,
// where each fingertip sits in its tool's frame (static digitization or pivot calibration,
// paper 003), and the rigid transform from tracker space to scene space (point-based
// registration). `palprig tracking register|pivot|digitize` write it; `palprig run --input
// igtl:HOST:PORT --tracking FILE` reads it.
//
//   {"version": 1,
//    "placement": "per_finger",                    (each finger at its own tool; or "triangle":
//                                                   one tool, the three fingers around it as the pen's)
//    "tools": [{"name": "Finger1ToTracker", "finger": 1,
//               "tip": {"offset_mm": [0, 0, 0], "method": "pivot", "rms_mm": 0.31}}, ...],
//    "tracker_to_scene": {"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "translation_mm": [0, 0, 0],
//                         "fre_mm": 0.42, "fiducials": 4},
//    "reader_fifo_priority": 60}
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/finger_layout.hpp"
#include "models/rigid_transform.hpp"

namespace palprig {

inline constexpr int kTrackingFileVersion = 1;
// OpenIGTLink's device name field: 20 bytes.
inline constexpr std::size_t kMaxToolNameChars = 20;

enum class TrackedPlacement { triangle, per_finger };

struct ToolTip {
  Vec3_mm offset_mm{};           // the fingertip in the tool's frame (paper 003's p_local)
  std::string method;            // how it was found: "pivot", "digitized", "measured" ("" unknown)
  double rms_mm = std::nan("");  // its residual, when a calibration measured one
};

struct TrackedTool {
  std::string name;  // the OpenIGTLink device name
  int finger = 0;    // 0-based; the triangle's tool is finger 0 (the right-angle vertex)
  ToolTip tip;
};

struct TrackerRegistration {
  RigidTransform tracker_to_scene;  // identity: the tracker's frame is the scene's
  double fre_mm = std::nan("");     // fiducial registration error, when registered
  int fiducials = 0;
};

struct TrackingConfig {
  std::string source;  // file, for messages
  TrackedPlacement placement = TrackedPlacement::triangle;
  std::vector<TrackedTool> tools;
  TrackerRegistration registration;
  int reader_fifo_priority = 60;  // runtime/thread_priorities.hpp; 0: normal scheduling

  // The tool mapped to `finger`, or nullptr.
  const TrackedTool* tool_for_finger(int finger) const noexcept;
  const TrackedTool* tool_named(const std::string& name) const noexcept;
};

// Throws InputError naming the file and field.
TrackingConfig load_tracking_file(const std::filesystem::path& path);
TrackingConfig parse_tracking(const nlohmann::json& doc, const std::string& file);
// The file's text as write_tracking_file writes it (one tool per line, numbers to 9 digits).
std::string tracking_text(const TrackingConfig& config);
// Written whole or not at all (io/checked_output.hpp), read back through the loader first.
void write_tracking_file(const std::filesystem::path& path, const TrackingConfig& config);

}  // namespace palprig
