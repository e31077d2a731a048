#include "inputs/igtl_input.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "formats/modbus_register_map.hpp"
#include "inputs/igtl_pose_reader.hpp"
#include "core/input_error.hpp"
#include "inputs/tracker_clock.hpp"
#include "runtime/monotonic_clock.hpp"
#include "runtime/realtime.hpp"
#include "runtime/worker_fault.hpp"

namespace palprig {

namespace {

constexpr int kIgtlHeartbeatMs = 10;
const char* const kSpecForm = "igtl:HOST:PORT (an OpenIGTLink server: PlusServer, 3D Slicer, palprig igtl-replay)";

}  // namespace

bool is_igtl_input(const std::string& spec) { return spec.rfind("igtl:", 0) == 0; }

IgtlEndpoint parse_igtl_spec(const std::string& spec) {
  if (!is_igtl_input(spec)) throw InputError("input", spec, kSpecForm);
  const std::string rest = spec.substr(5);
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0) throw InputError("input", spec, kSpecForm);
  IgtlEndpoint e;
  e.host = rest.substr(0, colon);
  const std::string port = rest.substr(colon + 1);
  if (const std::string why = modbus_host_refusal(e.host); !why.empty())
    throw InputError("input", spec, kSpecForm + std::string(": ") + why);
  char* end = nullptr;
  const long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || p < 1 || p > 65535)
    throw InputError("input", spec, std::string(kSpecForm) + " with a port 1..65535, got '" + port + "'");
  e.port = static_cast<int>(p);
  return e;
}

IgtlInput::IgtlInput(const IgtlEndpoint& endpoint, TrackingConfig tracking, double max_pose_age_s)
    : endpoint_(endpoint),
      tracking_(std::move(tracking)),
      max_pose_age_ns_(static_cast<std::int64_t>(std::llround(max_pose_age_s * 1e9))),
      reader_socket_(std::make_unique<IgtlPoseReader>(endpoint_.host, endpoint_.port, "input igtl")) {
  TrackerStatus first;
  first.connected = true;
  first.heartbeat_ns = mono_ns();
  for_loop_.publish(first);
  status_.publish(first);
  reader_ = std::thread([this] { reader_main(); });
}

IgtlInput::~IgtlInput() {
  stop_.store(true, std::memory_order_release);
  if (reader_.joinable()) reader_.join();
}

std::string IgtlInput::describe() const {
  std::string tools;
  for (const auto& t : tracking_.tools) tools += (tools.empty() ? "" : ", ") + t.name;
  return "tracker igtl:" + endpoint_.text() + " (" + tools + ")";
}

void IgtlInput::reader_main() noexcept {
  const std::string who = "tracker igtl:" + endpoint_.text();
  try {
    // Below the loop (runtime/thread_priorities.hpp). Refused quietly when the system does not
    // permit it: the loop's own note says so once.
    (void)set_thread_fifo(tracking_.reader_fifo_priority);
    std::vector<DecodedPose> poses;
    poses.reserve(256);
    TrackerStatus st;
    st.connected = true;
    int other_names = 0;
    std::array<TrackerClock, kFingerCount> clocks{};  // per tool: each tool's stamps must behave like a clock
    while (!stop_.load(std::memory_order_acquire)) {
      poses.clear();
      const IgtlPoseReader::Status got = reader_socket_->poll(poses, kIgtlHeartbeatMs);
      const std::int64_t now = mono_ns();
      if (got != IgtlPoseReader::Status::ok) {
        st.connected = false;
        st.heartbeat_ns = now;
        status_.publish(st);
        // The heartbeat stops too, so even a loop that missed the report vents on input age.
        char why[240];
        std::snprintf(why, sizeof why, "%s; every finger vented",
                      got == IgtlPoseReader::Status::closed ? "the server closed the connection (the tracker stopped)"
                                                            : reader_socket_->why());
        report_worker_fault(who.c_str(), why);
        return;
      }
      if (!poses.empty()) {
        st.last_message_ns = now;
        for (const DecodedPose& p : poses) {
          bool mapped = false;
          for (std::size_t k = 0; k < tracking_.tools.size() && k < st.tools.size(); ++k) {
            const TrackedTool& tool = tracking_.tools[k];
            if (tool.name != p.device) continue;
            mapped = true;
            TrackedToolState& ts = st.tools[k];
            const bool offset = tool.tip.offset_mm[0] != 0 || tool.tip.offset_mm[1] != 0 || tool.tip.offset_mm[2] != 0;
            if (!p.is_rotation) {
              ts.refused = FingerVent::tool_invalid;
            } else if (!p.has_rotation && offset) {
              ts.refused = FingerVent::tool_no_rotation;
            } else {
              // Paper 003 eq. 1, then tracker -> scene.
              ts.tip_scene_mm = tracking_.registration.tracker_to_scene.apply(p.pose.apply(tool.tip.offset_mm));
              ts.refused = FingerVent::none;
              ts.arrived_ns = now;
              ts.taken_ns =
                  static_cast<std::int64_t>(std::llround(clocks[k].taken_at(p.stamp_s, double(now) * 1e-9) * 1e9));
              ++ts.poses;
            }
          }
          if (!mapped && other_names < TrackerStatus::kOtherNames) {
            bool known = false;
            for (int i = 0; i < other_names; ++i) known = known || std::strcmp(st.other_names[i], p.device) == 0;
            if (!known) std::snprintf(st.other_names[other_names++], sizeof st.other_names[0], "%s", p.device);
          }
        }
        const IgtlStreamCounts& c = reader_socket_->counts();
        st.messages = c.messages;
        st.skipped = c.other_types + c.other_versions + c.crc_failures + c.malformed;
      }
      st.heartbeat_ns = now;
      for_loop_.publish(st);
      status_.publish(st);
    }
  } catch (const std::exception& e) {
    report_worker_fault(who.c_str(), e.what());
  } catch (...) {
    report_worker_fault(who.c_str(), "unknown exception");
  }
}

