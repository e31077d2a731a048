#pragma once
// RigStimulus: StimulusOutput on a real or simulated rig through the controller's rig step
// (controller/rig_step.hpp). Direct stimuli go through tick_direct (hysteresis inverse and the
// safety stage), scenes through tick (finger layout, stiffness, stress and actuator models,
// safety), then to the backend. The backend is armed for the stimulus's lifetime; pressure
// rises from the vented state under the slew limit. A safety fault or backend error vents every
// channel and throws RigFault.
#include "controller/rig_step.hpp"
#include "controller/telemetry.hpp"
#include "controller/telemetry_writer.hpp"
#include "experiments/stimulus_output.hpp"

namespace palprig {
class TickObserver;  // controller/loop_runner.hpp
}

namespace palprig {

class RigStimulus final : public StimulusOutput {
 public:
  // The backend must be open and outlive this object. rate_hz: how often service() is called
  // (the session loop's period); it sizes the first slew step. Throws RigFault when the
  // backend refuses to arm.
  RigStimulus(const TickConfig& config, RigBackend& backend, double rate_hz = 200.0);
  ~RigStimulus() override;  // disarms: every channel vented

  void hold(const ChannelPressures& target_kPa, double t_s) override;
  void palpate(const Scene& scene, InputSource& pen, double t_s) override;
  void vent(double t_s) override;
  ChannelPressures service(double t_s) override;
  std::string describe() const override { return rig_.backend().describe(); }

  // The rig step: its fault and the record of the ticks before it (controller/fault_recorder.hpp).
  const RigStep& step() const noexcept { return rig_; }

  // The record of the last serviced tick (pen position and per-finger values, for observers).
  const TelemetryRecord* last_record() const noexcept override { return &last_; }

  // Every serviced tick from now on also goes to `writer` (null: none). keep_every_record: wait
  // for room in its queue (a session on simulated time, which has no deadline) instead of
  // dropping and counting (real time: the rig is never made to wait for the disk). A writer
  // that failed (disk full, its size budget) is a fault: every channel vented.
  void record_to(TelemetryWriter* writer, bool keep_every_record) noexcept {
    telemetry_ = writer;
    keep_every_record_ = keep_every_record;
  }
  // Every serviced tick from now on is also handed to `observer` (null: none), which must be
  // wait-free (the GUI's live view: gui/telemetry_feed.hpp drops rather than wait).
  void observe_with(TickObserver* observer) noexcept { observer_ = observer; }

 private:
  enum class Mode { vented, hold, scene };
  [[noreturn]] void fault(const std::string& why);

  RigStep rig_;
  Mode mode_ = Mode::vented;
  ChannelPressures target_kPa_{};
  const Scene* scene_ = nullptr;
  InputSource* pen_ = nullptr;
  TelemetryRecord last_{};
  TelemetryWriter* telemetry_ = nullptr;
  bool keep_every_record_ = false;
  TickObserver* observer_ = nullptr;
};

}  // namespace palprig
