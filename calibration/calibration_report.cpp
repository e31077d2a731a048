#include "calibration/calibration_report.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <stdexcept>

#include "io/checked_output.hpp"

namespace palprig {

namespace {

void line_row(std::ostream& out, const std::string& who, const char* branch, const LineFit& f, const char* unit) {
  out << "  " << std::left << std::setw(9) << who << std::setw(11) << branch << std::right << std::setw(4) << f.n
      << std::fixed << std::setprecision(4) << std::setw(10) << f.slope << std::setw(11) << std::setprecision(3)
      << f.intercept << std::setw(10) << std::setprecision(4) << f.r_squared << std::setw(11) << std::setprecision(3)
      << f.residual_sd << " " << unit << "\n";
}

void branch_table(std::ostream& out, const std::string& title, const char* unit,
                  const std::vector<std::pair<std::string, const BranchFits*>>& rows) {
  if (rows.empty()) return;
  out << title << "\n";
  out << "  channel  branch        n     slope  intercept       R^2   resid SD\n";
  for (const auto& [who, f] : rows) {
    line_row(out, who, "inflation", f->inflation, unit);
    line_row(out, who, "deflation", f->deflation, unit);
    line_row(out, who, "both", f->both, unit);
  }
  out << "  gap (deflation - inflation, mean over levels) / spread between repeats:\n";
  for (const auto& [who, f] : rows) {
    out << "    " << std::left << std::setw(8) << who << std::right << std::fixed << std::setprecision(3) << f->gap
        << " " << unit << " / ";
    if (std::isfinite(f->repeat_sd_percent))
      out << std::setprecision(2) << f->repeat_sd_percent << " % of reading";
    else
      out << "n/a (one repeat)";
    out << "  (" << f->levels << " levels x " << f->repeats << " repeats)\n";
  }
}

}  // namespace

void print_fit_report(std::ostream& out, const CalibrationResult& r, const std::string& written_to) {
  out << "palprig calibrate fit: " << r.data_file << " (rig " << r.rig_id << ") -> " << written_to << "\n";
  std::vector<std::pair<std::string, const BranchFits*>> reg, sen;
  for (const auto& ch : r.channels) {
    if (ch.regulator) reg.emplace_back(std::to_string(ch.channel), &*ch.regulator);
    if (ch.response) sen.emplace_back(std::to_string(ch.channel), &*ch.response);
  }
  if (r.pooled_regulator) reg.emplace_back("all", &*r.pooled_regulator);
  if (r.pooled_response) sen.emplace_back("all", &*r.pooled_response);
  branch_table(out, "Regulator: monitored against commanded pressure, staircase (paper 002 fig. 8 layout)", "kPa", reg);
  branch_table(out, "Sensor (" + r.sensor_name + ") against commanded pressure, staircase (paper 002 fig. 8)",
               r.sensor_name.c_str(), sen);
  bool any_check = false;
  for (const auto& ch : r.channels)
    if (ch.regulator_check) {
      if (!any_check)
        out << "Regulator check (monitor line against the command, tolerance " << std::setprecision(1)
            << ch.regulator_check->tolerance_kPa << " kPa):\n";
      any_check = true;
      out << "  channel " << ch.channel << ": off by at most " << std::setprecision(2)
          << ch.regulator_check->worst_deviation_kPa << " kPa (at " << std::setprecision(1)
          << ch.regulator_check->at_command_kPa << " kPa): " << (ch.regulator_check->passed() ? "ok" : "REFUSED")
          << "\n";
    }
  out << "Hysteresis (Prandtl-Ishlinskii, Ceres; the tick applies the inverse):\n";
  for (const auto& ch : r.channels) {
    out << "  channel " << ch.channel << ": ";
    if (!ch.hysteresis) {
      out << (ch.swept ? "not fitted (--hysteresis-from none)" : "not swept") << ": identity\n";
      continue;
    }
    const HysteresisFit& h = *ch.hysteresis;
    out << "from " << to_string(ch.hysteresis_source) << ", " << h.samples << " holds; w0 " << std::setprecision(3)
        << h.model.linear_weight << ", " << (h.model.asymmetric ? "asymmetric plays" : "plays");
    for (std::size_t i = 0; i < h.model.operator_count; ++i) {
      out << " " << std::setprecision(2) << h.model.thresholds_kPa[i];
      if (h.model.asymmetric) out << "/" << h.model.falling_thresholds_kPa[i];
      out << ":" << std::setprecision(3) << h.model.weights[i];
    }
    out << (h.model.asymmetric ? " (rising/falling kPa:weight); RMS " : " (kPa:weight); RMS ") << std::setprecision(3)
        << h.rms_error_kPa << " kPa, max " << h.max_abs_error_kPa << " kPa, R^2 " << std::setprecision(5) << h.r_squared
        << "; " << h.iterations << " iterations, " << std::setprecision(3) << h.solve_seconds << " s, thresholds "
        << (h.thresholds_refined ? "refined" : "on the grid") << "\n";
    if (ch.hysteresis_selection) out << "    model chosen: " << ch.hysteresis_selection->reason << "\n";
  }
  bool any_dynamics = false;
  for (const auto& ch : r.channels) any_dynamics = any_dynamics || ch.dynamics.has_value();
  if (any_dynamics) {
    out << "Regulator dynamics (dead time + first-order lag from the step and chirp rows, Ceres; lag compensation "
        << (r.lag_compensation.enabled ? "enabled" : "off until enabled") << ", needs R^2 >= " << std::setprecision(3)
        << r.lag_compensation.min_r_squared << "):\n";
    for (const auto& ch : r.channels) {
      if (!ch.dynamics) continue;
      const DynamicsFit& d = *ch.dynamics;
      out << "  channel " << ch.channel << ": dead time " << std::setprecision(1) << d.dead_time_s * 1000 << " ms, lag "
          << d.time_constant_s * 1000 << " ms";
      if (d.directional)
        out << " filling, " << d.exhaust_time_constant_s * 1000 << " ms exhausting (one lag left "
            << std::setprecision(3) << d.one_lag_rms_residual_kPa << " kPa RMS)";
      out << "; R^2 " << std::setprecision(5) << d.r_squared;
      for (std::size_t k = 0; k < d.segments.size(); ++k)
        out << (k == 0 ? " (" : ", ") << to_string(d.segments[k].segment) << " " << d.segments[k].r_squared
            << (k + 1 == d.segments.size() ? ")" : "");
      out << "; residual RMS " << std::setprecision(3) << d.rms_residual_kPa << " kPa, max " << d.max_residual_kPa
          << " kPa; " << d.samples << " samples at " << std::setprecision(0) << d.rate_hz << " Hz; "
          << (ch.dynamics_usable() ? "usable" : "POOR FIT: compensation stays off") << "\n";
    }
  }
  out << "Actuator stress lines (stress = slope * p + intercept):\n";
  for (const auto& ch : r.channels) {
    out << "  channel " << ch.channel << ": slope " << std::setprecision(5) << ch.actuator.slope << ", intercept "
        << std::setprecision(3) << ch.actuator.intercept_kPa << " kPa";
    if (ch.stress_line)
      out << ", R^2 " << std::setprecision(4) << ch.stress_line->r_squared << " (" << ch.stress_line->n
          << " pairs from " << r.stress_file << ")";
    else
      out << " (base calibration)";
    out << "; 11.75 kPa of air -> " << std::setprecision(3) << ch.actuator.stress_kPa(11.75) << " kPa of stress\n";
  }
  if (r.force_window) {
    const auto& w = *r.force_window;
    out << "Force window (paper 003): F_min " << std::setprecision(3) << w.window.f_min_N << " N at "
        << std::setprecision(0) << w.window.diastolic_mmHg << " mmHg (" << w.presses_min << " presses, SD "
        << std::setprecision(3) << w.f_min_sd_N << " N), F_max " << w.window.f_max_N << " N at " << std::setprecision(0)
        << w.window.systolic_mmHg << " mmHg (" << w.presses_max << " presses, SD " << std::setprecision(3)
        << w.f_max_sd_N << " N)\n";
  }
  for (const auto& n : r.notes) out << "note: " << n << "\n";
  out.unsetf(std::ios::fixed);
}

nlohmann::json evaluation_json(const EvaluationResult& r, const std::array<bool, kFingerCount>& channels) {
  using nlohmann::json;
  auto metrics = [](const TrackingMetrics& m) {
    return json{{"samples", m.samples},
                {"rms_error_kPa", m.rms_error_kPa},
                {"max_abs_error_kPa", m.max_abs_error_kPa},
                {"mean_error_inflation_kPa", m.mean_error_inflation_kPa},
                {"mean_error_deflation_kPa", m.mean_error_deflation_kPa},
                {"gap_kPa", m.gap_kPa},
                {"r_squared", m.r_squared}};
  };
  json ch = json::array();
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!channels[c]) continue;
    ch.push_back({{"channel", c + 1},
                  {"uncompensated", metrics(r.uncompensated.channels[c])},
                  {"compensated", metrics(r.compensated.channels[c])},
                  {"improvement", r.improvement[c]}});
  }
  auto run_state = [&](const EvaluationRun& run) {
    json excursions = json::array();
    for (const Excursion& e : run.excursions)
      excursions.push_back({{"channel", e.channel},
                            {"start_s", e.start_s},
                            {"duration_s", e.duration_s},
                            {"worst_kPa", e.worst_kPa},
                            {"worst_at_s", e.worst_at_s}});
    return json{{"stopped", run.stopped}, {"faulted", run.faulted}, {"fault", run.fault}, {"excursions", excursions}};
  };
  return json{{"trajectory",
               {{"from_kPa", r.from_kPa},
                {"to_kPa", r.to_kPa},
                {"ramp_kPa_per_s", r.ramp_kPa_per_s},
                {"duration_s", r.duration_s},
                {"reversals", r.reversals}}},
              {"channels", ch},
              {"worst_improvement", r.worst_improvement},
              {"tolerance_kPa", r.tolerance_kPa},
              {"complete", r.complete()},
              {"uncompensated_run", run_state(r.uncompensated)},
              {"compensated_run", run_state(r.compensated)}};
}

