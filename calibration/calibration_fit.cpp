#include "calibration/calibration_fit.hpp"

#include <cmath>
#include <sstream>

#include "core/input_error.hpp"

namespace palprig {

const char* to_string(HysteresisSource s) noexcept {
  switch (s) {
    case HysteresisSource::monitor: return "monitor";
    case HysteresisSource::sensor: return "sensor";
    case HysteresisSource::none: return "none";
  }
  return "?";
}

const char* to_string(HysteresisModelClass c) noexcept {
  switch (c) {
    case HysteresisModelClass::automatic: return "auto";
    case HysteresisModelClass::symmetric: return "symmetric";
    case HysteresisModelClass::asymmetric: return "asymmetric";
  }
  return "?";
}

namespace {

std::vector<HoldPoint> staircase_of(const std::vector<HoldPoint>& pts) {
  std::vector<HoldPoint> out;
  for (const auto& p : pts)
    if (p.segment == SweepSegment::staircase && p.branch != SweepBranch::none) out.push_back(p);
  return out;
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace

bool ChannelCalibration::dynamics_usable() const noexcept { return dynamics && dynamics->r_squared >= min_r_squared; }

CalibrationResult fit_calibration(const SweepData& data, const CalibrationFitOptions& o) {
  const std::string& file = data.file;
  CalibrationResult out;
  out.data_file = file;
  out.date = o.date;
  out.sensor_name = data.info.sensor_name;
  out.rig_id = o.rig_id.empty() ? data.info.rig_id : o.rig_id;
  if (out.rig_id.empty())
    throw InputError(file, "rig_id", "the rig the data came from (a \"# rig_id: ...\" line, or `rig_id`)");
  if (out.rig_id == "*")
    throw InputError(file, "rig_id", "a real rig id: a fitted calibration belongs to one rig, not \"*\"");
  if (data.points.empty() && data.dynamics.empty())
    throw InputError(file, "rows", "settled readings (every hold of the file is unsettled or empty)");
  if (data.unsettled_holds)
    out.notes.push_back(std::to_string(data.unsettled_holds) + " holds never settled and were left out");

  const HysteresisSource source =
      o.hysteresis_from.value_or(data.has_monitor ? HysteresisSource::monitor : HysteresisSource::none);
  if (source == HysteresisSource::monitor && !data.has_monitor)
    throw InputError(file, "monitor_kPa",
                     "monitor readings to fit the hysteresis on (or `hysteresis_from` sensor|none)");
  if (source == HysteresisSource::sensor && !data.has_sensor)
    throw InputError(file, "sensor", "sensor readings to fit the hysteresis on (or `hysteresis_from` monitor|none)");

  out.stress = o.base.stress;
  out.stress_file = o.stress_file;
  out.force_file = o.force_file;
  out.force_window = o.force_window;
  out.lag_compensation = o.lag_compensation;
  bool any_dynamics = false;
  std::vector<HoldPoint> pooled;
  int swept_channels = 0, fitted = 0;
  for (int c = 1; c <= int(kFingerCount); ++c)
    swept_channels += !data.channel_points(c).empty() || !data.channel_dynamics(c).empty() ? 1 : 0;
  // Silent for the first 2 s: most fits are over by then (the Ceres stages take longer on long
  // recordings with step and chirp rows).
  ProgressMeter meter("fit", o.progress, 5.0, 2.0);
  for (int c = 1; c <= int(kFingerCount); ++c) {
    ChannelCalibration& ch = out.channels[std::size_t(c - 1)];
    ch.channel = c;
    ch.actuator = o.base.actuators[std::size_t(c - 1)];
    bool has_pairs = false;
    for (const auto& q : o.stress_pairs) has_pairs = has_pairs || q.channel == 0 || q.channel == c;
    if (!o.stress_pairs.empty() && !has_pairs)
      out.notes.push_back("channel " + std::to_string(c) + " has no stress pairs: its actuator line is the base's");
    if (has_pairs) {
      const ActuatorFit a = fit_actuator_stress(o.stress_pairs, c, o.stress_file);
      ch.actuator = a.model;
      ch.stress_line = a.line;
    }
    const std::vector<HoldPoint> pts = data.channel_points(c);
    const std::vector<DynamicsSample> dynamics = data.channel_dynamics(c);
    ch.points = pts.size();
    ch.swept = !pts.empty() || !dynamics.empty();
    ch.min_r_squared = o.lag_compensation.min_r_squared;
    if (!ch.swept) {
      out.notes.push_back("channel " + std::to_string(c) + " was not swept: no hysteresis model (identity)");
      continue;
    }
    const std::string name = "channel " + std::to_string(c);
    ++fitted;
    meter.phase(name + " (" + std::to_string(fitted) + " of " + std::to_string(swept_channels) +
                    "): branch lines, hysteresis model, dynamics",
                double(fitted - 1) / double(std::max(swept_channels, 1)));
    // The regulator's dynamics, through the hysteresis model fitted on the monitor (so the lag
    // is fitted on what the play leaves of the command), once that model exists.
    auto fit_channel_dynamics = [&] {
      if (dynamics.empty()) return;
      any_dynamics = true;
      const PrandtlIshlinskii* h =
          ch.hysteresis && ch.hysteresis_source == HysteresisSource::monitor ? &ch.hysteresis->model : nullptr;
      ch.dynamics = fit_dynamics(dynamics, h, o.dynamics, file, name + " dynamics");
      if (!ch.dynamics->converged)
        out.notes.push_back(name + ": the dynamics fit did not converge in Ceres (" + ch.dynamics->solver_report +
                            "); the best grid point is kept");
      if (!ch.dynamics_usable())
        out.notes.push_back(name + ": its dynamics fit with R^2 " + fixed(ch.dynamics->r_squared, 4) + ", below " +
                            fixed(o.lag_compensation.min_r_squared, 4) + ": lag compensation stays off on it");
    };
    if (pts.empty()) {  // step and chirp rows only: no quasi-static points, no hysteresis model
      fit_channel_dynamics();
      continue;
    }
    const std::vector<HoldPoint> stairs = staircase_of(pts);
    if (data.has_monitor) check_response_moves(pts, MeasuredSignal::monitor, file, name + " monitor");
    if (data.has_sensor) check_response_moves(pts, MeasuredSignal::sensor, file, name + " sensor");
    if (!stairs.empty()) {
      if (data.has_monitor) {
        check_staircase_monotone(stairs, MeasuredSignal::monitor, o.monotone_tolerance, file, name);
        ch.regulator = fit_branches(stairs, MeasuredSignal::monitor, file, name + " regulator");
        ch.regulator_check = check_regulator(ch.regulator->both, o.regulator_tolerance_kPa);
        if (!ch.regulator_check->passed()) {
          const LineFit& l = ch.regulator->both;
          throw InputError(file, name + " regulator",
                           "a monitor within " + fixed(o.regulator_tolerance_kPa, 1) +
                               " kPa of the command; its line " + "monitor = " + fixed(l.slope, 3) + " * command " +
                               (l.intercept < 0 ? "- " : "+ ") + fixed(std::abs(l.intercept), 2) + " kPa is off by " +
                               fixed(ch.regulator_check->worst_deviation_kPa, 2) + " kPa at " +
                               fixed(ch.regulator_check->at_command_kPa, 1) +
                               " kPa (check the regulator's supply, range and scaling, or raise "
                               "`regulator_tolerance_kPa`)");
        }
      }
      if (data.has_sensor) {
        check_staircase_monotone(stairs, MeasuredSignal::sensor, o.monotone_tolerance, file, name);
        ch.response = fit_branches(stairs, MeasuredSignal::sensor, file, name + " sensor");
      }
      pooled.insert(pooled.end(), stairs.begin(), stairs.end());
    }

    ch.hysteresis_source = source;
    if (source == HysteresisSource::none || pts.empty()) {
      fit_channel_dynamics();
      continue;
    }
    std::vector<double> x, y;
    for (const auto& p : pts) {
      x.push_back(p.command_kPa);
      y.push_back(source == HysteresisSource::monitor ? p.monitor_kPa : p.sensor);
    }
    if (source == HysteresisSource::sensor) {
      // Sensor readings become the pressure that would give them: zero at the first vented
      // reading (the record starts at rest, as paper 002 zeroed its caliper on the uninflated
      // actuator), scaled by the sensor's sensitivity through that zero. A line's intercept
      // would put an offset in the data that a PI model cannot hold.
      double zero = 0;
      for (const auto& p : pts)
        if (p.segment == SweepSegment::vent && std::isfinite(p.sensor)) {
          zero = p.sensor;
          break;
        }
      double sxy = 0, sxx = 0;
      for (const auto& p : stairs) {
        sxy += (p.sensor - zero) * p.command_kPa;
        sxx += p.command_kPa * p.command_kPa;
      }
      const double per_kPa = sxx > 0 ? sxy / sxx : 0.0;
      if (!(std::abs(per_kPa) > 0) || !std::isfinite(per_kPa))
        throw InputError(file, name + " sensor", "a staircase over which the sensor moves, to scale it to pressure");
      for (double& v : y) v = (v - zero) / per_kPa;
    }
    for (std::size_t k = 0; k < y.size(); ++k)
      if (!std::isfinite(y[k]))
        throw InputError(file, "line " + std::to_string(pts[k].line),
                         std::string("a ") + to_string(source) + " reading for the hysteresis fit of " + name);
    HysteresisFitOptions hysteresis = o.hysteresis;
    if (o.operators_from_data) {
      // 1 + 2n parameters need 4 samples each: the default staircase (paper 002's, 66 holds on
      // a 60 kPa rig) supports 7 operators, the richer excitations 8.
      const std::size_t supported = x.size() >= 12 ? (x.size() / 4 - 1) / 2 : 1;
      if (supported < hysteresis.operator_count) {
        out.notes.push_back(name + ": " + std::to_string(supported) + " play operators, the most its " +
                            std::to_string(x.size()) + " quasi-static samples support (" +
                            std::to_string(hysteresis.operator_count) + " need " +
                            std::to_string(4 * (1 + 2 * hysteresis.operator_count)) +
                            "; record more holds with --excitation staircase,random,sine, or set --operators)");
        hysteresis.operator_count = supported;
      }
    }
    // The model class: by held-out error over the runs (each from a vent), or as asked.
    if (o.hysteresis_model == HysteresisModelClass::automatic) {
      std::vector<std::size_t> run_starts;
      for (std::size_t k = 0; k < pts.size(); ++k)
        if (pts[k].segment == SweepSegment::vent) run_starts.push_back(k);
      ch.hysteresis_selection = select_hysteresis_model(x, y, run_starts, hysteresis);
      hysteresis.asymmetric = ch.hysteresis_selection->asymmetric_chosen;
    } else {
      hysteresis.asymmetric = o.hysteresis_model == HysteresisModelClass::asymmetric;
    }
    if (hysteresis.asymmetric) {
      // 1 + 3n parameters, 4 samples each.
      const std::size_t supported = x.size() >= 16 ? (x.size() / 4 - 1) / 3 : 1;
      if (supported < hysteresis.operator_count) {
        out.notes.push_back(name + ": " + std::to_string(supported) + " asymmetric play operators, the most its " +
                            std::to_string(x.size()) + " quasi-static samples support");
        hysteresis.operator_count = supported;
      }
    }
    HysteresisFit fit = fit_hysteresis(x, y, hysteresis, file, name + " hysteresis");
    if (!fit.converged)
      throw InputError(file, name + " hysteresis",
                       "a fit Ceres converges on; it did not (" + fit.solver_report +
                           "). Record more holds (`excitation` staircase,random,sine), use fewer operators "
                           "(`operator_count`), or fix the thresholds (`fixed_thresholds`)");
    ch.hysteresis = fit;
    fit_channel_dynamics();
  }
  if (!any_dynamics)
    out.notes.push_back(
        "no step or chirp rows: the regulators' dynamics were not identified (lag compensation needs "
        "calibrate sweep --excitation ...,step,chirp)");
  if (o.lag_compensation.enabled && !any_dynamics)
    throw InputError(file, "lag_compensation",
                     "step and chirp rows to identify the regulators' dynamics before lag "
                     "compensation is enabled (calibrate sweep --excitation ...,step,chirp)");
  if (pooled.empty() && data.has_monitor)
    out.notes.push_back("no staircase rows: the branch tables of paper 002 fig. 8 were not computed");
  if (!pooled.empty()) {
    bool several = false;
    for (const auto& p : pooled) several = several || p.channel != pooled.front().channel;
    if (several) {
      if (data.has_monitor)
        out.pooled_regulator = fit_branches(pooled, MeasuredSignal::monitor, file, "all channels regulator");
      if (data.has_sensor)
        out.pooled_response = fit_branches(pooled, MeasuredSignal::sensor, file, "all channels sensor");
    }
  }
  if (o.stress_pairs.empty()) {
    // The base is paper 002's built-in models unless --base or --stress-model named a file.
    const bool built_in = o.base.source == CalibrationModels{}.source;
    out.notes.push_back(built_in ? "actuator stress lines kept from paper 002's regression (no --stress pairs given)"
                                 : "actuator stress lines kept from " + o.base.source + " (no --stress pairs given)");
  }
  meter.finish();
  return out;
}

}  // namespace palprig
