#pragma once
// Why the rig was vented. Stored in every telemetry record and in the run summary.
#include <cstdint>

namespace palprig {

enum class FaultCode : std::uint8_t {
  none = 0,
  bad_sample,         // non-finite or negative pen force
  non_finite_target,  // a model produced NaN/inf
  backend_error,      // the rig backend failed to write or read
  input_stale,        // the pen sample is older than the configured limit
  overrun_limit,      // too many consecutive missed deadlines
  signal,             // SIGINT / SIGTERM
  thread_exception,   // an exception on another thread (writer, I/O, input)
  operator_stop,      // stopped on purpose (end of run, GUI stop button)
  bad_position,       // non-finite pen position (added after the others: stored codes keep their values)
  bad_time,           // non-finite pen sample time or loop time
  lost_time_limit,    // the loop lost more than safety.max_lost_time_s of periods: it cannot hold its rate
};

constexpr const char* to_string(FaultCode f) noexcept {
  switch (f) {
    case FaultCode::none: return "none";
    case FaultCode::bad_sample: return "bad pen sample (non-finite or negative force)";
    case FaultCode::bad_position: return "bad pen sample (non-finite x or y position)";
    case FaultCode::bad_time: return "bad pen sample (non-finite time)";
    case FaultCode::non_finite_target: return "non-finite pressure target";
    case FaultCode::backend_error: return "rig backend error";
    case FaultCode::input_stale: return "pen input stale";
    case FaultCode::overrun_limit: return "too many consecutive deadline overruns";
    case FaultCode::signal: return "stopped by signal";
    case FaultCode::thread_exception: return "exception on a worker thread";
    case FaultCode::operator_stop: return "operator stop";
    case FaultCode::lost_time_limit: return "loop cannot hold its rate (lost time beyond safety.max_lost_time_s)";
  }
  return "unknown";
}

}  // namespace palprig
