#pragma once
// What threshold and pulse sessions share before their first trial: the rig and calibration
// loaded and checked, the backend opened only once every file has been accepted, and the clock
// the session runs on (hardware always on the wall clock, as `palprig run` insists).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "controller/tick.hpp"
#include "experiments/session_clock.hpp"
#include "formats/rig_file.hpp"
#include "models/calibration_models.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig {

struct StudyRig {
  RigConfig rig;
  CalibrationModels cal;
  TickConfig config;
  std::unique_ptr<RigBackend> backend;  // made and opened (vented) by open()

  bool hardware() const { return rig.backend != "simulated"; }
  void open();
  void vent_and_close();
};

// Throws InputError for a refused file (nothing is opened). An empty calibration file: paper
// 002's models.
StudyRig load_study_rig(const std::filesystem::path& rig_file, const std::filesystem::path& calibration_file);

// True for sim:SEED (seed set); false for a person's code; a malformed sim:... is refused.
bool simulated_participant(const std::string& code, std::uint64_t& seed);

// Hardware refuses a speed other than 1 (or none); a simulated participant on a simulated rig
// runs on simulated time (speed 0) or `speed` times real time; everything else in real time.
void refuse_speed_on_hardware(const StudyRig& rig, double speed);
std::unique_ptr<SessionClock> session_clock(const StudyRig& rig, bool simulated, double speed);

}  // namespace palprig
