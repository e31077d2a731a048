#pragma once
// IgtlPoseServer: a tracker's OpenIGTLink server made from a recorded path (inputs/pose_recording.hpp),
// built on libopenigtlink's igtl::ServerSocket and igtl::TransformMessage like the library's
// Tracker server example: each client that connects gets the recording from its start, in
// real time, as TRANSFORM messages named by tool (or POSITION messages: position and
// quaternion), the way PlusServer streams an NDI Aurora's "StylusToTracker". After the last row
// the connection stays open and silent (a tracker that stopped sending), or the recording starts
// over (loop). `palprig igtl-replay` wraps it; the tests and the latency benchmark run it.
//
// It listens on every interface, as PlusServer does (igtl::ServerSocket binds INADDR_ANY).
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "inputs/pose_recording.hpp"

namespace palprig {

struct PoseServerOptions {
  int port = 18944;                // 0: a free port (see port())
  bool position_messages = false;  // POSITION instead of TRANSFORM
  bool loop = false;               // start the recording over at its end
};

class IgtlPoseServer {
 public:
  using LogSink = std::function<void(const std::string&)>;

  IgtlPoseServer(std::vector<RecordedPose> poses, PoseServerOptions options);
  ~IgtlPoseServer();
  IgtlPoseServer(const IgtlPoseServer&) = delete;
  IgtlPoseServer& operator=(const IgtlPoseServer&) = delete;

  // Where connections and departures are told (called on the server's threads). Default: none.
  void set_log_sink(LogSink sink) { log_ = std::move(sink); }
  // Keep the CLOCK_MONOTONIC time each row was sent (the latency benchmark); before start().
  void record_sends(bool on) { record_ = on; }

  // Listens and starts accepting. Throws Error naming the port when it cannot.
  void start();
  void stop() noexcept;
  int port() const noexcept { return port_; }
  int clients() const noexcept { return clients_.load(std::memory_order_relaxed); }
  std::uint64_t sent() const noexcept { return sent_.load(std::memory_order_relaxed); }
  double duration_s() const noexcept { return poses_.empty() ? 0 : poses_.back().t_s; }
  // (row, mono_ns sent) of every row sent so far, with record_sends(true).
  std::vector<std::pair<std::size_t, std::int64_t>> sends() const;

 private:
  struct Listener;
  void accept_main() noexcept;
  void serve(void* client) noexcept;  // an igtl::ClientSocket* held by the serving thread
  void log(const std::string& line);

  std::vector<RecordedPose> poses_;
  PoseServerOptions options_;
  LogSink log_;
  bool record_ = false;
  std::unique_ptr<Listener> listener_;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<int> clients_{0};
  std::atomic<std::uint64_t> sent_{0};
  std::thread acceptor_;
  mutable std::mutex mutex_;  // guards servers_ and sends_ (server threads only: never the loop)
  std::vector<std::thread> servers_;
  std::vector<std::pair<std::size_t, std::int64_t>> sends_;
};

}  // namespace palprig
