#pragma once
// Why the rig was vented: the code (stored in every telemetry record) and the Fault that carries
// it with its time and the words of whoever found it (the backend's, a worker's, the loop's).
#include <array>
#include <cstdint>
#include <cstdio>
#include <string>

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

// A fault with its reason. The first reason latched wins, as the tick's latch does: a backend
// error that follows a signal does not hide the signal. Fixed size, so the loop thread latches it
// without allocating; compared with a FaultCode it compares its code.
struct Fault {
  FaultCode code = FaultCode::none;
  double t_s = 0;                 // loop time it was latched at
  std::array<char, 224> words{};  // the finder's own words; empty when the code says it all

  bool active() const noexcept { return code != FaultCode::none; }
  std::string detail() const { return words.data(); }
  // Latch `why` at t_s with `text` (copied, cut to fit) unless a fault is already latched.
  // True when this call latched it.
  bool latch(FaultCode why, double at_t_s, const char* text = nullptr) noexcept {
    if (active() || why == FaultCode::none) return false;
    code = why;
    t_s = at_t_s;
    std::snprintf(words.data(), words.size(), "%s", text ? text : "");
    return true;
  }
  // "rig backend error at t=1.234 s (modbus link down ...)"; "none" when no fault.
  std::string describe() const {
    if (!active()) return "none";
    char when[48];
    std::snprintf(when, sizeof when, " at t=%.3f s", t_s);
    std::string text = std::string(to_string(code)) + when;
    if (words[0] != '\0') text += std::string(" (") + words.data() + ")";
    return text;
  }
  friend bool operator==(const Fault& f, FaultCode c) noexcept { return f.code == c; }
};

inline const char* to_string(const Fault& f) noexcept { return to_string(f.code); }

}  // namespace palprig
