#include "sessions/study_rig.hpp"

#include "controller/tick_setup.hpp"
#include "experiments/simulated_participant.hpp"
#include "formats/calibration_file.hpp"
#include "core/input_error.hpp"

namespace palprig {

StudyRig load_study_rig(const std::filesystem::path& rig_file, const std::filesystem::path& calibration_file) {
  StudyRig s;
  s.rig = load_rig_file(rig_file);
  s.cal = calibration_file.empty() ? CalibrationModels{} : load_calibration_file(calibration_file);
  check_calibration_matches(s.cal, s.rig.id, s.rig.source);
  s.config = make_tick_config(s.rig, s.cal);
  return s;
}

SessionRig::SessionRig(Rig* given, const RigConfig& config, const std::string& holder) {
  Rig* rig = given;
  if (!rig) {
    opened_ = open_rig(config);
    rig = opened_.get();
  }
  lease_.emplace(rig->lease(holder));
  // The window's simulated rig, which its live loop drove until now: opened again, so the
  // session starts from a regulator at rest with its noise seeded afresh, as on a rig opened for
  // it (the command line's). Hardware is what it is and is not touched.
  if (given && config.backend == "simulated") lease_->backend().open();
}

std::string save_session_fault_record(const RigStimulus& output, const std::string& what_ran,
                                      const std::filesystem::path& telemetry_file,
                                      const std::filesystem::path& beside) {
  if (!output.step().faulted()) return "";  // a telemetry failure: no rig fault to record
  std::error_code ec;
  std::filesystem::path folder = std::filesystem::absolute(beside, ec).parent_path();
  if (folder.empty()) folder = std::filesystem::current_path(ec);
  return save_fault_record(output.step().recorder(), output.step().fault(), what_ran, telemetry_file, folder);
}

bool simulated_participant(const std::string& code, std::uint64_t& seed) {
  const bool simulated = parse_simulated_participant(code, seed);
  if (!simulated && code.rfind("sim:", 0) == 0) {
    throw InputError("command line", "participant", "sim:SEED with a decimal seed, got '" + code + "'");
  }
  return simulated;
}

void refuse_speed_on_hardware(const StudyRig& s, double speed) {
  if (s.hardware() && speed != 0 && speed != 1) {
    throw InputError("command line", "speed",
                     "1 (real time) or none with a hardware rig (" + s.rig.source + ", backend " + s.rig.backend +
                         "): hardware runs in real time");
  }
}

std::unique_ptr<SessionClock> session_clock(const StudyRig& s, bool simulated, double speed) {
  // On simulated time a hardware session would pass in a few bus cycles and the regulators
  // would never reach a stimulus.
  if (simulated && !s.hardware() && speed <= 0) return std::make_unique<SimulatedClock>();
  return std::make_unique<SteadyClock>(simulated && !s.hardware() ? speed : 1.0);
}

}  // namespace palprig
