#pragma once
// The lag compensation stage alone on channel 0 against a simulated regulator, as the controller
// suites drive it (tests/controller/lag_compensation_test.cpp, exhaust_lag_compensation_test.cpp).
#include <vector>

#include "controller/lag_compensation_stage.hpp"
#include "models/pneumatic_plant.hpp"

namespace palprig::testing {

// The simulated regulator without play or noise: the lag alone, as the stage sees it once the
// hysteresis inverse has done its work.
inline PlantParams lag_only_plant() {
  PlantParams p;
  p.hysteresis_kPa = 0;
  p.noise_sd_kPa = 0;
  return p;
}

struct StageDrive {
  std::vector<double> target, output, command;
};

// The stage alone on channel 0: base_at(t) is the target at time t (known ahead, as the scene
// sampled where the finger will be), the plant stepped at 1 kHz under each command.
template <typename Target>
StageDrive drive_stage(Target base_at, bool compensate, const RegulatorLag& model, double max_lead_kPa, double seconds,
                       const PlantParams& plant_params = lag_only_plant()) {
  PneumaticPlant plant(plant_params);
  LagCompensationState st;
  LagPlan plan;
  plan.part[0] = compensate ? CompensatedPart::total : CompensatedPart::none;
  plan.model[0] = model;
  const double dt = 0.001;
  plan.lead_s[0] = model.dead_time_s + dt;
  const LagLimits limits{60, 2000, max_lead_kPa};
  StageDrive d;
  double previous = 0;
  for (int k = 0; k * dt < seconds; ++k) {
    const double t = k * dt;
    LagTargets in;
    in.base_now_kPa[0] = base_at(t);
    in.base_ahead_kPa[0] = base_at(t + plan.lead_s[0]);
    const ChannelPressures u = lag_compensation_stage(st, plan, in, limits, k > 0 ? dt : 0.0);
    if (k > 0) plant.step(previous, dt);
    previous = u[0];
    d.target.push_back(in.base_now_kPa[0]);
    d.output.push_back(plant.output_kPa());
    d.command.push_back(u[0]);
  }
  return d;
}

}  // namespace palprig::testing
