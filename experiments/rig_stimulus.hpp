#pragma once
// RigStimulus: StimulusOutput on a real or simulated rig through the controller's public tick.
// Direct stimuli go through tick_direct (hysteresis compensation and the safety stage), scenes
// through tick (finger layout, stiffness, stress and actuator models, safety), then to the
// backend. A safety fault or backend error vents every channel and throws RigFault.
#include "rigs/rig_backend.hpp"
#include "controller/telemetry.hpp"
#include "controller/tick.hpp"
#include "experiments/stimulus_output.hpp"

namespace palprig {

class RigStimulus final : public StimulusOutput {
 public:
  // The configuration and backend must outlive this object; the backend must be open.
  RigStimulus(const TickConfig& config, RigBackend& backend);

  void hold(const ChannelPressures& target_kPa, double t_s) override;
  void palpate(const Scene& scene, InputSource& pen, double t_s) override;
  void vent(double t_s) override;
  ChannelPressures service(double t_s) override;
  std::string describe() const override { return backend_.describe(); }

  // The record of the last serviced tick (pen position and per-finger values, for observers).
  const TelemetryRecord* last_record() const noexcept override { return &last_; }

 private:
  enum class Mode { vented, hold, scene };
  [[noreturn]] void fault(const std::string& why);

  const TickConfig& config_;
  RigBackend& backend_;
  TickState state_;
  Mode mode_ = Mode::vented;
  ChannelPressures target_kPa_{};
  const Scene* scene_ = nullptr;
  InputSource* pen_ = nullptr;
  TelemetryRecord last_{};
};

}  // namespace palprig
