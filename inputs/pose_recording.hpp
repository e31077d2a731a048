#pragma once
// A recorded tracker path: the poses of tracked tools over time, as a tracker (an NDI Aurora
// behind PLUS) sent them. `palprig igtl-replay` serves it over OpenIGTLink in real time; the
// tests and the shipped example replay one. CSV, header required, one row per tool and time:
//
//   t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw
//   0.000,Finger1ToTracker,112.0,-40.5,8.0,0,0,0,1
//
// t_s never goes back; one tool's rows are strictly increasing in time (several tools may share
// a time). A tool missing for a while is a tool out of view (PlusServer sends valid transforms
// only). Position in mm in the tracker's frame, orientation a quaternion (normalised on load).
#include <filesystem>
#include <string>
#include <vector>

#include "models/rigid_transform.hpp"

namespace palprig {

struct RecordedPose {
  double t_s = 0;
  std::string tool;
  RigidTransform pose;  // tool -> tracker
};

struct PoseRecordingLimits {
  double max_length_s = 3600.0;
};

// Throws InputError naming the file and line. Times are shifted so the first row is at 0 s.
std::vector<RecordedPose> load_pose_recording(const std::filesystem::path& path,
                                              const PoseRecordingLimits& limits = {});
// The distinct tool names in order of first appearance.
std::vector<std::string> recorded_tools(const std::vector<RecordedPose>& poses);

}  // namespace palprig
