#pragma once
// IgtlInput: tracked fingers over OpenIGTLink as the loop's input source. A client
// connects to a tracker's server (PlusServer streaming an NDI Aurora, 3D Slicer, `palprig
// igtl-replay`) at `igtl:HOST:PORT`; a reader thread below the loop's priority receives
// TRANSFORM (and POSITION) messages, keeps the poses of the tools the tracking file names,
// carries each fingertip into scene space (p = o + R p_local, paper 003 eq. 1, then the
// registration) and publishes them with their arrival times through a wait-free LatestValue;
// latest() only reads it, allocates nothing and never waits.
//
// What the loop sees (TouchSample):
//   - per_finger placement: each finger at its own tool's fingertip (own_positions); a finger
//     without a tool, or whose tool has not been seen, sent no pose for safety.max_input_age_s
//     (out of view: PlusServer sends valid transforms only; or the tracker stopped sending) or
//     sent an invalid one, is vented with that reason (FingerVent) while the others go on.
//   - triangle placement: the one tool's fingertip is the pen; the three fingers stand around it.
//   - the pressing force is the rig's load cells' (force_from_load_cells): RigStep reads them.
//   - the sample's time is the reader's last wake (every 10 ms at least), so a reader that
//     stalls makes the sample stale and the tick vents everything (input_stale). Each finger's
//     position carries the time its pose was taken (FingerTouch::pose_t_s: the tracker's stamp
//     on the loop's clock, inputs/tracker_clock.hpp), which the lag compensation extrapolates
//     from; a tool's staleness is counted from its pose's arrival.
// A connection the server closes (the tracker process died) or a stream that is not
// OpenIGTLink is a worker fault: every channel vents and the run stops with the reason.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "formats/tracking_file.hpp"
#include "inputs/igtl_pose_reader.hpp"
#include "inputs/input_source.hpp"
#include "runtime/latest_value.hpp"

namespace palprig {

struct IgtlEndpoint {
  std::string host;
  int port = 18944;
  std::string text() const { return host + ":" + std::to_string(port); }
};

// "igtl:HOST:PORT" -> endpoint; throws InputError naming the field "input".
IgtlEndpoint parse_igtl_spec(const std::string& spec);
bool is_igtl_input(const std::string& spec);

// What the reader knows of one tool the tracking file names. Plain data: crosses threads as is.
struct TrackedToolState {
  std::int64_t arrived_ns = 0;            // CLOCK_MONOTONIC of its last usable pose; 0: none yet
  std::int64_t taken_ns = 0;              // when that pose was taken, on CLOCK_MONOTONIC (TrackerClock)
  std::uint64_t poses = 0;                // usable poses received
  FingerVent refused = FingerVent::none;  // the last pose was unusable (tool_invalid, tool_no_rotation)
  Vec3_mm tip_scene_mm{};                 // its fingertip in scene space (mm)
};

// The tracker as the window shows it (one thread besides the loop, the window's poll, copies it
// through IgtlInput::status()).
struct TrackerStatus {
  bool connected = false;
  std::int64_t heartbeat_ns = 0;  // the reader's last wake
  std::int64_t last_message_ns = 0;
  std::uint64_t messages = 0, skipped = 0;
  std::array<TrackedToolState, kFingerCount> tools{};  // indexed as TrackingConfig::tools
  // Device names the tracker sends that the tracking file does not map (the first few).
  static constexpr int kOtherNames = 4;
  char other_names[kOtherNames][21] = {};
};

class IgtlInput final : public InputSource {
 public:
  // Connects (throws InputError with the reason: refused, no such host) and starts the reader.
  // max_pose_age_s: a tool with no pose for longer is vented (the rig's max_input_age_s).
  IgtlInput(const IgtlEndpoint& endpoint, TrackingConfig tracking, double max_pose_age_s);
  ~IgtlInput() override;

  TouchSample latest(double t_s) noexcept override;
  double duration_s() const noexcept override { return 0; }  // live
  std::string describe() const override;
  // The reader's newest status. One reader thread (the window's poll) besides the loop.
  TrackerStatus status() noexcept { return status_.latest(); }
  const TrackingConfig& tracking() const noexcept { return tracking_; }
  // A new run starts its clock at 0 again (the window restarts its loop after a fault): the
  // next latest() fixes loop time 0. The reader goes on; a tracker that has gone stays gone
  // (its heartbeat has stopped), so the new run vents at once.
  void restart_clock() noexcept;
  const IgtlEndpoint& endpoint() const noexcept { return endpoint_; }

 private:
  void reader_main() noexcept;

  IgtlEndpoint endpoint_;
  TrackingConfig tracking_;
  std::int64_t max_pose_age_ns_;
  std::unique_ptr<IgtlPoseReader> reader_socket_;
  LatestValue<TrackerStatus> for_loop_, status_;
  std::atomic<bool> stop_{false};
  std::atomic<std::int64_t> epoch_ns_{0};  // loop time 0 on CLOCK_MONOTONIC, fixed at the first latest()
  std::thread reader_;
};

}  // namespace palprig
