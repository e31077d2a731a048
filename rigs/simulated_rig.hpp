#pragma once
// SimulatedRig: three PneumaticPlant channels in process. The plants advance by the loop time
// passed to writes and reads, so a replay runs the same physics as real time, only faster.
#include <array>
#include <vector>

#include "rigs/rig_backend.hpp"
#include "models/load_cell.hpp"
#include "models/pneumatic_plant.hpp"

namespace palprig {

class SimulatedRig final : public RigBackend {
 public:
  SimulatedRig(const std::array<PlantParams, kFingerCount>& plants, double p_max_kPa);
  std::string describe() const override { return "simulated"; }
  BackendCapabilities capabilities() const override;
  // The true actuator pressure (what a finger feels), for tests and telemetry.
  double plant_output_kPa(std::size_t channel) const noexcept { return plants_[channel].output_kPa(); }

  // Load cells (the rig file's "load_cells" with its "simulated" part): each cell feels the
  // press of its finger (shared: the deepest finger) as SimulatedLoadCell models it.
  void feel_press(const std::array<double, kFingerCount>& depth_mm) noexcept override { depth_mm_ = depth_mm; }
  // A load placed on cell `channel` by hand (a calibration weight; 0 to lift it).
  void place_load_N(std::size_t channel, double load_N) noexcept {
    if (channel < extra_load_N_.size()) extra_load_N_[channel] = load_N;
  }

 protected:
  void do_open() override;
  void do_close() noexcept override {}
  BackendStatus do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept override;
  BackendStatus do_read(ChannelPressures& monitor_kPa, double t_s) noexcept override;
  BackendStatus do_vent() noexcept override;
  BackendStatus do_read_load_cells(std::array<double, kFingerCount>& volts, double t_s) noexcept override;

 private:
  void advance_to(double t_s) noexcept;

  std::array<PneumaticPlant, kFingerCount> plants_;
  ChannelPressures command_kPa_{};
  double last_t_s_ = 0;
  bool started_ = false;
  std::vector<SimulatedLoadCell> cells_;  // made at open() from the rig file's load cells
  std::array<double, kFingerCount> depth_mm_{};
  std::array<double, kFingerCount> extra_load_N_{};
};

}  // namespace palprig
