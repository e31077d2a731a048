#pragma once
// SimulatedRig: three PneumaticPlant channels in process. The plants advance by the loop time
// passed to writes and reads, so a replay runs the same physics as real time, only faster.
#include <array>

#include "rigs/rig_backend.hpp"
#include "models/pneumatic_plant.hpp"

namespace palprig {

class SimulatedRig final : public RigBackend {
 public:
  SimulatedRig(const std::array<PlantParams, kFingerCount>& plants, double p_max_kPa);
  std::string describe() const override { return "simulated"; }
  BackendCapabilities capabilities() const override;
  // The true actuator pressure (what a finger feels), for tests and telemetry.
  double plant_output_kPa(std::size_t channel) const noexcept { return plants_[channel].output_kPa(); }

 protected:
  void do_open() override;
  void do_close() noexcept override {}
  BackendStatus do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept override;
  BackendStatus do_read(ChannelPressures& monitor_kPa, double t_s) noexcept override;
  BackendStatus do_vent() noexcept override;

 private:
  void advance_to(double t_s) noexcept;

  std::array<PneumaticPlant, kFingerCount> plants_;
  ChannelPressures command_kPa_{};
  double last_t_s_ = 0;
  bool started_ = false;
};

}  // namespace palprig
