#pragma once
// What sessions share before their first trial: the rig and calibration loaded and checked, the
// rig taken (its lease: controller/rig_lease.hpp) only once every file has been accepted, and the
// clock the session runs on (hardware always on the wall clock, as `palprig run` insists).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "controller/tick.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/session_clock.hpp"
#include "formats/rig_file.hpp"
#include "models/calibration_models.hpp"
#include "controller/rig_lease.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig {

// The rig a session drives: the front end's opened rig (the window's), leased for the session,
// or one opened here from the rig file. Given back, vented, when this goes (a rig opened here is
// closed too).
class SessionRig {
 public:
  // Throws RigBusy when `given` is held by something that does not give way, Error when the
  // rig file's device cannot be reached.
  SessionRig(Rig* given, const RigConfig& config, const std::string& holder);
  RigBackend& backend() noexcept { return lease_->backend(); }

 private:
  std::unique_ptr<Rig> opened_;  // declared before the lease: the lease goes back first
  std::optional<RigLease> lease_;
};

struct StudyRig {
  RigConfig rig;
  CalibrationModels cal;
  TickConfig config;
  std::optional<SessionRig> taken;  // by take()

  bool hardware() const { return rig.backend != "simulated"; }
  // The front end's rig (null: open the rig file's), leased for the session.
  void take(Rig* given, const std::string& holder) { taken.emplace(given, rig, holder); }
  RigBackend& backend() { return taken->backend(); }
  // Every channel to 0 kPa at the session's end; the lease goes back when this goes (after the
  // session's RigStimulus, which refers to the backend).
  void vent() { (void)taken->backend().vent(); }
};

// Throws InputError for a refused file (nothing is opened). An empty calibration file: paper
// 002's models.
StudyRig load_study_rig(const std::filesystem::path& rig_file, const std::filesystem::path& calibration_file);

// After a session that faulted: the ticks before the fault written beside the session's
// telemetry file, else beside its store (an SQLite file's folder; a server store's journal
// folder). Returns the sentence for the front end's fault line.
std::string save_session_fault_record(const RigStimulus& output, const std::string& what_ran,
                                      const std::filesystem::path& telemetry_file, const std::filesystem::path& beside);

// True for sim:SEED (seed set); false for a person's code; a malformed sim:... is refused.
bool simulated_participant(const std::string& code, std::uint64_t& seed);

// Hardware refuses a speed other than 1 (or none); a simulated participant on a simulated rig
// runs on simulated time (speed 0) or `speed` times real time; everything else in real time.
void refuse_speed_on_hardware(const StudyRig& rig, double speed);
std::unique_ptr<SessionClock> session_clock(const StudyRig& rig, bool simulated, double speed);

}  // namespace palprig
