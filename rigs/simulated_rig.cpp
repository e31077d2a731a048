#include "rigs/simulated_rig.hpp"

#include <cmath>

namespace palprig {

SimulatedRig::SimulatedRig(const std::array<PlantParams, kFingerCount>& plants, double p_max_kPa)
    : RigBackend(p_max_kPa), plants_{PneumaticPlant(plants[0]), PneumaticPlant(plants[1]), PneumaticPlant(plants[2])} {}

BackendCapabilities SimulatedRig::capabilities() const {
  BackendCapabilities c;
  c.link_kind = "in-process";
  c.endpoint = "simulated plant";
  describe_load_cells(c);
  return c;
}

void SimulatedRig::do_open() {
  // A fresh regulator each time the rig opens, its noise from the seed again: a session that
  // opens the window's simulated rig after the live loop ran on it gives what `experiment run`
  // gives on a rig opened for it (same seeds, same trials).
  for (auto& p : plants_) p = PneumaticPlant(p.params());
  command_kPa_ = {};
  started_ = false;
  cells_.clear();
  depth_mm_ = {};
  if (load_cells()) {
    for (std::size_t i = 0; i < load_cells()->channels.size(); ++i) {
      SimulatedLoadCellParams p = load_cells()->simulated;
      p.seed += i;
      cells_.emplace_back(p);
    }
  }
}

BackendStatus SimulatedRig::do_read_load_cells(std::array<double, kFingerCount>& volts, double) noexcept {
  if (cells_.empty()) {
    return set_error("the simulated rig's load cells are read after open()");
  }
  if (cells_.size() == 1) {
    // One cell under every finger: it feels the deepest press.
    double depth = 0;
    for (double d : depth_mm_)
      if (std::isfinite(d) && d > depth) depth = d;
    volts[0] = cells_[0].volts(depth, extra_load_N_[0]);
    return BackendStatus::ok;
  }
  for (std::size_t i = 0; i < cells_.size(); ++i) volts[i] = cells_[i].volts(depth_mm_[i], extra_load_N_[i]);
  return BackendStatus::ok;
}

void SimulatedRig::advance_to(double t_s) noexcept {
  // The plants run under the latched command up to now (a regulator holds its last command
  // between writes).
  if (started_ && t_s > last_t_s_)
    for (std::size_t i = 0; i < plants_.size(); ++i) plants_[i].step(command_kPa_[i], t_s - last_t_s_);
  last_t_s_ = t_s;  // a new run may start its clock at 0 again
  started_ = true;
}

BackendStatus SimulatedRig::do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept {
  advance_to(t_s);
  command_kPa_ = setpoint_kPa;
  return BackendStatus::ok;
}

BackendStatus SimulatedRig::do_read(ChannelPressures& monitor_kPa, double t_s) noexcept {
  // Reading advances too, so a vented (disarmed) rig that is only read keeps exhausting.
  advance_to(t_s);
  for (std::size_t i = 0; i < plants_.size(); ++i) monitor_kPa[i] = plants_[i].monitor_kPa();
  return BackendStatus::ok;
}

BackendStatus SimulatedRig::do_vent() noexcept {
  command_kPa_ = {};
  return BackendStatus::ok;
}

}  // namespace palprig
