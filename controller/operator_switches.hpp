#pragma once
// OperatorSwitches: what the window's controls set while a run goes on (the lag compensation
// check box, each artery's rate and amplitude). The GUI thread writes them; the loop reads them
// once per tick into the tick's inputs (TickInputs), so the tick itself stays a function of its
// arguments. Relaxed atomics: each switch is independent and any recent value will do.
#include <array>
#include <atomic>
#include <cstddef>

#include "controller/tick.hpp"

namespace palprig {

class OperatorSwitches {
 public:
  OperatorSwitches() noexcept;
  OperatorSwitches(const OperatorSwitches&) = delete;
  OperatorSwitches& operator=(const OperatorSwitches&) = delete;

  // Any thread.
  void set_lag_compensation(bool on) noexcept { compensate_lag_.store(on, std::memory_order_relaxed); }
  bool lag_compensation() const noexcept { return compensate_lag_.load(std::memory_order_relaxed); }
  // Beat artery i at bpm, or set its amplitude, from the next tick. False (and no change) for an
  // index beyond kMaxArteries or a value PulseField refuses (valid_rate_bpm, valid_amplitude_kPa).
  bool request_pulse_rate_bpm(std::size_t artery, double bpm) noexcept;
  bool request_pulse_amplitude_kPa(std::size_t artery, double amplitude_kPa) noexcept;

  // The loop's thread, once per tick.
  TickInputs read() const noexcept;

 private:
  std::atomic<bool> compensate_lag_{true};
  std::array<std::atomic<double>, kMaxArteries> rate_bpm_;
  std::array<std::atomic<double>, kMaxArteries> amplitude_kPa_;
};

}  // namespace palprig
