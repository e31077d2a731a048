// touch_fiducials as `palprig tracking register` runs it, against a real OpenIGTLink server on
// loopback (IgtlPoseServer, which `palprig igtl-replay` wraps): a reader that falls behind and
// then reads the poses in one burst, as on a loaded machine, still takes each rest at its own
// fiducial, because a hold is counted in the tracker's time (the poses' header timestamps).
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "calibration/tracker_calibration.hpp"
#include "inputs/igtl_pose_reader.hpp"
#include "inputs/igtl_pose_server.hpp"

namespace palprig {
namespace {

using namespace std::chrono_literals;

constexpr int kWayPoses = 12;   // 0.3 s on the way to a fiducial at 40 Hz
constexpr int kRestPoses = 48;  // then 1.2 s at rest on it: 0.2 s more than the 1 s hold

Fiducial fiducial(const std::string& name, double x_mm, double y_mm) {
  Fiducial f;
  f.name = name;
  f.scene_mm = {x_mm, y_mm, 0};
  return f;
}

// A stylus whose pose is its tip, moving to each fiducial in turn and resting on it.
std::vector<RecordedPose> touches(const std::vector<Fiducial>& fiducials) {
  std::vector<RecordedPose> rec;
  double t_s = 0;
  Vec3_mm from{0, 0, 30};
  for (const Fiducial& f : fiducials) {
    for (int k = 0; k < kWayPoses + kRestPoses; ++k, t_s += 0.025) {
      const double u = k < kWayPoses ? (k + 1.0) / kWayPoses : 1.0;
      RecordedPose r;
      r.t_s = t_s;
      r.tool = "StylusTipToTracker";
      for (int i = 0; i < 3; ++i) r.pose.translation_mm[i] = from[i] + (f.scene_mm[i] - from[i]) * u;
      rec.push_back(r);
    }
    from = f.scene_mm;
  }
  return rec;
}

TEST(TouchFiducials, ARestReadInOneBurstIsTakenByTheTrackersTimeAtItsOwnFiducial) {
  const std::vector<Fiducial> fiducials = {fiducial("F1", 10, 10), fiducial("F2", 150, 10), fiducial("F3", 150, 110)};
  PoseServerOptions options;
  options.port = 0;
  IgtlPoseServer server(touches(fiducials), options);
  server.start();
  IgtlPoseReader tracker("127.0.0.1", server.port(), "the test's tracker");
  // The reader stalls while the first rest and the way to the second are sent, so they reach it
  // in one read. Counted in arrival time that rest lasted no time at all, and the second
  // fiducial's rest was taken as the first's.
  const std::uint64_t stalled_through = kWayPoses + kRestPoses + kWayPoses;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (server.sent() < stalled_through && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(5ms);  // the stall itself: the fault this test makes
  ASSERT_GE(server.sent(), stalled_through);

  TrackedTool stylus;
  stylus.name = "StylusTipToTracker";
  TouchRules rules;
  rules.timeout_s = 20;
  std::vector<std::string> said;
  const std::vector<Vec3_mm> touched =
      touch_fiducials(tracker, stylus, fiducials, rules, [&](const std::string& line) { said.push_back(line); });
  ASSERT_EQ(touched.size(), fiducials.size());
  for (std::size_t k = 0; k < fiducials.size(); ++k)
    EXPECT_LT(distance_mm(touched[k], fiducials[k].scene_mm), 1e-3) << fiducials[k].name;
  server.stop();
}

}  // namespace
}  // namespace palprig
