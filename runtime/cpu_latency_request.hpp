#pragma once
// CpuLatencyRequest: a PM QoS request that keeps every CPU out of deep idle states while a
// real-time loop runs, the way cyclictest does. Writing a 32-bit 0 to /dev/cpu_dma_latency
// asks for 0 us exit latency; the kernel honours it while the file stays open and drops it
// when the descriptor is closed (also when the process dies), so the request is an RAII object
// held for exactly as long as the loop runs.
//
// Why: waking a CPU from a deep C-state costs hundreds of microseconds on a lab PC and
// milliseconds on a virtual machine; with the request held the loop's p99 wake-up latency
// fell from 1.3-2.9 ms to 52-58 us on the development machine (docs/rig.md, real-time loop).
#include <string>

namespace palprig {

inline constexpr const char* kCpuDmaLatencyPath = "/dev/cpu_dma_latency";

class CpuLatencyRequest {
 public:
  CpuLatencyRequest() = default;  // holds nothing
  // Opens `path` and writes `max_latency_us` as a 32-bit value. Never throws: when the device
  // is missing or not writable, held() is false and note() says why in one line.
  explicit CpuLatencyRequest(int max_latency_us, const std::string& path = kCpuDmaLatencyPath) noexcept;
  ~CpuLatencyRequest();
  CpuLatencyRequest(CpuLatencyRequest&& other) noexcept;
  CpuLatencyRequest& operator=(CpuLatencyRequest&& other) noexcept;
  CpuLatencyRequest(const CpuLatencyRequest&) = delete;
  CpuLatencyRequest& operator=(const CpuLatencyRequest&) = delete;

  bool held() const noexcept { return fd_ >= 0; }
  const std::string& note() const noexcept { return note_; }
  void release() noexcept;  // closes the file: the kernel drops the request

 private:
  int fd_ = -1;
  std::string note_;
};

}  // namespace palprig
