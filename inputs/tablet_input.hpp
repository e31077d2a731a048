#pragma once
// TabletInput: the pen tablet as the loop's input source. A reader thread waits on the device
// (or replays a recording), decodes events with TabletDecoder and publishes the newest frame
// with a heartbeat through a wait-free LatestValue; latest() only reads it.
//
// Sample age: evdev only reports changes, so a pen held still, or lifted out of proximity,
// sends nothing, and that is not stale. The reader wakes at least every 10 ms, and each wake
// is a heartbeat: the sample's time is the last heartbeat, on the loop's clock. If the reader
// stalls or its device goes away, the heartbeat stops, the sample ages, and the tick's
// max_input_age_s check vents and stops the loop (input_stale). A device that disappears is
// also reported as a worker fault with the reason; an exception on the reader thread likewise.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "inputs/input_source.hpp"
#include "runtime/latest_value.hpp"
#include "formats/tablet_config.hpp"
#include "inputs/tablet_decoder.hpp"
#include "inputs/tablet_source.hpp"

namespace palprig {

class TabletInput final : public InputSource {
 public:
  // Starts the reader thread at once. Throws BadInput (axes the config cannot
  // convert) before starting it.
  TabletInput(std::unique_ptr<PenEventSource> source, const TabletConfig& config);
  ~TabletInput() override;

  TouchSample latest(double t_s) noexcept override;
  double duration_s() const noexcept override { return duration_s_; }
  std::string describe() const override { return description_; }
  // Frames decoded so far (any thread; for tests and statistics).
  std::uint64_t frames() const noexcept { return frames_.load(std::memory_order_relaxed); }

 private:
  struct Published {
    PenFrame frame;
    std::int64_t heartbeat_ns = 0;  // CLOCK_MONOTONIC of the reader's last wake
  };
  void reader_main() noexcept;

  std::unique_ptr<PenEventSource> source_;
  TabletDecoder decoder_;
  std::string description_;
  double duration_s_ = 0;
  LatestValue<Published> published_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> started_{false};  // the loop asked for its first sample
  std::atomic<std::uint64_t> frames_{0};
  int reader_fifo_priority_ = 0;
  std::int64_t epoch_ns_ = 0;  // loop time 0 on CLOCK_MONOTONIC, fixed at the first latest()
  std::thread reader_;
};

// "tablet", "tablet:/dev/input/eventN" or "tablet:FILE.evemu" (a recording replayed in real
// time through the same reader). Throws InputError when no such device or file can be used.
std::unique_ptr<TabletInput> make_tablet_input(const std::string& spec, const TabletConfig& config,
                                               const PenRecordingLimits& recording_limits = {});

}  // namespace palprig
