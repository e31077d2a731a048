// Tracked fingers over OpenIGTLink, against a real server on loopback: the stream
// decoder on messages packed by libopenigtlink itself, the pose recording file, the replay
// server, and the loop's input following the tools, venting a finger whose tool stops and
// reporting a server that goes away.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <igtlOSUtil.h>
#include <igtlPositionMessage.h>
#include <igtlServerSocket.h>
#include <igtlStringMessage.h>
#include <igtlTransformMessage.h>
#include <igtl_util.h>

#include "inputs/igtl_input.hpp"
#include "inputs/igtl_pose_server.hpp"
#include "inputs/igtl_stream.hpp"
#include "inputs/pose_recording.hpp"
#include "inputs/tracker_clock.hpp"
#include "core/input_error.hpp"
#include "runtime/worker_fault.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using namespace std::chrono_literals;
using palprig::test_support::TempDir;

namespace {

std::vector<std::uint8_t> bytes_of(igtl::MessageBase* m) {
  m->Pack();
  const auto* p = static_cast<const std::uint8_t*>(m->GetPackPointer());
  return {p, p + m->GetPackSize()};
}

std::vector<std::uint8_t> transform_bytes(const char* name, float x, float y, float z) {
  igtl::TransformMessage::Pointer m = igtl::TransformMessage::New();
  m->SetDeviceName(name);
  igtl::Matrix4x4 mat;
  igtl::IdentityMatrix(mat);
  // 90 degrees about z.
  mat[0][0] = 0, mat[0][1] = -1, mat[1][0] = 1, mat[1][1] = 0;
  mat[0][3] = x, mat[1][3] = y, mat[2][3] = z;
  m->SetMatrix(mat);
  return bytes_of(m.GetPointer());
}

void append(std::vector<std::uint8_t>& to, const std::vector<std::uint8_t>& more) {
  to.insert(to.end(), more.begin(), more.end());
}

// Waits for a condition with a deadline (no fixed sleeps).
template <class F>
bool eventually(F&& condition, std::chrono::milliseconds deadline = 5000ms) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(2ms);
  }
  return condition();
}

RecordedPose at(double t, const std::string& tool, Vec3_mm p) {
  RecordedPose r;
  r.t_s = t;
  r.tool = tool;
  r.pose.translation_mm = p;
  return r;
}

TrackingConfig two_finger_tracking() {
  TrackingConfig t;
  t.placement = TrackedPlacement::per_finger;
  t.tools = {TrackedTool{"Finger1ToTracker", 0, {{0, 0, -10}, "", std::nan("")}},
             TrackedTool{"Finger2ToTracker", 1, {{0, 0, -10}, "", std::nan("")}},
             TrackedTool{"Finger3ToTracker", 2, {}}};
  // Tracker -> scene: a shift.
  t.registration.tracker_to_scene.translation_mm = {100, 50, 0};
  t.reader_fifo_priority = 0;
  return t;
}

}  // namespace

