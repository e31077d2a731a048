#pragma once
// StimulusOutput: what the trial runner drives. RigStimulus puts it on a rig through the
// controller's tick (direct per-finger pressures, or a scene felt through pen input); tests
// substitute a recording fake. Calls come from the session thread, never the real-time loop.
#include <string>

#include "core/error.hpp"  // RigFault: the rig faulted (backend error, safety fault), every channel vented

#include "inputs/input_source.hpp"
#include "rigs/rig_backend.hpp"
#include "controller/telemetry.hpp"
#include "models/scene.hpp"

namespace palprig {

class StimulusOutput {
 public:
  virtual ~StimulusOutput() = default;
  // From t_s on, hold these pressures on the fingers.
  virtual void hold(const ChannelPressures& target_kPa, double t_s) = 0;
  // From t_s on, render the scene under the pen (localisation).
  virtual void palpate(const Scene& scene, InputSource& pen, double t_s) = 0;
  // From t_s on, every channel at 0 kPa.
  virtual void vent(double t_s) = 0;
  // Called on every pass of the session loop, so slew-limited setpoints ramp and a simulated
  // plant advances. Returns what the fingers feel now (the regulators' monitor readings).
  // Throws RigFault after venting when the rig faults.
  virtual ChannelPressures service(double t_s) = 0;
  virtual std::string describe() const = 0;
  // The last tick's record (pen position, per-finger values), when the output has one.
  virtual const TelemetryRecord* last_record() const noexcept { return nullptr; }
};

}  // namespace palprig
