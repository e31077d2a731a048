#pragma once
// IgtlStreamDecoder: the tracker's byte stream (OpenIGTLink over TCP) cut into messages, and the
// poses in them. A TCP read may end anywhere inside a message, so bytes are kept until a whole
// header (58 bytes) and then its whole body have arrived; libopenigtlink then unpacks and
// CRC-checks each message (igtl::MessageHeader, igtl::TransformMessage, igtl::PositionMessage).
//
// TRANSFORM and POSITION give a pose (POSITION may carry no orientation); every other message
// type (STATUS, IMAGE, STRING, ...) is skipped by its body size without being kept, and so is
// a TRANSFORM or POSITION whose body has not the size its type has (which the library would
// read past its end). Messages
// with a header version other than 1 (OpenIGTLink 3's extended header, which Debian's
// libopenigtlink 1.11 does not read) and messages whose CRC fails are skipped and counted.
// A body size beyond kMaxIgtlBodyBytes means the stream is not OpenIGTLink: error() says so.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "models/rigid_transform.hpp"

namespace palprig {

inline constexpr std::uint64_t kMaxIgtlBodyBytes = 256ull << 20;

struct DecodedPose {
  char device[21] = {0};     // the device (tool) name, NUL-terminated
  RigidTransform pose;       // tool -> tracker, as the message carried it
  bool has_rotation = true;  // false: POSITION without a quaternion
  bool is_rotation = true;   // the rotation part is a proper rotation (a lost tool sends zeros)
  // The header's timestamp in seconds (by the OpenIGTLink spec the time the data was acquired;
  // PlusServer and `palprig igtl-replay` set it), 0 when the sender set none.
  double stamp_s = 0;
};

struct IgtlStreamCounts {
  std::uint64_t messages = 0;        // whole messages seen, of any type
  std::uint64_t poses = 0;           // TRANSFORM and POSITION decoded
  std::uint64_t other_types = 0;     // skipped: not a pose
  std::uint64_t other_versions = 0;  // skipped: header version other than 1
  std::uint64_t crc_failures = 0;    // skipped: the body's CRC did not match
  std::uint64_t malformed = 0;       // skipped: a TRANSFORM or POSITION whose body has the wrong size
};

class IgtlStreamDecoder {
 public:
  IgtlStreamDecoder();
  ~IgtlStreamDecoder();
  IgtlStreamDecoder(const IgtlStreamDecoder&) = delete;
  IgtlStreamDecoder& operator=(const IgtlStreamDecoder&) = delete;

  // Takes n bytes of the stream; appends the poses of every message they complete to `poses`.
  // False once the stream is found corrupt (error() says why); nothing is decoded after that.
  bool feed(const std::uint8_t* data, std::size_t n, std::vector<DecodedPose>& poses);
  const char* error() const noexcept { return error_; }
  const IgtlStreamCounts& counts() const noexcept { return counts_; }

 private:
  struct Messages;  // the library's message objects, made once and reused
  void decode(const std::uint8_t* header, const std::uint8_t* body, std::size_t body_size,
              std::vector<DecodedPose>& poses);

  Messages* msg_;
  std::vector<std::uint8_t> pending_;  // bytes of an incomplete message
  std::uint64_t skip_ = 0;             // bytes of a skipped body still to come
  IgtlStreamCounts counts_;
  char error_[160] = {0};
};

}  // namespace palprig