TEST(IgtlStream, DecodesTransformAndPositionEvenOneByteAtATime) {
  std::vector<std::uint8_t> stream;
  append(stream, transform_bytes("StylusToTracker", 10, 20, 30));
  igtl::StringMessage::Pointer text = igtl::StringMessage::New();
  text->SetDeviceName("Note");
  text->SetString("not a pose");
  append(stream, bytes_of(text.GetPointer()));
  igtl::PositionMessage::Pointer pos = igtl::PositionMessage::New();
  pos->SetDeviceName("Finger1");
  pos->SetPackType(igtl::PositionMessage::ALL);
  pos->SetPosition(1.f, 2.f, 3.f);
  pos->SetQuaternion(0.f, 0.f, 0.7071068f, 0.7071068f);
  append(stream, bytes_of(pos.GetPointer()));
  // POSITION without a quaternion: libopenigtlink 1.11 cannot pack one (its PackBody converts
  // all seven floats of a 12-byte body, past its end), so it is cut from a whole one here: the
  // position's 12 bytes, the header's body size and CRC set to match.
  igtl::PositionMessage::Pointer full = igtl::PositionMessage::New();
  full->SetDeviceName("Finger2");
  full->SetPackType(igtl::PositionMessage::ALL);
  full->SetPosition(4.f, 5.f, 6.f);
  std::vector<std::uint8_t> only = bytes_of(full.GetPointer());
  only.resize(58 + 12);
  const std::uint64_t crc = crc64(only.data() + 58, 12, 0);
  for (int i = 0; i < 8; ++i) {
    only[42 + i] = static_cast<std::uint8_t>(i == 7 ? 12 : 0);  // body size, big-endian
    only[50 + i] = static_cast<std::uint8_t>(crc >> (8 * (7 - i)));
  }
  append(stream, only);

  IgtlStreamDecoder decoder;
  std::vector<DecodedPose> poses;
  for (std::uint8_t b : stream) ASSERT_TRUE(decoder.feed(&b, 1, poses));
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_STREQ(poses[0].device, "StylusToTracker");
  EXPECT_FLOAT_EQ(poses[0].pose.translation_mm[1], 20);
  EXPECT_NEAR(poses[0].pose.rotation[1][0], 1, 1e-6);
  EXPECT_TRUE(poses[0].is_rotation);
  EXPECT_STREQ(poses[1].device, "Finger1");
  EXPECT_NEAR(poses[1].pose.rotation[0][1], -1, 1e-6);  // the quaternion: 90 degrees about z
  EXPECT_TRUE(poses[1].has_rotation);
  EXPECT_FALSE(poses[2].has_rotation);
  EXPECT_FLOAT_EQ(poses[2].pose.translation_mm[2], 6);
  EXPECT_EQ(decoder.counts().messages, 4u);
  EXPECT_EQ(decoder.counts().other_types, 1u);
  // All at once gives the same.
  IgtlStreamDecoder whole;
  std::vector<DecodedPose> again;
  ASSERT_TRUE(whole.feed(stream.data(), stream.size(), again));
  EXPECT_EQ(again.size(), 3u);
}

TEST(IgtlStream, CarriesTheHeadersTimestampAsThePosesTime) {
  igtl::TransformMessage::Pointer m = igtl::TransformMessage::New();
  m->SetDeviceName("StylusToTracker");
  m->SetTimeStamp(1700000000u, 1u << 30);  // a quarter of a second in the header's units of 2^-32 s
  std::vector<std::uint8_t> stream = bytes_of(m.GetPointer());
  // A sender that sets 0. (One that sets nothing sends whatever libopenigtlink 1.11 left in the
  // field, which it does not initialise: 0xbebebebe under AddressSanitizer; HoldTime copes.)
  igtl::TransformMessage::Pointer zero = igtl::TransformMessage::New();
  zero->SetDeviceName("StylusToTracker");
  zero->SetTimeStamp(0u, 0u);
  append(stream, bytes_of(zero.GetPointer()));
  IgtlStreamDecoder decoder;
  std::vector<DecodedPose> poses;
  ASSERT_TRUE(decoder.feed(stream.data(), stream.size(), poses));
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_DOUBLE_EQ(poses[0].stamp_s, 1700000000.25);
  EXPECT_EQ(poses[1].stamp_s, 0.0);
}

TEST(IgtlStream, SkipsBadCrcAndOtherHeaderVersionsAndRefusesGarbage) {
  std::vector<std::uint8_t> bad = transform_bytes("T", 1, 2, 3);
  bad.back() ^= 0x40;  // the body no longer matches its CRC
  std::vector<std::uint8_t> v3 = transform_bytes("T", 1, 2, 3);
  v3[1] = 2;  // header version 2: OpenIGTLink 3's extended header
  std::vector<std::uint8_t> zeros = transform_bytes("Lost", 0, 0, 0);
  {
    // A lost tool's all-zero matrix: decoded, flagged as no rotation.
    igtl::TransformMessage::Pointer m = igtl::TransformMessage::New();
    m->SetDeviceName("Lost");
    igtl::Matrix4x4 mat = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 1}};
    m->SetMatrix(mat);
    zeros = bytes_of(m.GetPointer());
  }
  // A TRANSFORM whose body is 16 bytes, not 48: libopenigtlink would read 48 (found by
  // fuzz_igtl_stream); skipped as malformed by its size.
  std::vector<std::uint8_t> short_body = transform_bytes("Short", 1, 2, 3);
  short_body.resize(58 + 16);
  for (int i = 0; i < 8; ++i) short_body[42 + i] = static_cast<std::uint8_t>(i == 7 ? 16 : 0);
  std::vector<std::uint8_t> stream;
  append(stream, bad);
  append(stream, v3);
  append(stream, short_body);
  append(stream, zeros);
  append(stream, transform_bytes("T", 7, 8, 9));
  IgtlStreamDecoder d;
  std::vector<DecodedPose> poses;
  ASSERT_TRUE(d.feed(stream.data(), stream.size(), poses));
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_STREQ(poses[0].device, "Lost");
  EXPECT_FALSE(poses[0].is_rotation);
  EXPECT_FLOAT_EQ(poses[1].pose.translation_mm[0], 7);
  EXPECT_EQ(d.counts().crc_failures, 1u);
  EXPECT_EQ(d.counts().other_versions, 1u);
  EXPECT_EQ(d.counts().malformed, 1u);

  // An HTTP server is no tracker.
  IgtlStreamDecoder http;
  const std::string reply = "HTTP/1.1 200 OK\r\nContent-Type: text/html\r\nContent-Length: 1000\r\n\r\n<html><body>...";
  std::vector<DecodedPose> none;
  EXPECT_FALSE(http.feed(reinterpret_cast<const std::uint8_t*>(reply.data()), reply.size(), none));
  EXPECT_NE(std::string(http.error()).find("not an OpenIGTLink stream"), std::string::npos) << http.error();
}

