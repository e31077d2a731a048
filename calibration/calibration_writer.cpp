#include "calibration/calibration_writer.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "io/checked_output.hpp"

namespace palprig {

namespace {

using nlohmann::json;

// JSON has no NaN: a figure that does not exist (one repeat: no spread) is null.
json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json line_json(const LineFit& f) {
  return json{
      {"slope", f.slope}, {"intercept", f.intercept}, {"r_squared", f.r_squared}, {"residual_sd", f.residual_sd},
      {"n", f.n},         {"x_min_kPa", f.x_min},     {"x_max_kPa", f.x_max}};
}

}  // namespace

json branch_fits_json(const BranchFits& f) {
  return json{{"inflation", line_json(f.inflation)},
              {"deflation", line_json(f.deflation)},
              {"both", line_json(f.both)},
              {"gap", f.gap},
              {"repeat_sd_percent", number_or_null(f.repeat_sd_percent)},
              {"levels", f.levels},
              {"repeats", f.repeats}};
}

json calibration_json(const CalibrationResult& r) {
  json doc;
  doc["version"] = kCalibrationFileVersion;
  doc["rig_id"] = r.rig_id;
  doc["date"] = r.date;
  std::string notes = "Fitted by palprig calibrate fit from " + r.data_file + ".";
  for (const auto& n : r.notes) notes += " " + n + ".";
  doc["notes"] = notes;
  doc["stress_model"] = {{"soft_stress_kPa", r.stress.soft_stress_kPa},
                         {"hard_stress_kPa", r.stress.hard_stress_kPa},
                         {"reference_force_N", r.stress.reference_force_N},
                         {"max_force_ratio", r.stress.max_force_ratio}};
  json channels = json::array(), fits_channels = json::array();
  for (const ChannelCalibration& ch : r.channels) {
    json c;
    c["actuator"] = {{"slope", ch.actuator.slope}, {"intercept_kPa", ch.actuator.intercept_kPa}};
    if (ch.stress_line) c["actuator"]["r_squared"] = ch.stress_line->r_squared;
    json f{{"channel", ch.channel}, {"swept", ch.swept}, {"points", ch.points}};
    if (ch.hysteresis) {
      const HysteresisFit& h = *ch.hysteresis;
      json thresholds = json::array(), weights = json::array();
      for (std::size_t i = 0; i < h.model.operator_count; ++i) {
        thresholds.push_back(h.model.thresholds_kPa[i]);
        weights.push_back(h.model.weights[i]);
      }
      c["hysteresis"] = {{"linear_weight", h.model.linear_weight},
                         {"thresholds_kPa", thresholds},
                         {"weights", weights},
                         {"rms_error_kPa", h.rms_error_kPa},
                         {"r_squared", h.r_squared}};
      if (h.model.asymmetric) {
        json falling = json::array();
        for (std::size_t i = 0; i < h.model.operator_count; ++i) falling.push_back(h.model.falling_thresholds_kPa[i]);
        c["hysteresis"]["falling_thresholds_kPa"] = falling;
      }
      f["hysteresis_fit"] = {{"source", to_string(ch.hysteresis_source)},
                             {"samples", h.samples},
                             {"max_abs_error_kPa", h.max_abs_error_kPa},
                             {"grid_rms_error_kPa", h.stage1_rms_error_kPa},
                             {"thresholds_refined", h.thresholds_refined},
                             {"converged", h.converged},
                             {"iterations", h.iterations},
                             {"solve_seconds", h.solve_seconds},
                             {"solver", h.solver_report},
                             {"model", h.model.asymmetric ? "asymmetric" : "symmetric"}};
      if (ch.hysteresis_selection) {
        const HysteresisSelection& s = *ch.hysteresis_selection;
        json sel{{"compared", s.compared}, {"reason", s.reason}};
        if (s.compared) {
          sel["folds"] = s.folds;
          sel["held_out_samples"] = s.samples;
          sel["symmetric_held_out_rms_kPa"] = s.symmetric.rms_kPa;
          sel["symmetric_held_out_max_kPa"] = s.symmetric.max_kPa;
          sel["asymmetric_held_out_rms_kPa"] = s.asymmetric.rms_kPa;
          sel["asymmetric_held_out_max_kPa"] = s.asymmetric.max_kPa;
          sel["min_gain"] = s.min_gain;
          sel["min_gain_kPa"] = s.min_gain_kPa;
        }
        f["hysteresis_fit"]["selection"] = sel;
      }
    }
    if (ch.dynamics) {
      const DynamicsFit& d = *ch.dynamics;
      json segments = json::array();
      for (const auto& g : d.segments)
        segments.push_back({{"segment", to_string(g.segment)},
                            {"samples", g.samples},
                            {"r_squared", g.r_squared},
                            {"rms_residual_kPa", g.rms_residual_kPa},
                            {"max_residual_kPa", g.max_residual_kPa}});
      c["dynamics"] = {{"dead_time_s", d.dead_time_s},
                       {"time_constant_s", d.time_constant_s},
                       {"r_squared", d.r_squared},
                       {"rms_residual_kPa", d.rms_residual_kPa},
                       {"max_residual_kPa", d.max_residual_kPa},
                       {"samples", d.samples},
                       {"rate_hz", d.rate_hz},
                       {"segments", segments}};
      if (d.directional) {
        c["dynamics"]["exhaust_time_constant_s"] = d.exhaust_time_constant_s;
        c["dynamics"]["one_lag_rms_residual_kPa"] = d.one_lag_rms_residual_kPa;
      }
      if (d.pressure_dependent) {
        c["dynamics"]["exhaust_lag_factor_at_0"] = d.exhaust_lag_factor_at_0;
        c["dynamics"]["exhaust_lag_scale_kPa"] = d.exhaust_lag_scale_kPa;
      }
      f["dynamics_fit"] = {{"grid_rms_residual_kPa", d.grid_rms_residual_kPa},
                           {"converged", d.converged},
                           {"iterations", d.iterations},
                           {"solve_seconds", d.solve_seconds},
                           {"usable", ch.dynamics_usable()},
                           {"solver", d.solver_report}};
      if (d.exhaust_lag_tried)
        f["dynamics_fit"]["exhaust_lag_near_0"] = {
            {"kept", d.pressure_dependent},
            {"factor_at_0", d.exhaust_lag_fitted_factor_at_0},
            {"scale_kPa", d.exhaust_lag_fitted_scale_kPa},
            {"held_out_rms_kPa", d.pressure_held_out_rms_kPa},
            {"one_exhaust_lag_held_out_rms_kPa", d.directional_held_out_rms_kPa}};
    }
    if (ch.regulator) f["regulator"] = branch_fits_json(*ch.regulator);
    if (ch.regulator_check)
      f["regulator_check"] = {{"worst_deviation_kPa", ch.regulator_check->worst_deviation_kPa},
                              {"at_command_kPa", ch.regulator_check->at_command_kPa},
                              {"tolerance_kPa", ch.regulator_check->tolerance_kPa},
                              {"passed", ch.regulator_check->passed()}};
    if (ch.response) f["sensor"] = branch_fits_json(*ch.response);
    if (ch.stress_line) f["stress_line"] = line_json(*ch.stress_line);
    channels.push_back(c);
    fits_channels.push_back(f);
  }
  doc["channels"] = channels;
  bool any_dynamics = false;
  for (const ChannelCalibration& ch : r.channels) any_dynamics = any_dynamics || ch.dynamics.has_value();
  if (any_dynamics || r.lag_compensation.enabled)
    doc["lag_compensation"] = {{"enabled", r.lag_compensation.enabled},
                               {"max_lead_kPa", r.lag_compensation.max_lead_kPa},
                               {"min_r_squared", r.lag_compensation.min_r_squared},
                               {"anticipate_edges", r.lag_compensation.anticipate_edges}};
  json fits{{"data", r.data_file},
            {"sensor", r.sensor_name.empty() ? json(nullptr) : json(r.sensor_name)},
            {"channels", fits_channels}};
  if (r.pooled_regulator) fits["all_channels"]["regulator"] = branch_fits_json(*r.pooled_regulator);
  if (r.pooled_response) fits["all_channels"]["sensor"] = branch_fits_json(*r.pooled_response);
  if (!r.stress_file.empty()) fits["stress_pairs"] = r.stress_file;
  doc["fits"] = fits;
  if (r.force_window) {
    const ForceWindowFit& w = *r.force_window;
    doc["force_window"] = {{"diastolic_mmHg", w.window.diastolic_mmHg},
                           {"systolic_mmHg", w.window.systolic_mmHg},
                           {"f_min_N", w.window.f_min_N},
                           {"f_max_N", w.window.f_max_N},
                           {"f_min_sd_N", w.f_min_sd_N},
                           {"f_max_sd_N", w.f_max_sd_N},
                           {"presses_min", w.presses_min},
                           {"presses_max", w.presses_max}};
  }
  return doc;
}

CalibrationModels write_calibration_file(const std::filesystem::path& path, const json& document) {
  // Read back through the controller's own loader before it replaces anything: a file the
  // controller would refuse is never put in place.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw OutputError(path, "a calibration file must be a regular file (this is a device, FIFO or folder)");
  CalibrationModels loaded;
  CheckedOutputFile out(path);
  out.write(document.dump(2) + "\n");
  out.commit([&](const std::filesystem::path& written) { loaded = load_calibration_file(written); });
  loaded.source = path.string();
  return loaded;
}

}  // namespace palprig
