#pragma once
// A session's telemetry (StudySessionRequest::telemetry_file): every rig tick the session's
// RigStimulus services, written as `palprig run --telemetry` writes (.bin binary, else CSV), on
// the session clock the stored trial onsets use. Shared by the discrimination/localisation,
// threshold and pulse sessions.
#include <filesystem>
#include <memory>
#include <string>

#include "controller/telemetry_writer.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/session_clock.hpp"
#include "sessions/study_session.hpp"

namespace palprig {

// Refuses (InputError) a path that cannot take a new recording: an existing non-empty file
// (e.g. an earlier attempt's: a resumed session never overwrites it) or a folder that does not
// exist. Called with the other checks, before the rig moves.
void refuse_unusable_telemetry_file(const std::filesystem::path& file);

// "telemetry: 58023 ticks in FILE" (and the dropped count when any), or "" without telemetry:
// what the command line prints and the console lists at the end of a session.
std::string telemetry_summary(const SessionEnd& end);

class SessionTelemetry {
 public:
  // Empty `file`: records nothing. On simulated time every tick is kept (the session waits for
  // the writer); in real time a tick the writer cannot queue is dropped and counted, so the rig
  // never waits for the disk. A writer that fails faults the session (RigStimulus vents).
  SessionTelemetry(const std::filesystem::path& file, RigStimulus& output, const SessionClock& clock);
  ~SessionTelemetry();
  SessionTelemetry(const SessionTelemetry&) = delete;
  SessionTelemetry& operator=(const SessionTelemetry&) = delete;

  // After the session loop: detaches from the output, drains and closes the file, and fills
  // end.telemetry_* (a writer failure becomes end.fault when there is none yet).
  void finish(SessionEnd& end);

 private:
  std::filesystem::path file_;
  RigStimulus& output_;
  std::unique_ptr<TelemetryWriter> writer_;
};

}  // namespace palprig
