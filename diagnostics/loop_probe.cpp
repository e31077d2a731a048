#include "diagnostics/loop_probe.hpp"
#include "controller/rig_lease.hpp"

#include <vector>

#include "controller/loop_runner.hpp"
#include "formats/rig_file.hpp"
#include "rigs/simulated_rig.hpp"

namespace palprig {

namespace {

// A pen pressing 2 N in the middle of the scene: the tick does its full work every period.
class StillPen final : public InputSource {
 public:
  TouchSample latest(double t) noexcept override { return {t, 50, 50, 2.0, true}; }
  double duration_s() const noexcept override { return 0; }
  std::string describe() const override { return "still pen"; }
};

}  // namespace

LoopMeasurement measure_loop(double rate_hz, double seconds, const RealtimeOptions& options) {
  const RigConfig rig = default_rig();
  const MapScene scene(StiffnessMap(11, 11, 100, 100, std::vector<float>(121, 0.5f)), MapSampling::nearest);
  StillPen pen;
  SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
  backend.open();
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.rate_hz = rate_hz;
  opt.duration_s = seconds;
  opt.realtime = options;
  opt.want_fifo = options.fifo;
  TickConfig config;
  // The probe measures scheduling, so it must not stop at the first burst of overruns.
  config.safety.max_consecutive_overruns = 1 << 30;
  config.safety.max_lost_time_s = 1e9;
  Rig probe_rig(backend, "the probe's simulated rig");
  RunSummary s;
  {
    RigLease lease = probe_rig.lease("the loop probe");
    s = run_loop(config, scene, pen, lease, opt);
  }
  backend.close();
  LoopMeasurement m;
  m.rate_hz = rate_hz;
  m.seconds = seconds;
  m.ticks = s.ticks;
  m.overruns = s.overruns;
  m.missed_periods = s.missed_periods;
  m.wake = s.wake_latency;
  m.tick = s.tick_time;
  // tick_time covers the tick alone; the backend calls follow it inside the same period. A sum
  // of percentiles bounds the percentile of the sum from above: the verdict errs on the safe side.
  m.tick.p999_us += s.io_time.p999_us;
  m.tick.p99_us += s.io_time.p99_us;
  m.tick.p50_us += s.io_time.p50_us;
  m.tick.max_us += s.io_time.max_us;
  m.practices = s.realtime_practices;
  m.note = s.realtime_note;
  return m;
}

}  // namespace palprig
