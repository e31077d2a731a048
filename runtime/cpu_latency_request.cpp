#include "runtime/cpu_latency_request.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <utility>

namespace palprig {

CpuLatencyRequest::CpuLatencyRequest(int max_latency_us, const std::string& path) noexcept {
  try {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) {
      note_ = "PM QoS request not held: cannot open " + path + " (" + std::strerror(errno) +
              "); the CPU may enter deep idle between ticks (run as root or give the user write access to it)";
      return;
    }
    // The kernel reads a binary 32-bit value (or an ASCII hex string); binary is what
    // cyclictest writes.
    const std::int32_t value = max_latency_us;
    if (::write(fd_, &value, sizeof value) != static_cast<ssize_t>(sizeof value)) {
      note_ = "PM QoS request not held: writing " + path + " failed (" + std::strerror(errno) + ")";
      ::close(fd_);
      fd_ = -1;
    }
  } catch (...) {  // std::string allocation; the request is an optimisation, never a reason to stop
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
}

CpuLatencyRequest::~CpuLatencyRequest() { release(); }

CpuLatencyRequest::CpuLatencyRequest(CpuLatencyRequest&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), note_(std::move(other.note_)) {}

CpuLatencyRequest& CpuLatencyRequest::operator=(CpuLatencyRequest&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = std::exchange(other.fd_, -1);
    note_ = std::move(other.note_);
  }
  return *this;
}

void CpuLatencyRequest::release() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

}  // namespace palprig
