#include "inputs/igtl_pose_reader.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include <igtlClientSocket.h>

#include "core/input_error.hpp"

namespace palprig {

struct IgtlPoseReader::Client {
  igtl::ClientSocket::Pointer socket = igtl::ClientSocket::New();
};

namespace {

// Why a TCP connection to host:port fails, in the system's words. libopenigtlink's
// ConnectToServer loses the reason (it closes the socket before returning, and errno is then
// the close's), so after it failed the connection is tried once more here, plainly.
std::string connect_failure(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_INET;  // the library connects over IPv4
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int rc = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
  if (rc != 0 || !found) return std::string("no IPv4 address for ") + host + " (" + gai_strerror(rc) + ")";
  std::string why = "the server closed at once";
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd >= 0) {
    if (::connect(fd, found->ai_addr, found->ai_addrlen) != 0) why = std::strerror(errno);
    ::close(fd);
  }
  freeaddrinfo(found);
  return why;
}

}  // namespace

IgtlPoseReader::IgtlPoseReader(const std::string& host, int port, const std::string& what)
    : client_(std::make_unique<Client>()), buffer_(std::size_t{16} * 1024) {
  // The library prints its failure to std::cerr in four lines of its own; palprig says it in one.
  std::ostringstream library_says;
  std::streambuf* cerr_buffer = std::cerr.rdbuf(library_says.rdbuf());
  const int rc = client_->socket->ConnectToServer(host.c_str(), port);
  std::cerr.rdbuf(cerr_buffer);
  if (rc != 0)
    throw InputError(what, host + ":" + std::to_string(port),
                     "a running OpenIGTLink server (PlusServer, 3D Slicer, palprig igtl-replay); cannot connect: " +
                         connect_failure(host, port));
}

IgtlPoseReader::~IgtlPoseReader() { client_->socket->CloseSocket(); }

IgtlPoseReader::Status IgtlPoseReader::poll(std::vector<DecodedPose>& poses, int timeout_ms) {
  if (timeout_ms < 1) timeout_ms = 1;
  if (timeout_ms != timeout_ms_) {
    // Reads are never "fully" (the library's readFully is ignored under a timeout, and a timeout
    // inside a message would lose the part read): the decoder gathers messages itself.
    // (libopenigtlink 1.11's SetReceiveTimeout saves the old timeout with getsockopt and an
    // uninitialised length, which valgrind reports; Linux writes at most a timeval there, the
    // size of the field it names, and the saved value is never restored by palprig.)
    client_->socket->SetReceiveTimeout(timeout_ms);
    timeout_ms_ = timeout_ms;
  }
  errno = 0;
  const int n = client_->socket->Receive(buffer_.data(), static_cast<int>(buffer_.size()), 0);
  if (n == 0) {
    std::snprintf(why_, sizeof why_, "the server closed the connection");
    return Status::closed;
  }
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return Status::ok;  // nothing came in time
    std::snprintf(why_, sizeof why_, "connection lost (%s)", std::strerror(errno));
    return Status::failed;
  }
  if (!decoder_.feed(buffer_.data(), static_cast<std::size_t>(n), poses)) {
    std::snprintf(why_, sizeof why_, "%s", decoder_.error());
    return Status::failed;
  }
  return Status::ok;
}

}  // namespace palprig