TEST(PoseRecording, LoadsTheShippedPathsAndRefusesBadRows) {
  const auto dir = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "tracking";
  const auto pass = load_pose_recording(dir / "phantom_three_fingers_pass.csv");
  EXPECT_EQ(recorded_tools(pass),
            (std::vector<std::string>{"Finger1ToTracker", "Finger2ToTracker", "Finger3ToTracker"}));
  EXPECT_NEAR(pass.back().t_s, 10.7, 0.05);
  TempDir t;
  auto refused = [&](const std::string& text) {
    try {
      (void)load_pose_recording(t.write("p.csv", text));
    } catch (const InputError& e) {
      const std::string w = e.what();
      return w.substr(w.find("p.csv"));
    }
    return std::string("accepted");
  };
  const std::string h = "t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw\n";
  EXPECT_EQ(refused(h + "0,A,1,2,3,0,0,0,1\n"), "accepted");
  EXPECT_EQ(refused("t,tool\n"), "p.csv: line 1: the header 't_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw', got 't,tool'");
  EXPECT_EQ(refused(h + "0,A,1,2,3,0,0,0\n"), "p.csv: line 2: 9 values (t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw), got 8");
  EXPECT_EQ(refused(h + "0,A,1,2,x,0,0,0,1\n"), "p.csv: line 2, z_mm: a finite number, got 'x'");
  EXPECT_EQ(refused(h + "0,A,1,2,3,0,0,0,0\n"), "p.csv: line 2, qx..qw: a non-zero quaternion (x, y, z, w)");
  EXPECT_EQ(refused(h + "1,A,1,2,3,0,0,0,1\n0.5,B,1,2,3,0,0,0,1\n"),
            "p.csv: line 3, t_s: a time no earlier than the previous row's, got 0.5");
  EXPECT_EQ(refused(h + "1,A,1,2,3,0,0,0,1\n1,A,1,2,3,0,0,0,1\n"),
            "p.csv: line 3, t_s: a time after tool A's previous row, got 1");
  EXPECT_EQ(refused(h + "0,ToolNameMuchTooLongForIGTL,1,2,3,0,0,0,1\n"),
            "p.csv: line 2, tool: an OpenIGTLink device name of 1 to 20 characters, got 'ToolNameMuchTooLongForIGTL'");
  EXPECT_EQ(refused(h), "p.csv: line 1: at least one pose");
}

