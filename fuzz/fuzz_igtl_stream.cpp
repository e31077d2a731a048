// What a tracker's server may send: any bytes, cut into reads at the positions the
// input's first byte picks, through the OpenIGTLink stream decoder (libopenigtlink unpacks and
// CRC-checks each message). A stream that is not OpenIGTLink is refused (feed() false); nothing
// may crash, read out of bounds or hang.
#include <cstdint>
#include <vector>

#include "inputs/igtl_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + data[0] % 97;
  palprig::IgtlStreamDecoder decoder;
  std::vector<palprig::DecodedPose> poses;
  for (std::size_t at = 1; at < size; at += chunk) {
    const std::size_t n = std::min(chunk, size - at);
    if (!decoder.feed(data + at, n, poses)) break;
    if (poses.size() > 4096) poses.clear();
  }
  return 0;
}