void print_evaluation_report(std::ostream& out, const EvaluationResult& r,
                             const std::array<bool, kFingerCount>& channels) {
  out << std::fixed << std::setprecision(1) << "  trajectory: " << r.from_kPa << " .. " << r.to_kPa << " kPa at "
      << r.ramp_kPa_per_s << " kPa/s, " << std::setprecision(0) << r.duration_s << " s scored, " << r.reversals
      << " reversals\n";
  // A run that did not start (the first one stopped or faulted) has no figures: it is said, not
  // printed as zeros.
  const bool compensated_ran = !r.uncompensated.stopped && !r.uncompensated.faulted;
  out << "  channel  compensation   RMS kPa   max kPa   gap kPa        R^2\n";
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    if (!channels[c]) continue;
    for (int with = 0; with < 2; ++with) {
      const TrackingMetrics& m = with ? r.compensated.channels[c] : r.uncompensated.channels[c];
      out << "  " << std::left << std::setw(9) << c + 1 << std::setw(13) << (with ? "on" : "off") << std::right;
      if (m.samples == 0) {
        out << "  not run" << (with && !compensated_ran ? " (the run without compensation did not finish)" : "")
            << "\n";
        continue;
      }
      out << std::setprecision(3) << std::setw(10) << m.rms_error_kPa << std::setw(10) << m.max_abs_error_kPa
          << std::setw(10) << m.gap_kPa << std::setprecision(5) << std::setw(11) << m.r_squared << "\n";
    }
  }
  if (r.complete()) {
    out << "  improvement (RMS off / on):";
    for (std::size_t c = 0; c < kFingerCount; ++c)
      if (channels[c]) out << " channel " << c + 1 << " " << std::setprecision(1) << r.improvement[c] << "x";
    out << "; worst " << r.worst_improvement << "x\n";
  }
  // Excursions: the plant away from the target by more than the tolerance, with their times.
  std::size_t excursions = 0;
  for (const EvaluationRun* run : {&r.uncompensated, &r.compensated}) excursions += run->excursions.size();
  out << std::setprecision(0) << "  excursions beyond " << r.tolerance_kPa << " kPa of the target: ";
  if (excursions == 0)
    out << "none\n";
  else
    out << excursions << "\n";
  for (int with = 0; with < 2; ++with) {
    const EvaluationRun& run = with ? r.compensated : r.uncompensated;
    const std::size_t shown = std::min<std::size_t>(run.excursions.size(), 10);
    for (std::size_t i = 0; i < shown; ++i)
      out << "    " << (with ? "compensated" : "uncompensated") << " run, "
          << excursion_text(run.excursions[i], r.tolerance_kPa) << "\n";
    if (run.excursions.size() > shown)
      out << "    " << (with ? "compensated" : "uncompensated") << " run: " << run.excursions.size() - shown
          << " more (--json lists them all)\n";
  }
  for (const EvaluationRun* run : {&r.uncompensated, &r.compensated}) {
    if (run->stopped)
      out << "  note: stopped (a signal or the operator); channels vented; figures cover what was driven\n";
    if (run->faulted)
      out << "  note: fault (" << run->fault << "); channels vented; figures cover what was driven"
          << (run->fault_record.empty() ? "" : "; " + run->fault_record) << "\n";
  }
  out.unsetf(std::ios::fixed);
}

void write_evaluation_trace_csv(const std::filesystem::path& path, const EvaluationResult& r) {
  CheckedOutputFile out(path);
  out.stream()
      << "t_s,compensation,target_kPa,setpoint_1_kPa,setpoint_2_kPa,setpoint_3_kPa,monitor_1_kPa,monitor_2_kPa,"
         "monitor_3_kPa\n";
  char line[256];
  for (int with = 0; with < 2; ++with)
    for (const auto& row : (with ? r.compensated : r.uncompensated).trace) {
      std::snprintf(line, sizeof line, "%.3f,%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", row.t_s, with ? "on" : "off",
                    row.target_kPa, row.setpoint_kPa[0], row.setpoint_kPa[1], row.setpoint_kPa[2], row.monitor_kPa[0],
                    row.monitor_kPa[1], row.monitor_kPa[2]);
      out.stream() << line;
    }
  out.commit();
}

std::string utc_timestamp_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace palprig