TEST(IgtlInput, FollowsEachToolOnLoopbackAndVentsAFingerWhoseToolStops) {
  clear_worker_faults();
  // Finger 1 for 2 s, finger 2 for 0.3 s only (then out of view), finger 3 never.
  std::vector<RecordedPose> rec;
  for (int k = 0; k <= 80; ++k) {
    const double t = k * 0.025;
    rec.push_back(at(t, "Finger1ToTracker", {10.0 + k, 20, 5}));
    if (t <= 0.3) rec.push_back(at(t, "Finger2ToTracker", {-5, -5, 7}));
  }
  PoseServerOptions options;
  options.port = 0;
  IgtlPoseServer server(rec, options);
  server.start();
  IgtlInput input({"127.0.0.1", server.port()}, two_finger_tracking(), 0.1);
  EXPECT_NE(input.describe().find("Finger2ToTracker"), std::string::npos);
  const auto start = std::chrono::steady_clock::now();
  auto now_s = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  TouchSample s;
  ASSERT_TRUE(eventually([&] {
    s = input.latest(now_s());
    return s.fingers[1].vent == FingerVent::none && s.fingers[0].vent == FingerVent::none;
  }));
  EXPECT_TRUE(s.own_positions);
  EXPECT_TRUE(s.force_from_load_cells);
  EXPECT_TRUE(s.in_contact);
  EXPECT_EQ(s.fingers[2].vent, FingerVent::tool_not_seen);
  // Tip 10 mm along the tool's -z (identity rotation), then the registration's shift.
  EXPECT_NEAR(s.fingers[1].x_mm, 95, 1e-3);
  EXPECT_NEAR(s.fingers[1].y_mm, 45, 1e-3);
  EXPECT_NEAR(s.fingers[1].z_mm, -3, 1e-3);
  EXPECT_GE(s.fingers[0].x_mm, 110);
  EXPECT_NEAR(s.fingers[0].y_mm, 70, 1e-3);
  // Finger 1 moves on while finger 2's tool has gone: finger 2 vented, stale, the rest goes on.
  ASSERT_TRUE(eventually([&] {
    s = input.latest(now_s());
    return s.fingers[1].vent == FingerVent::tool_stale;
  }));
  EXPECT_EQ(s.fingers[0].vent, FingerVent::none);
  const double x_then = s.fingers[0].x_mm;
  ASSERT_TRUE(eventually([&] { return input.latest(now_s()).fingers[0].x_mm > x_then + 5; }));
  // The sample itself stays fresh: the reader's heartbeat goes on.
  EXPECT_LT(now_s() - input.latest(now_s()).t_s, 0.05);
  const TrackerStatus st = input.status();
  EXPECT_TRUE(st.connected);
  EXPECT_GT(st.tools[0].poses, 10u);
  EXPECT_EQ(st.tools[2].poses, 0u);
  EXPECT_FALSE(worker_fault_pending(nullptr, 0));
}

TEST(TrackerClock, APoseIsTimedByItsStampOnOurClockAndNeverAfterItArrived) {
  // The tracker's clock is 1.7e9 s ahead of ours; transport takes 2 ms plus 0 to 15 ms.
  TrackerClock clock;
  const double extra_s[] = {0.015, 0.004, 0.0, 0.011, 0.007};
  for (int k = 0; k < 50; ++k) {
    const double taken = 100 + 0.025 * k, arrived = taken + 0.002 + extra_s[k % 5];
    const double t = clock.taken_at(1.7e9 + taken, arrived);
    EXPECT_LE(t, arrived) << k;
    // Once the fastest pose has been seen (the third), every pose is timed 2 ms after it was
    // taken, give or take what the offset may grow between the fastest poses (kDriftAllowance x
    // 125 ms) and the stamps' rounding at 1.7e9 s.
    if (k >= 2) {
      EXPECT_NEAR(t, taken + 0.002, TrackerClock::kDriftAllowance * 0.125 + 1e-6) << k;
    }
  }
  EXPECT_TRUE(clock.stamped());
}

TEST(TrackerClock, FollowsATrackerClockThatRunsSlowAndFallsBackToArrivalWithoutStamps) {
  // 100 ppm slow (a poor crystal), 40 poses a second for ten minutes, 1 to 3 ms in transit: the
  // offset grows with it (up to 1000 ppm is followed), so poses stay timed within the jitter.
  TrackerClock slow;
  double worst_s = 0;
  for (int k = 0; k < 24000; ++k) {
    const double taken = 0.025 * k, arrived = taken + 0.001 + 0.002 * ((k * 7) % 11) / 10.0;
    const double t = slow.taken_at(1.7e9 + taken * (1 - 1e-4), arrived);
    worst_s = std::max(worst_s, std::abs(t - (taken + 0.001)));
  }
  EXPECT_LT(worst_s, 0.002);
  // None set (0), or left unset (libopenigtlink 1.11's constant): the arrival time, as before.
  for (const double garbage : {0.0, 3.2e9}) {
    TrackerClock none;
    for (int k = 0; k < 5; ++k) EXPECT_EQ(none.taken_at(garbage, 7.0 + 0.03 * k), 7.0 + 0.03 * k) << garbage;
    EXPECT_FALSE(none.stamped());
  }
}