void IgtlInput::restart_clock() noexcept { epoch_ns_.store(0, std::memory_order_relaxed); }

TouchSample IgtlInput::latest(double t_s) noexcept {
  const std::int64_t now = mono_ns();
  std::int64_t epoch = epoch_ns_.load(std::memory_order_relaxed);
  if (epoch == 0) {
    epoch = now - static_cast<std::int64_t>(std::llround(t_s * 1e9));
    epoch_ns_.store(epoch, std::memory_order_relaxed);
  }
  const TrackerStatus& st = for_loop_.latest();
  TouchSample s;
  s.t_s = std::min(t_s, double(st.heartbeat_ns - epoch) * 1e-9);
  s.force_from_load_cells = true;
  s.own_positions = tracking_.placement == TrackedPlacement::per_finger;
  auto vent_of = [&](std::size_t k) noexcept {
    const TrackedToolState& ts = st.tools[k];
    if (ts.refused != FingerVent::none) return ts.refused;
    if (ts.arrived_ns == 0) return FingerVent::tool_not_seen;
    if (now - ts.arrived_ns > max_pose_age_ns_) return FingerVent::tool_stale;
    return FingerVent::none;
  };
  // A vented finger keeps the position its tool was last seen at (the window draws it there,
  // hollow); the tick does not use it. A tool never seen has none: (0, 0).
  bool placed_any = false;
  if (!s.own_positions) {
    const FingerVent v = tracking_.tools.empty() ? FingerVent::no_tool : vent_of(0);
    const Vec3_mm& p = st.tools[0].tip_scene_mm;
    s.x_mm = p[0];
    s.y_mm = p[1];
    placed_any = v == FingerVent::none;
    for (FingerTouch& f : s.fingers) {
      f.vent = v;
      f.z_mm = placed_any ? p[2] : 0.0;
    }
  } else {
    bool pen_set = false;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      FingerTouch& f = s.fingers[i];
      f.vent = FingerVent::no_tool;
      for (std::size_t k = 0; k < tracking_.tools.size() && k < kFingerCount; ++k) {
        if (tracking_.tools[k].finger != static_cast<int>(i)) continue;
        f.vent = vent_of(k);
        const Vec3_mm& p = st.tools[k].tip_scene_mm;
        f.x_mm = p[0];
        f.y_mm = p[1];
        f.z_mm = f.vent == FingerVent::none ? p[2] : 0.0;
        if (st.tools[k].taken_ns != 0) f.pose_t_s = double(st.tools[k].taken_ns - epoch) * 1e-9;
        if (f.vent == FingerVent::none) {
          if (!pen_set) {
            // The sample's own x, y (the "pen" of telemetry): the first placed finger.
            s.x_mm = p[0];
            s.y_mm = p[1];
            pen_set = true;
          }
          placed_any = true;
        }
      }
    }
  }
  s.in_contact = placed_any;  // whether a finger presses is the load cells' to say
  return s;
}

}  // namespace palprig
