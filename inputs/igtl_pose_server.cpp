#include "inputs/igtl_pose_server.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <igtlOSUtil.h>
#include <igtlPositionMessage.h>
#include <igtlServerSocket.h>
#include <igtlTimeStamp.h>
#include <igtlTransformMessage.h>

#include "core/error.hpp"
#include "runtime/monotonic_clock.hpp"

namespace palprig {

struct IgtlPoseServer::Listener {
  igtl::ServerSocket::Pointer socket = igtl::ServerSocket::New();
};

IgtlPoseServer::IgtlPoseServer(std::vector<RecordedPose> poses, PoseServerOptions options)
    : poses_(std::move(poses)), options_(options), listener_(std::make_unique<Listener>()) {}

IgtlPoseServer::~IgtlPoseServer() { stop(); }

void IgtlPoseServer::log(const std::string& line) {
  if (log_) log_(line);
}

void IgtlPoseServer::start() {
  errno = 0;
  if (listener_->socket->CreateServer(options_.port) != 0) {
    const int error = errno;
    throw Error("cannot listen on port " + std::to_string(options_.port) +
                (error ? std::string(": ") + std::strerror(error) : std::string()));
  }
  port_ = listener_->socket->GetServerPort();
  if (record_) sends_.reserve(poses_.size() * 2);
  acceptor_ = std::thread([this] { accept_main(); });
}

void IgtlPoseServer::stop() noexcept {
  stop_.store(true, std::memory_order_release);
  if (acceptor_.joinable()) acceptor_.join();
  std::vector<std::thread> servers;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    servers.swap(servers_);
  }
  for (auto& t : servers)
    if (t.joinable()) t.join();
  listener_->socket->CloseSocket();
}

std::vector<std::pair<std::size_t, std::int64_t>> IgtlPoseServer::sends() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return sends_;
}

void IgtlPoseServer::accept_main() noexcept {
  while (!stop_.load(std::memory_order_acquire)) {
    igtl::ClientSocket::Pointer client = listener_->socket->WaitForConnection(100);
    if (client.IsNull()) continue;
    char text[160];
    std::snprintf(text, sizeof text, "a client connected; replaying %zu poses over %.2f s", poses_.size(),
                  duration_s());
    log(text);
    clients_.fetch_add(1, std::memory_order_relaxed);
    // The thread owns a reference to the socket (released when it ends).
    client->Register();
    igtl::ClientSocket* raw = client.GetPointer();
    std::lock_guard<std::mutex> lock(mutex_);
    servers_.emplace_back([this, raw] { serve(raw); });
  }
}

void IgtlPoseServer::serve(void* raw_client) noexcept {
  igtl::ClientSocket::Pointer client = static_cast<igtl::ClientSocket*>(raw_client);
  client->UnRegister();  // the smart pointer above holds it now
  igtl::TransformMessage::Pointer transform = igtl::TransformMessage::New();
  igtl::PositionMessage::Pointer position = igtl::PositionMessage::New();
  position->SetPackType(igtl::PositionMessage::ALL);
  igtl::TimeStamp::Pointer stamp = igtl::TimeStamp::New();
  std::int64_t start_ns = mono_ns();
  // Each pose is stamped with the time it was taken in the recording (the header's timestamp is
  // the acquisition time), on the wall clock from this client's start: a client that reads late
  // and in a burst still sees the recording's spacing, as it would a tracker's.
  const std::int64_t first_start_ns = start_ns;
  stamp->GetTime();
  const double wall_start_s = stamp->GetTimeStamp();
  const std::int64_t period_ns = static_cast<std::int64_t>((duration_s() + 0.02) * 1e9);
  bool gone = false;
  while (!stop_.load(std::memory_order_acquire) && !gone) {
    for (std::size_t i = 0; i < poses_.size() && !gone; ++i) {
      const RecordedPose& row = poses_[i];
      const std::int64_t due = start_ns + static_cast<std::int64_t>(row.t_s * 1e9);
      // Sleep in steps so stop() is never kept waiting by a long gap in the recording.
      while (mono_ns() < due && !stop_.load(std::memory_order_acquire))
        sleep_until_ns(std::min(due, mono_ns() + 50'000'000));
      if (stop_.load(std::memory_order_acquire)) break;
      stamp->SetTime(wall_start_s + static_cast<double>(due - first_start_ns) * 1e-9);
      igtl::MessageBase* msg = nullptr;
      if (options_.position_messages) {
        // Rotation matrix -> quaternion (x, y, z, w), as the library converts it.
        const Rotation3& r = row.pose.rotation;
        float q[4];
        igtl::Matrix4x4 m;
        igtl::IdentityMatrix(m);
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) m[a][b] = static_cast<float>(r[a][b]);
        igtl::MatrixToQuaternion(m, q);
        position->SetDeviceName(row.tool.c_str());
        position->SetPosition(float(row.pose.translation_mm[0]), float(row.pose.translation_mm[1]),
                              float(row.pose.translation_mm[2]));
        position->SetQuaternion(q);
        position->SetTimeStamp(stamp);
        position->Pack();
        msg = position.GetPointer();
      } else {
        igtl::Matrix4x4 m;
        igtl::IdentityMatrix(m);
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) m[a][b] = static_cast<float>(row.pose.rotation[a][b]);
          m[a][3] = static_cast<float>(row.pose.translation_mm[a]);
        }
        transform->SetDeviceName(row.tool.c_str());
        transform->SetMatrix(m);
        transform->SetTimeStamp(stamp);
        transform->Pack();
        msg = transform.GetPointer();
      }
      if (client->Send(msg->GetPackPointer(), msg->GetPackSize()) != 1) {
        gone = true;
        break;
      }
      const std::int64_t sent_at = mono_ns();
      sent_.fetch_add(1, std::memory_order_relaxed);
      if (record_) {
        std::lock_guard<std::mutex> lock(mutex_);
        sends_.emplace_back(i, sent_at);
      }
    }
    if (gone || !options_.loop) break;
    start_ns += period_ns;
  }
  // The end of the recording: stay connected and silent (a tracker that stopped sending) until
  // the server stops or the client leaves.
  while (!gone && !stop_.load(std::memory_order_acquire)) {
    char byte;
    client->SetReceiveTimeout(100);
    const int n = client->Receive(&byte, 1, 0);
    if (n == 0) gone = true;
  }
  client->CloseSocket();
  clients_.fetch_sub(1, std::memory_order_relaxed);
  log(gone ? "the client left" : "stopping");
}

}  // namespace palprig
