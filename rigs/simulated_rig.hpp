#pragma once
// SimulatedRig: three PneumaticPlant channels in process. The plants advance by the loop time
// between writes, so a replay runs the same physics as real time, only faster.
#include <array>

#include "rigs/rig_backend.hpp"
#include "models/pneumatic_plant.hpp"

namespace palprig {

class SimulatedRig final : public RigBackend {
 public:
  SimulatedRig(const std::array<PlantParams, kFingerCount>& plants, double p_max_kPa);
  void open() override;
  void close() noexcept override {}
  std::string describe() const override { return "simulated"; }
  // The true actuator pressure (what a finger feels), for tests and telemetry.
  double plant_output_kPa(std::size_t channel) const noexcept { return plants_[channel].output_kPa(); }

 protected:
  BackendStatus do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept override;
  BackendStatus do_read(ChannelPressures& monitor_kPa, double t_s) noexcept override;
  BackendStatus do_vent() noexcept override;

 private:
  std::array<PneumaticPlant, kFingerCount> plants_;
  ChannelPressures command_kPa_{};
  double last_t_s_ = 0;
  bool started_ = false;
};

}  // namespace palprig
