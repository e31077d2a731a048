#include "inputs/igtl_stream.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include <igtlMessageHeader.h>
#include <igtlPositionMessage.h>
#include <igtlTransformMessage.h>
#include <igtl_header.h>

namespace palprig {

struct IgtlStreamDecoder::Messages {
  igtl::MessageHeader::Pointer header = igtl::MessageHeader::New();
  igtl::TransformMessage::Pointer transform = igtl::TransformMessage::New();
  igtl::PositionMessage::Pointer position = igtl::PositionMessage::New();
};

IgtlStreamDecoder::IgtlStreamDecoder() : msg_(new Messages) { pending_.reserve(std::size_t{64} * 1024); }
IgtlStreamDecoder::~IgtlStreamDecoder() { delete msg_; }

namespace {

std::uint64_t big_endian(const std::uint8_t* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

bool IgtlStreamDecoder::feed(const std::uint8_t* data, std::size_t n, std::vector<DecodedPose>& poses) {
  if (error_[0]) return false;
  std::size_t at = 0;
  while (at < n) {
    if (skip_ > 0) {
      const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(skip_, n - at));
      skip_ -= k;
      at += k;
      continue;
    }
    // Gather a header, then (for a message we read) its body.
    const std::size_t have = pending_.size();
    std::size_t need = IGTL_HEADER_SIZE;
    if (have >= IGTL_HEADER_SIZE) need += static_cast<std::size_t>(big_endian(pending_.data() + 42, 8));
    const std::size_t k = std::min(need - have, n - at);
    pending_.insert(pending_.end(), data + at, data + at + k);
    at += k;
    if (pending_.size() < IGTL_HEADER_SIZE) continue;
    const std::uint8_t* h = pending_.data();
    const std::uint64_t body = big_endian(h + 42, 8);
    if (pending_.size() == IGTL_HEADER_SIZE) {
      if (body > kMaxIgtlBodyBytes) {
        char type[13] = {0};
        std::memcpy(type, h + 2, 12);
        for (char& c : type)
          if (c && (c < 0x20 || c > 0x7e)) c = '?';
        std::snprintf(error_, sizeof error_,
                      "not an OpenIGTLink stream (a message of type '%s' announces a %llu-byte body)", type,
                      static_cast<unsigned long long>(body));
        return false;
      }
      const bool version_1 = big_endian(h, 2) == IGTL_HEADER_VERSION;
      const bool transform = std::memcmp(h + 2, "TRANSFORM\0", 10) == 0;
      const bool position = std::memcmp(h + 2, "POSITION\0", 9) == 0;
      // libopenigtlink 1.11 unpacks a TRANSFORM as 48 bytes and a POSITION of any other size
      // than 12, 24 or 28 bytes as 28, whatever the body holds: a body of another size would be
      // read (and byte-swapped in place) past its end. Such a message is malformed: skipped.
      const bool well_sized = (transform && body == 48) || (position && (body == 12 || body == 24 || body == 28));
      if (!version_1 || !well_sized) {
        // Not kept: skip its body as it streams past.
        ++counts_.messages;
        if (!version_1)
          ++counts_.other_versions;
        else if (transform || position)
          ++counts_.malformed;
        else
          ++counts_.other_types;
        skip_ = body;
        pending_.clear();
        continue;
      }
    }
    if (pending_.size() < IGTL_HEADER_SIZE + body) continue;
    ++counts_.messages;
    decode(h, h + IGTL_HEADER_SIZE, static_cast<std::size_t>(body), poses);
    pending_.clear();
  }
  return true;
}

void IgtlStreamDecoder::decode(const std::uint8_t* header, const std::uint8_t* body, std::size_t body_size,
                               std::vector<DecodedPose>& poses) {
  igtl::MessageHeader::Pointer& mh = msg_->header;
  mh->InitPack();
  std::memcpy(mh->GetPackPointer(), header, IGTL_HEADER_SIZE);
  mh->Unpack();
  DecodedPose out;
  std::snprintf(out.device, sizeof out.device, "%s", mh->GetDeviceName());
  unsigned int stamp_sec = 0, stamp_frac = 0;  // the fraction in units of 2^-32 s, as the header carries it
  mh->GetTimeStamp(&stamp_sec, &stamp_frac);
  out.stamp_s = double(stamp_sec) + double(stamp_frac) / 4294967296.0;
  if (std::strcmp(mh->GetDeviceType(), "TRANSFORM") == 0) {
    igtl::TransformMessage::Pointer& m = msg_->transform;
    m->SetMessageHeader(mh);
    m->AllocatePack();
    if (static_cast<std::size_t>(m->GetPackBodySize()) != body_size) {  // checked in feed(); kept as a guard
      ++counts_.malformed;
      return;
    }
    std::memcpy(m->GetPackBodyPointer(), body, body_size);
    if (!(m->Unpack(1) & igtl::MessageHeader::UNPACK_BODY)) {
      ++counts_.crc_failures;
      return;
    }
    igtl::Matrix4x4 mat;
    m->GetMatrix(mat);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) out.pose.rotation[r][c] = mat[r][c];
      out.pose.translation_mm[r] = mat[r][3];
    }
  } else {
    igtl::PositionMessage::Pointer& m = msg_->position;
    m->SetMessageHeader(mh);
    m->AllocatePack();
    if (static_cast<std::size_t>(m->GetPackBodySize()) != body_size) {  // checked in feed(); kept as a guard
      ++counts_.malformed;
      return;
    }
    std::memcpy(m->GetPackBodyPointer(), body, body_size);
    if (!(m->Unpack(1) & igtl::MessageHeader::UNPACK_BODY)) {
      ++counts_.crc_failures;
      return;
    }
    float p[3], q[4];
    m->GetPosition(p);
    m->GetQuaternion(q);
    out.has_rotation = m->GetPackType() != igtl::PositionMessage::POSITION_ONLY;
    if (!rotation_from_quaternion(q[0], q[1], q[2], q[3], out.pose.rotation)) out.is_rotation = false;
    for (int r = 0; r < 3; ++r) out.pose.translation_mm[r] = p[r];
  }
  // float32 on the wire: 1e-3 is far above its rounding, far below any real scale or shear.
  out.is_rotation = out.is_rotation && is_rotation(out.pose.rotation, 1e-3) &&
                    std::isfinite(out.pose.translation_mm[0]) && std::isfinite(out.pose.translation_mm[1]) &&
                    std::isfinite(out.pose.translation_mm[2]);
  ++counts_.poses;
  poses.push_back(out);
}

}  // namespace palprig