TEST(TrackerClock, AToolBackInViewKeepsItsStampsAndAStampThatIsNoClockIsDropped) {
  // Out of view for 5 s (PlusServer sends nothing for it): its next stamp is 5 s on, and so is
  // its arrival; that is a clock.
  TrackerClock clock;
  EXPECT_NEAR(clock.taken_at(1.7e9, 10.002), 10.002, 1e-6);
  // 1 ms late: timed 2 ms after it was taken, give or take the offset's allowed growth (28 us here).
  EXPECT_NEAR(clock.taken_at(1.7e9 + 0.025, 10.030), 10.027, 1e-4);
  EXPECT_NEAR(clock.taken_at(1.7e9 + 5.025, 15.027), 15.027, 1e-4);
  EXPECT_TRUE(clock.stamped());
  // A stamp 100 s on after 25 ms here is no clock, nor one that goes back: arrival times from then on.
  TrackerClock jumps;
  jumps.taken_at(1.7e9, 10.0);
  EXPECT_EQ(jumps.taken_at(1.7e9 + 100, 10.025), 10.025);
  EXPECT_FALSE(jumps.stamped());
  EXPECT_EQ(jumps.taken_at(1.7e9 + 100.025, 10.05), 10.05);
  TrackerClock back;
  back.taken_at(1.7e9, 10.0);
  EXPECT_EQ(back.taken_at(1.7e9 - 0.025, 10.025), 10.025);
  EXPECT_FALSE(back.stamped());
}

namespace {

// A tracker whose poses reach us late by turns: pose k of finger 1 (x = 10 + k mm) is stamped
// when it was taken, k * 25 ms after the start, and sent 0 or 15 ms after that. libopenigtlink's
// own server socket; a thread paced on the clock as a tracker is.
class LateTracker {
 public:
  LateTracker() {
    if (socket_->CreateServer(0) != 0) throw std::runtime_error("cannot listen");
    port_ = socket_->GetServerPort();
    thread_ = std::thread([this] { serve(); });
  }
  ~LateTracker() {
    stop_ = true;
    thread_.join();
    socket_->CloseSocket();
  }
  int port() const { return port_; }
  static constexpr int kPoses = 60;

