#pragma once
// IgtlPoseReader: a client of a tracker's OpenIGTLink server (igtl::ClientSocket) and the poses
// it receives, decoded by IgtlStreamDecoder. poll() waits at most a timeout for bytes and
// returns the poses they completed; it never loses a partial message to a timeout. The
// loop's tracker input (IgtlInput) polls it on its reader thread; the registration and tip
// calibration commands poll it directly.
#include <memory>
#include <string>
#include <vector>

#include "inputs/igtl_stream.hpp"

namespace palprig {

class IgtlPoseReader {
 public:
  enum class Status { ok, closed, failed };

  // Connects to host:port. Throws InputError naming `what` (e.g. "input igtl:HOST:PORT") with
  // the reason when no server answers.
  IgtlPoseReader(const std::string& host, int port, const std::string& what);
  ~IgtlPoseReader();
  IgtlPoseReader(const IgtlPoseReader&) = delete;
  IgtlPoseReader& operator=(const IgtlPoseReader&) = delete;

  // Waits up to timeout_ms for data; appends the poses it completed. closed: the server closed
  // the connection; failed: a socket error or a stream that is not OpenIGTLink (why() says).
  Status poll(std::vector<DecodedPose>& poses, int timeout_ms);
  const char* why() const noexcept { return why_; }
  const IgtlStreamCounts& counts() const noexcept { return decoder_.counts(); }

 private:
  struct Client;
  std::unique_ptr<Client> client_;
  IgtlStreamDecoder decoder_;
  std::vector<std::uint8_t> buffer_;
  int timeout_ms_ = -1;
  char why_[200] = {0};
};

}  // namespace palprig
