#include "calibration/compensation_evaluation.hpp"

#include "controller/tick_setup.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "calibration/pacer.hpp"
#include "controller/fault_recorder.hpp"
#include "controller/rig_step.hpp"
#include "core/input_error.hpp"

namespace palprig {

namespace {

// Piecewise-linear target through knots (t, p).
struct Trajectory {
  std::vector<double> t_s, p_kPa;
  double scored_from_s = 0;  // end of the rest and of the first approach
  std::size_t reversals = 0;

  double at(double t, double& slope) const noexcept {
    if (t <= t_s.front()) {
      slope = 0;
      return p_kPa.front();
    }
    const auto it = std::upper_bound(t_s.begin(), t_s.end(), t);
    if (it == t_s.end()) {
      slope = 0;
      return p_kPa.back();
    }
    const auto i = std::size_t(it - t_s.begin());
    slope = (p_kPa[i] - p_kPa[i - 1]) / (t_s[i] - t_s[i - 1]);
    return p_kPa[i - 1] + slope * (t - t_s[i - 1]);
  }
  double end_s() const noexcept { return t_s.back(); }
};

Trajectory make_trajectory(const EvaluationOptions& o, double lo, double hi) {
  Trajectory tr;
  tr.t_s = {0.0, o.rest_s};
  tr.p_kPa = {0.0, 0.0};
  tr.t_s.push_back(o.rest_s + lo / o.ramp_kPa_per_s);
  tr.p_kPa.push_back(lo);
  tr.scored_from_s = tr.t_s.back();
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> level(lo, hi);
  const double min_swing = std::min(1.0, 0.1 * (hi - lo));
  const double end = tr.scored_from_s + o.duration_s;
  int direction = 1;
  while (tr.t_s.back() < end) {
    const double cur = tr.p_kPa.back();
    // Alternate up and down so every knot is a reversal, of a random size.
    const double room = direction > 0 ? hi - cur : cur - lo;
    if (room < min_swing) {
      direction = -direction;
      continue;
    }
    const double swing = std::max(min_swing, std::abs(level(rng) - lo) / (hi - lo) * room);
    const double next = cur + direction * swing;
    tr.t_s.push_back(tr.t_s.back() + swing / o.ramp_kPa_per_s);
    tr.p_kPa.push_back(next);
    direction = -direction;
    ++tr.reversals;
  }
  return tr;
}

struct ChannelErrors {
  std::size_t n = 0, n_up = 0, n_down = 0;
  double sum_sq = 0, max_abs = 0, sum_up = 0, sum_down = 0, sum_y = 0, sum_yy = 0;
  void add(double target, double output, double slope) noexcept {
    const double e = output - target;
    ++n;
    sum_sq += e * e;
    max_abs = std::max(max_abs, std::abs(e));
    sum_y += output;
    sum_yy += output * output;
    if (slope > 0) {
      sum_up += e;
      ++n_up;
    } else if (slope < 0) {
      sum_down += e;
      ++n_down;
    }
  }
  TrackingMetrics metrics() const noexcept {
    TrackingMetrics m;
    m.samples = n;
    if (n == 0) return m;
    m.rms_error_kPa = std::sqrt(sum_sq / double(n));
    m.max_abs_error_kPa = max_abs;
    m.mean_error_inflation_kPa = n_up ? sum_up / double(n_up) : 0.0;
    m.mean_error_deflation_kPa = n_down ? sum_down / double(n_down) : 0.0;
    m.gap_kPa = m.mean_error_deflation_kPa - m.mean_error_inflation_kPa;
    const double ss_tot = sum_yy - sum_y * sum_y / double(n);
    m.r_squared = ss_tot > 0 ? 1.0 - sum_sq / ss_tot : 0.0;
    return m;
  }
};

// One run on the shared time base (the backend's clock only moves forward), through the
// controller's rig step: tick_direct (hysteresis inverse, safety stage), write, monitors.
EvaluationRun drive(RigBackend& backend, const TickConfig& config, const Trajectory& tr, const EvaluationOptions& o,
                    Pacer& pacer, std::uint64_t& k, ProgressMeter& meter, double done_before, double share) {
  EvaluationRun run;
  ExcursionWatch watch(o.tolerance_kPa);
  const double t0 = pacer.period_s() * double(k);
  const auto ticks = static_cast<std::uint64_t>(std::ceil(tr.end_s() * o.rate_hz));
  const auto record_every = std::max<std::uint64_t>(1, std::uint64_t(std::llround(o.rate_hz / o.record_hz)));
  run.trace.reserve(std::size_t(ticks / record_every + 2));
  run.scored_from_t_s = t0 + tr.scored_from_s;
  RigStep rig(config, backend, RigStepOptions{o.rate_hz, false});
  std::array<ChannelErrors, kFingerCount> acc{};
  if (rig.arm() != BackendStatus::ok) {
    run.faulted = true;
    run.fault = rig.fault().detail();
    return run;
  }
  for (std::uint64_t i = 0; i < ticks; ++i) {
    meter.update(done_before + share * double(i) / double(ticks));
    const double t = pacer.wait_for_tick(k++);
    if (o.control && o.control->stop_requested()) {
      run.stopped = true;
      break;
    }
    double slope = 0;
    const double target = tr.at(t - t0, slope);
    ChannelPressures want{};
    for (std::size_t c = 0; c < kFingerCount; ++c) want[c] = o.channels[c] ? target : 0.0;
    const StepResult& r = rig.step_direct(want, t);
    if (rig.faulted()) {
      run.faulted = true;
      run.fault = rig.fault() == FaultCode::backend_error ? rig.fault().detail()
                                                          : std::string("tick fault: ") + to_string(rig.fault());
      break;
    }
    if (t - t0 >= tr.scored_from_s)
      for (std::size_t c = 0; c < kFingerCount; ++c)
        if (o.channels[c]) {
          acc[c].add(target, r.monitor_kPa[c], slope);
          watch.add(c, t - t0, target, r.monitor_kPa[c]);
        }
    if (i % record_every == 0) run.trace.push_back({t, target, r.tick.setpoint_kPa, r.monitor_kPa});
  }
  rig.disarm();
  if (rig.faulted())
    run.fault_record =
        save_fault_record(rig.recorder(), rig.fault(), "the compensation evaluation", {},
                          o.fault_record_folder.empty() ? std::filesystem::current_path() : o.fault_record_folder);
  watch.close();
  run.excursions = watch.excursions();
  for (std::size_t c = 0; c < kFingerCount; ++c) run.channels[c] = acc[c].metrics();
  return run;
}

}  // namespace

EvaluationResult evaluate_compensation(RigLease& lease, const RigConfig& rig, const CalibrationModels& cal,
                                       const EvaluationOptions& o) {
  const double p_max = rig.safety.p_max_kPa;
  const double hi = o.to_kPa > 0 ? o.to_kPa : 0.8 * p_max;
  auto need = [](bool ok, const char* option, const std::string& expected) {
    if (!ok) throw InputError(option, "value", expected);
  };
  need(std::isfinite(o.from_kPa) && o.from_kPa >= 0, "from_kPa", "a pressure >= 0 kPa");
  need(std::isfinite(hi) && hi > o.from_kPa + 1.0, "to_kPa", "a pressure at least 1 kPa above `from_kPa`");
  std::ostringstream pmax;
  pmax << "at most the rig's p_max (" << p_max << " kPa) minus room for the compensation";
  need(hi <= 0.95 * p_max, "to_kPa", pmax.str());
  need(o.ramp_kPa_per_s > 0 && o.ramp_kPa_per_s <= 1000, "ramp_kPa_per_s", "a ramp rate in (0, 1000] kPa/s");
  need(o.duration_s > 0 && o.duration_s <= 86400, "duration_s", "a duration in (0, 86400] s");
  need(o.rest_s >= 0 && o.rest_s <= 600, "rest_s", "a rest of 0 to 600 s");
  need(o.record_hz > 0 && o.record_hz <= o.rate_hz, "record_hz", "a trace rate in (0, `rate_hz`]");
  need(o.tolerance_kPa > 0 && o.tolerance_kPa <= 1000, "tolerance_kPa", "a tolerance in (0, 1000] kPa");
  bool any = false;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!o.channels[c]) continue;
    any = true;
    if (cal.hysteresis[c].is_identity())
      throw InputError(
          cal.source, "channels[" + std::to_string(c) + "].hysteresis",
          "a hysteresis model for channel " + std::to_string(c + 1) + " to evaluate (run palprig calibrate fit first)");
  }
  need(any, "channels", "at least one channel");

  TickConfig compensated = make_tick_config(rig, cal);
  TickConfig plain = compensated;
  plain.hysteresis_model = {};  // identity: setpoint = target

  EvaluationResult result;
  result.from_kPa = o.from_kPa;
  result.to_kPa = hi;
  result.ramp_kPa_per_s = o.ramp_kPa_per_s;
  result.duration_s = o.duration_s;
  result.tolerance_kPa = o.tolerance_kPa;
  const Trajectory tr = make_trajectory(o, o.from_kPa, hi);
  result.reversals = tr.reversals;
  Pacer pacer(o.rate_hz, o.realtime);
  std::uint64_t k = 0;
  RigBackend& backend = lease.backend();
  ProgressMeter meter("evaluate", o.progress);
  meter.phase("uncompensated run", 0.0);
  result.uncompensated = drive(backend, plain, tr, o, pacer, k, meter, 0.0, 0.5);
  if (!result.uncompensated.stopped && !result.uncompensated.faulted) {
    meter.phase("compensated run", 0.5);
    result.compensated = drive(backend, compensated, tr, o, pacer, k, meter, 0.5, 0.5);
    if (!result.compensated.stopped && !result.compensated.faulted) meter.finish();
  }
  result.worst_improvement = 0;
  bool first = true;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!o.channels[c]) continue;
    const double with = result.compensated.channels[c].rms_error_kPa;
    result.improvement[c] = with > 0 ? result.uncompensated.channels[c].rms_error_kPa / with : 0.0;
    if (first || result.improvement[c] < result.worst_improvement) result.worst_improvement = result.improvement[c];
    first = false;
  }
  return result;
}

}  // namespace palprig