 private:
  void serve() {
    igtl::ClientSocket::Pointer client;
    while (!stop_ && client.IsNull()) client = socket_->WaitForConnection(100);
    if (client.IsNull()) return;
    igtl::TimeStamp::Pointer stamp = igtl::TimeStamp::New();
    stamp->GetTime();
    const double wall_start_s = stamp->GetTimeStamp();
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kPoses && !stop_; ++k) {
      const double taken_s = 0.025 * k, late_s = k % 2 ? 0.015 : 0.0;
      std::this_thread::sleep_until(start + std::chrono::duration<double>(taken_s + late_s));
      igtl::TransformMessage::Pointer m = igtl::TransformMessage::New();
      m->SetDeviceName("Finger1ToTracker");
      igtl::Matrix4x4 mat;
      igtl::IdentityMatrix(mat);
      mat[0][3] = static_cast<float>(10 + k);
      m->SetMatrix(mat);
      stamp->SetTime(wall_start_s + taken_s);
      m->SetTimeStamp(stamp);
      m->Pack();
      if (client->Send(m->GetPackPointer(), m->GetPackSize()) != 1) return;
    }
    while (!stop_) std::this_thread::sleep_for(5ms);  // stay connected until the test is done
  }
  igtl::ServerSocket::Pointer socket_ = igtl::ServerSocket::New();
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace

TEST(IgtlInput, EachFingersPoseCarriesTheTimeItWasTakenNotWhenItArrived) {
  clear_worker_faults();
  LateTracker tracker;
  IgtlInput input({"127.0.0.1", tracker.port()}, two_finger_tracking(), 0.1);
  const auto start = std::chrono::steady_clock::now();
  auto now_s = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // Every pose the loop would see: its x (which pose it is) and the time it says it was taken.
  std::vector<std::pair<double, double>> seen;
  ASSERT_TRUE(eventually([&] {
    const TouchSample s = input.latest(now_s());
    if (s.fingers[0].vent == FingerVent::none && (seen.empty() || s.fingers[0].x_mm != seen.back().first)) {
      EXPECT_LE(s.fingers[0].pose_t_s, s.t_s + 1e-9);
      seen.emplace_back(s.fingers[0].x_mm, s.fingers[0].pose_t_s);
    }
    return !seen.empty() && seen.back().first >= 100 + 10 + LateTracker::kPoses - 1 - 1e-3;
  }));
  ASSERT_GT(seen.size(), 20u);
  // Poses k and j were taken (k - j) * 25 ms apart, whether they came 0 or 15 ms late (timed by
  // arrival, consecutive poses would be 10 or 40 ms apart). The first few fix the offset.
  for (std::size_t i = 6; i < seen.size(); ++i) {
    const double poses_apart = seen[i].first - seen[i - 1].first;
    EXPECT_NEAR(seen[i].second - seen[i - 1].second, 0.025 * poses_apart, 0.002) << "pose at x " << seen[i].first;
  }
  // The unmapped finger has no pose and no pose time.
  EXPECT_FALSE(std::isfinite(input.latest(now_s()).fingers[2].pose_t_s));
  EXPECT_FALSE(worker_fault_pending(nullptr, 0));
}

TEST(IgtlInput, OneToolCarriesTheTriangleAndUnmappedToolsAreListed) {
  clear_worker_faults();
  std::vector<RecordedPose> rec;
  for (int k = 0; k < 200; ++k) {
    rec.push_back(at(k * 0.01, "StylusToTracker", {30, 40, -2}));
    rec.push_back(at(k * 0.01, "ReferenceToTracker", {0, 0, 0}));
  }
  PoseServerOptions options;
  options.port = 0;
  options.position_messages = true;
  IgtlPoseServer server(rec, options);
  server.start();
  TrackingConfig t;
  t.placement = TrackedPlacement::triangle;
  t.tools = {TrackedTool{"StylusToTracker", 0, {}}};
  t.reader_fifo_priority = 0;
  IgtlInput input({"127.0.0.1", server.port()}, t, 0.1);
  TouchSample s;
  ASSERT_TRUE(eventually([&] {
    s = input.latest(0);
    return s.fingers[0].vent == FingerVent::none;
  }));
  EXPECT_FALSE(s.own_positions);
  EXPECT_NEAR(s.x_mm, 30, 1e-4);
  EXPECT_NEAR(s.y_mm, 40, 1e-4);
  for (const auto& f : s.fingers) {
    EXPECT_EQ(f.vent, FingerVent::none);
    EXPECT_NEAR(f.z_mm, -2, 1e-4);  // the one tool's depth for every finger
  }
  ASSERT_TRUE(eventually([&] { return std::strcmp(input.status().other_names[0], "ReferenceToTracker") == 0; }));
}

TEST(IgtlInput, RefusesAServerThatIsNotThereAndReportsOneThatGoes) {
  clear_worker_faults();
  // A port nobody listens on: bind one, learn it, close it.
  int port = 0;
  {
    IgtlPoseServer probe({at(0, "X", {0, 0, 0})}, PoseServerOptions{0, false, false});
    probe.start();
    port = probe.port();
    probe.stop();
  }
  try {
    IgtlInput input({"127.0.0.1", port}, two_finger_tracking(), 0.1);
    FAIL() << "connected to a closed port";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot connect: Connection refused"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_igtl_spec("igtl:localhost"), InputError);
  EXPECT_THROW(parse_igtl_spec("igtl:localhost:99999"), InputError);
  EXPECT_THROW(parse_igtl_spec("igtl:bad host:18944"), InputError);
  EXPECT_EQ(parse_igtl_spec("igtl:127.0.0.1:18944").port, 18944);

  std::vector<RecordedPose> rec;
  rec.reserve(400);
  for (int k = 0; k < 400; ++k) rec.push_back(at(k * 0.01, "Finger1ToTracker", {0, 0, 0}));
  IgtlPoseServer server(rec, PoseServerOptions{0, false, false});
  server.start();
  IgtlInput input({"127.0.0.1", server.port()}, two_finger_tracking(), 0.1);
  ASSERT_TRUE(eventually([&] { return input.latest(0).fingers[0].vent == FingerVent::none; }));
  server.stop();  // the tracker goes away: its connection closes
  char detail[256] = {0};
  ASSERT_TRUE(eventually([&] { return worker_fault_pending(detail, sizeof detail); }));
  EXPECT_NE(std::string(detail).find("the server closed the connection"), std::string::npos) << detail;
  EXPECT_FALSE(input.status().connected);
  clear_worker_faults();
}
