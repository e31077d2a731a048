#include "controller/operator_switches.hpp"

namespace palprig {

OperatorSwitches::OperatorSwitches() noexcept {
  for (auto& r : rate_bpm_) r.store(PulseSettings::kScene, std::memory_order_relaxed);
  for (auto& a : amplitude_kPa_) a.store(PulseSettings::kScene, std::memory_order_relaxed);
}

bool OperatorSwitches::request_pulse_rate_bpm(std::size_t artery, double bpm) noexcept {
  if (artery >= kMaxArteries || !PulseField::valid_rate_bpm(bpm)) return false;
  rate_bpm_[artery].store(bpm, std::memory_order_relaxed);
  return true;
}

bool OperatorSwitches::request_pulse_amplitude_kPa(std::size_t artery, double amplitude_kPa) noexcept {
  if (artery >= kMaxArteries || !PulseField::valid_amplitude_kPa(amplitude_kPa)) return false;
  amplitude_kPa_[artery].store(amplitude_kPa, std::memory_order_relaxed);
  return true;
}

TickInputs OperatorSwitches::read() const noexcept {
  TickInputs in;
  in.compensate_lag = compensate_lag_.load(std::memory_order_relaxed);
  for (std::size_t i = 0; i < kMaxArteries; ++i) {
    in.pulse.rate_bpm[i] = rate_bpm_[i].load(std::memory_order_relaxed);
    in.pulse.amplitude_kPa[i] = amplitude_kPa_[i].load(std::memory_order_relaxed);
  }
  return in;
}

}  // namespace palprig
