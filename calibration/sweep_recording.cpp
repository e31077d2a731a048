#include "calibration/sweep_recording.hpp"

#include "calibration/calibration_report.hpp"

namespace palprig {

SweepRecording record_calibration_sweep(RigLease& lease, const RigConfig& rig, const SweepSchedule& schedule,
                                        const SweepRunOptions& options, const std::filesystem::path& out,
                                        const SweepProgress& progress) {
  SweepFileInfo info;
  info.rig_id = rig.id;
  const RigBackend& backend = lease.backend();
  info.backend = backend.describe();
  info.date = utc_timestamp_now();
  info.p_max_kPa = rig.safety.p_max_kPa;
  info.rate_hz = options.rate_hz;
  info.sensor_name = backend.sensor_name();
  info.notes = schedule.notes;
  SweepCsvWriter writer(out, info, options.channels);
  SweepRecording r;
  r.outcome = run_calibration_sweep(lease, schedule, options, writer, progress);
  writer.finish(r.outcome);
  r.rows = writer.rows();
  return r;
}

}  // namespace palprig
