#include "controller/run_report.hpp"

#include <iomanip>
#include <ostream>

namespace palprig {

nlohmann::json run_summary_json(const RunSummary& s, const LoadedRun& run, const RunOptions& opt) {
  using nlohmann::json;
  auto stats = [](const std::array<RangeStats, kFingerCount>& a) {
    json arr = json::array();
    for (const auto& r : a) arr.push_back({{"min", r.min}, {"mean", r.mean()}, {"max", r.max}});
    return arr;
  };
  auto lat = [](const LatencySummary& l) {
    return json{{"p50_us", l.p50_us}, {"p99_us", l.p99_us}, {"p999_us", l.p999_us}, {"max_us", l.max_us}};
  };
  json j = {
      {"scene", run.scene.source},
      {"rig", run.rig.id},
      {"backend", run.rig_opened ? run.rig_opened->backend().describe() : std::string("none")},
      {"input", run.input->describe()},
      {"mode", opt.mode == LoopMode::realtime ? "realtime" : "replay"},
      {"rate_hz", opt.rate_hz},
      {"ticks", s.ticks},
      {"overruns", s.overruns},
      {"missed_periods", s.missed_periods},
      {"link_outages", s.link_outages},
      {"unlinked_ticks", s.unlinked_ticks},
      {"sim_time_s", s.sim_time_s},
      {"wall_time_s", s.wall_time_s},
      {"speedup", s.wall_time_s > 0 ? s.sim_time_s / s.wall_time_s : 0.0},
      {"target_kPa", stats(s.target_kPa)},
      {"setpoint_kPa", stats(s.setpoint_kPa)},
      {"plant_kPa", stats(s.monitor_kPa)},
      {"fault", s.fault == FaultCode::none ? json(nullptr)
                                           : json{{"code", static_cast<int>(s.fault.code)},
                                                  {"reason", to_string(s.fault)},
                                                  {"detail", s.fault.detail()},
                                                  {"t_s", s.fault.t_s}}},
      {"tick_time", lat(s.tick_time)},
      {"io_time", lat(s.io_time)},
      {"telemetry", s.telemetry_path.empty() ? json(nullptr) : json(s.telemetry_path)},
      {"telemetry_dropped", s.telemetry_dropped},
  };
  if (run.tracking) {
    json fingers = json::array();
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      json vents = json::object();
      for (std::size_t why = 1; why < RunSummary::kVentReasons; ++why)
        if (s.finger_vent_ticks[i][why]) vents[to_string(static_cast<FingerVent>(why))] = s.finger_vent_ticks[i][why];
      fingers.push_back(
          {{"force_N", {{"mean", s.force_N[i].mean()}, {"max", s.force_N[i].max}}}, {"vented_ticks", vents}});
    }
    j["tracked_fingers"] = fingers;
  }
  if (opt.mode == LoopMode::realtime) {
    j["wake_latency"] = lat(s.wake_latency);
    j["realtime_note"] = s.realtime_note;
    j["realtime_practices"] = s.realtime_practices;
  }
  return j;
}

void print_run_summary(std::ostream& out, const RunSummary& s, const LoadedRun& run, const RunOptions& opt) {
  out << "palprig run: " << run.scene.source << " on " << (run.rig_opened ? run.rig_opened->backend().describe() : "?")
      << " (" << run.rig.id << "), input " << run.input->describe() << "\n";
  out << "  " << s.ticks << " ticks at " << opt.rate_hz << " Hz, " << std::fixed << std::setprecision(3);
  // A replay says how much faster than real time it ran; a real-time run took its own length
  // by design, so it says so rather than "13.290 s simulated in 13.290 s wall (1x)".
  if (opt.mode == LoopMode::realtime) {
    out << s.wall_time_s << " s in real time";
  } else {
    out << s.sim_time_s << " s simulated in " << s.wall_time_s << " s wall (" << std::setprecision(0)
        << (s.wall_time_s > 0 ? s.sim_time_s / s.wall_time_s : 0) << "x faster than real time)";
  }
  out << ", overruns " << s.overruns << " (" << s.missed_periods << " periods skipped)\n";
  out << std::setprecision(2);
  out << "  finger   target kPa min/mean/max      plant kPa min/mean/max\n";
  for (int i = 0; i < kFingerCount; ++i)
    out << "  " << i + 1 << "        " << std::setw(6) << s.target_kPa[i].min << " / " << std::setw(6)
        << s.target_kPa[i].mean() << " / " << std::setw(6) << s.target_kPa[i].max << "    " << std::setw(6)
        << s.monitor_kPa[i].min << " / " << std::setw(6) << s.monitor_kPa[i].mean() << " / " << std::setw(6)
        << s.monitor_kPa[i].max << "\n";
  out << std::setprecision(1) << "  tick time p50/p99/max " << s.tick_time.p50_us << "/" << s.tick_time.p99_us << "/"
      << s.tick_time.max_us << " us, backend I/O p50/p99/p99.9/max " << s.io_time.p50_us << "/" << s.io_time.p99_us
      << "/" << s.io_time.p999_us << "/" << s.io_time.max_us << " us\n";
  if (run.tracking) {
    // Tracked fingers: what the load cells measured, and how long each finger was vented for a
    // reason of its own (its tool out of view, not seen, invalid).
    out << std::setprecision(2) << "  load cells: force N mean/max";
    for (int i = 0; i < kFingerCount; ++i)
      out << (i ? ", " : " ") << "finger " << i + 1 << " " << s.force_N[i].mean() << "/" << s.force_N[i].max;
    out << "\n";
    for (int i = 0; i < kFingerCount; ++i)
      for (std::size_t why = 1; why < RunSummary::kVentReasons; ++why)
        if (const std::uint64_t n = s.finger_vent_ticks[i][why])
          out << "  finger " << i + 1 << " vented " << n << (n == 1 ? " tick: " : " ticks: ")
              << to_string(static_cast<FingerVent>(why)) << "\n";
    out << std::setprecision(1);
  }
  if (s.link_outages)
    out << "  link outages: " << s.link_outages << " (" << s.unlinked_ticks << " ticks vented while reconnecting)\n";
  if (opt.mode == LoopMode::realtime) {
    out << "  wake-up latency p50/p99/p99.9/max " << s.wake_latency.p50_us << "/" << s.wake_latency.p99_us << "/"
        << s.wake_latency.p999_us << "/" << s.wake_latency.max_us << " us\n";
    out << "  real time: " << s.realtime_practices << "\n";
    if (!s.realtime_note.empty()) out << "  note: " << s.realtime_note << "\n";
  }
  out << "  faults: "
      << (s.fault == FaultCode::none
              ? std::string("none")
              : std::string(to_string(s.fault)) + (s.fault.detail().empty() ? "" : ": " + s.fault.detail()))
      << "\n";
  if (!s.telemetry_path.empty())
    out << "  telemetry: " << s.telemetry_path
        << (s.telemetry_dropped ? " (" + std::to_string(s.telemetry_dropped) + " records dropped)" : "") << "\n";
}

}  // namespace palprig
