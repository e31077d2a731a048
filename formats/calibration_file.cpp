#include "formats/calibration_file.hpp"

#include <cmath>
#include <sstream>

#include "formats/json_file.hpp"

namespace palprig {

namespace {

constexpr double kMaxFitFigure = 1e9;    // any figure of the "fits" tables
constexpr double kMaxFitPressure = 1e4;  // kPa: 100 bar, beyond any proportional regulator

std::string plain(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// The fit tables calibration writes ("fits"): every straight-line fit (an object with "slope"
// and "intercept") rises (a falling regulator or stress line is a damaged table), and its
// quality numbers are what they can be. Walked with its field path for the refusal.
void check_fit_tables(const nlohmann::json& v, const std::string& file, const std::string& where, int depth = 0) {
  if (depth > 16) return;  // the JSON reader bounds nesting; the tables are 4 levels deep
  // Every figure of the tables is a count, a time, a pressure or a quality of fit: none is
  // beyond 1e9 in any unit palprig writes (a calibration with a pressure of 1.8e19 kPa read as
  // valid before).
  if (v.is_number() && !(std::fabs(v.get<double>()) <= kMaxFitFigure))
    throw InputError(file, where, "a figure within -1e+09..1e+09, got " + json_excerpt(v));
  if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i)
      check_fit_tables(v[i], file, where + "[" + std::to_string(i) + "]", depth + 1);
    return;
  }
  if (!v.is_object()) return;
  if (v.contains("slope") || v.contains("intercept")) {
    auto number = [&](const char* key, double lo, double hi, const std::string& expected) {
      if (!v.contains(key)) return;
      const auto& x = v.at(key);
      if (x.is_null()) return;  // a figure that does not exist (JSON has no NaN)
      if (!x.is_number() || !(x.get<double>() >= lo && x.get<double>() <= hi))
        throw InputError(file, where + "." + key, expected + ", got " + json_excerpt(x));
    };
    if (!v.contains("slope")) throw InputError(file, where + ".slope", "a fit line's slope beside its intercept");
    number(
        "slope", 1e-9, kMaxActuatorSlope,
        "a rising fit line: a slope in 1e-09.." + plain(kMaxActuatorSlope) + " (a flat or falling fit is degenerate)");
    number("intercept", -1e6, 1e6, "an intercept in -1e+06..1e+06 kPa");
    number("r_squared", -1e9, 1, "an R^2 of at most 1");
    number("residual_sd", 0, 1e6, "a residual sd in 0..1e+06");
    number("n", 0, 1e9, "a count of points in 0..1e9");
    // The commanded pressures the line was fitted over: a regulator's range.
    number("x_min_kPa", -kMaxFitPressure, kMaxFitPressure, "a pressure in -1e+04..1e+04 kPa");
    number("x_max_kPa", -kMaxFitPressure, kMaxFitPressure, "a pressure in -1e+04..1e+04 kPa");
    if (v.contains("x_min_kPa") && v.contains("x_max_kPa") && v.at("x_min_kPa").is_number() &&
        v.at("x_max_kPa").is_number() && v.at("x_min_kPa").get<double>() > v.at("x_max_kPa").get<double>())
      throw InputError(file, where + ".x_max_kPa",
                       "a pressure at or above x_min_kPa, got " + json_excerpt(v.at("x_max_kPa")));
  }
  for (auto it = v.begin(); it != v.end(); ++it) check_fit_tables(it.value(), file, where + "." + it.key(), depth + 1);
}

}  // namespace

CalibrationModels load_calibration_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  const nlohmann::json doc = read_json_file(path);
  JsonObject root(doc, file, "");
  root.require_version(kCalibrationFileVersion);
  CalibrationModels cal;
  cal.source = file;
  cal.rig_id = root.string("rig_id");
  if (root.has("date")) (void)root.string("date");
  if (root.has("stress_model")) {
    const JsonObject s = root.object("stress_model");
    cal.stress.soft_stress_kPa = s.number("soft_stress_kPa", 0, 1000);
    cal.stress.hard_stress_kPa = s.number("hard_stress_kPa", 0, 1000);
    cal.stress.reference_force_N = s.number("reference_force_N", 1e-3, 100);
    cal.stress.max_force_ratio = s.number_or("max_force_ratio", cal.stress.max_force_ratio, 0.1, 100);
    if (!(cal.stress.hard_stress_kPa > cal.stress.soft_stress_kPa))
      s.fail("hard_stress_kPa", "a hard-nodule stress above the soft-tissue stress");
    s.refuse_unknown();
  }
  const auto channels = root.objects("channels");
  if (channels.size() != kFingerCount)
    root.fail("channels",
              "exactly " + std::to_string(kFingerCount) + " channels, got " + std::to_string(channels.size()));
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const JsonObject& ch = channels[i];
    const JsonObject a = ch.object("actuator");
    cal.actuators[i].slope = a.number("slope", -1e6, 1e6);
    cal.actuators[i].intercept_kPa = a.number("intercept_kPa", -1e6, 1e6);
    if (!(cal.actuators[i].slope > 1e-9))
      a.fail("slope", "a positive stress-per-pressure slope (a flat or falling fit is degenerate)");
    if (cal.actuators[i].slope > kMaxActuatorSlope)
      a.fail("slope", "a stress-per-pressure slope of at most " + plain(kMaxActuatorSlope) + " kPa per kPa, got " +
                          plain(cal.actuators[i].slope));
    // stress = slope * p + intercept: with the intercept at or above the stress model's hard
    // stress, every target pressure is 0 kPa (the rig renders nothing); far below it, soft
    // tissue alone asks for more than any regulator gives.
    const double hard = cal.stress.hard_stress_kPa;
    if (!(cal.actuators[i].intercept_kPa >= kMinActuatorIntercept_kPa && cal.actuators[i].intercept_kPa < hard))
      a.fail("intercept_kPa", "the stress of the uninflated actuator in " + plain(kMinActuatorIntercept_kPa) + ".." +
                                  plain(hard) +
                                  " kPa (below the stress model's hard_stress_kPa, or every target is 0 kPa), got " +
                                  plain(cal.actuators[i].intercept_kPa));
    if (a.has("r_squared")) (void)a.number("r_squared", -1e9, 1);
    a.refuse_unknown();
    if (ch.has("hysteresis")) {
      const JsonObject h = ch.object("hysteresis");
      PrandtlIshlinskii& pi = cal.hysteresis[i];
      pi.linear_weight = h.number("linear_weight", -1e6, 1e6);
      const auto r = h.numbers("thresholds_kPa", -1e6, 1e6);
      const auto w = h.numbers("weights", -1e6, 1e6);
      if (r.size() != w.size())
        h.fail("weights", "as many weights as thresholds_kPa (" + std::to_string(r.size()) + ")");
      if (r.size() > kMaxPlayOperators)
        h.fail("thresholds_kPa", "at most " + std::to_string(kMaxPlayOperators) + " play operators");
      pi.operator_count = r.size();
      for (std::size_t k = 0; k < r.size(); ++k) {
        pi.thresholds_kPa[k] = r[k];
        pi.weights[k] = w[k];
      }
      // An asymmetric model (calibrate fit chose it): thresholds_kPa are then the rising ones and
      // these the falling ones. A file without them is the symmetric model, as files always were.
      if (h.has("falling_thresholds_kPa")) {
        const auto f = h.numbers("falling_thresholds_kPa", -1e6, 1e6);
        if (f.size() != r.size())
          h.fail("falling_thresholds_kPa",
                 "as many falling thresholds as thresholds_kPa (" + std::to_string(r.size()) + ")");
        pi.asymmetric = true;
        for (std::size_t k = 0; k < f.size(); ++k) pi.falling_thresholds_kPa[k] = f[k];
      }
      if (!pi.valid())
        h.fail("weights", pi.asymmetric ? "an invertible model: linear_weight > 0, weights >= 0, thresholds > 0"
                                        : "an invertible model: linear_weight > 0, weights >= 0, thresholds > 0 and "
                                          "increasing");
      // A regulator's output follows its command about one to one; a gain far from it is a
      // degenerate fit (or a model in other units) that would drive the inverse wild.
      double gain = pi.linear_weight;
      for (std::size_t k = 0; k < pi.operator_count; ++k) gain += pi.weights[k];
      if (!(gain >= 0.2 && gain <= 5.0))
        h.fail("weights",
               "a model of gain near 1 (linear_weight + sum of weights in 0.2..5), got " + std::to_string(gain));
      // Fit-quality fields written by calibration are informative here.
      for (const char* k : {"rms_error_kPa", "r_squared"})
        if (h.has(k)) (void)h.number(k, -1e9, 1e9);
      h.refuse_unknown();
    }
    if (ch.has("dynamics")) {
      // The regulator's identified dynamics (calibrate fit from step and chirp rows): a dead time
      // and a first-order lag a real regulator can have, and how well they fit.
      const JsonObject d = ch.object("dynamics");
      RegulatorDynamics dyn;
      dyn.dead_time_s = d.number("dead_time_s", 0, 0.5);
      dyn.time_constant_s = d.number("time_constant_s", 0.0005, 2);
      dyn.r_squared = d.number("r_squared", -1e9, 1);
      dyn.rms_residual_kPa = d.number_or("rms_residual_kPa", 0, 0, 1e6);
      dyn.max_residual_kPa = d.number_or("max_residual_kPa", 0, 0, 1e6);
      dyn.samples = static_cast<std::size_t>(d.integer_or("samples", 0, 0, 1000000000));
      dyn.rate_hz = d.number_or("rate_hz", 0, 0, 100000);
      // Separate fill and exhaust lags (absent: one lag, as every earlier file).
      if (d.has("exhaust_time_constant_s"))
        dyn.exhaust_time_constant_s = d.number("exhaust_time_constant_s", 0.0005, 2);
      if (d.has("segments")) (void)d.raw("segments");  // per-segment R^2 and residuals, for people
      if (d.has("one_lag_rms_residual_kPa")) (void)d.number("one_lag_rms_residual_kPa", 0, 1e6);
      d.refuse_unknown();
      cal.dynamics[i] = dyn;
    }
    ch.refuse_unknown();
  }
  // Sections written by calibration for people and later tools (fit tables, force window)
  // are kept in the file; the tick does not need them, but a fit table that is physically
  // impossible says the file is damaged or edited by hand.
  if (root.has("fits")) check_fit_tables(root.raw("fits"), file, root.path("fits"));
  (void)root.has("notes");
  if (root.has("force_window")) {
    const JsonObject f = root.object("force_window");
    MeasuredForceWindow w;
    w.f_min_N = f.number("f_min_N", 0, 1000);
    w.f_max_N = f.number("f_max_N", 0, 1000);
    w.diastolic_mmHg = f.number_or("diastolic_mmHg", w.diastolic_mmHg, 1, 400);
    w.systolic_mmHg = f.number_or("systolic_mmHg", w.systolic_mmHg, 1, 400);
    if (!(w.f_max_N > w.f_min_N)) f.fail("f_max_N", "a force above f_min_N (the systolic press above the diastolic)");
    if (!(w.systolic_mmHg > w.diastolic_mmHg)) f.fail("systolic_mmHg", "a reference above diastolic_mmHg");
    // How the window was measured, kept for people: spread and number of presses.
    for (const char* k : {"f_min_sd_N", "f_max_sd_N"}) (void)f.number_or(k, 0, 0, 1000);
    for (const char* k : {"presses_min", "presses_max"}) (void)f.integer_or(k, 0, 0, 1000000);
    f.refuse_unknown();
    cal.force_window = w;
  }
  if (root.has("lag_compensation")) {
    const JsonObject l = root.object("lag_compensation");
    LagCompensationChoice& c = cal.lag_compensation;
    c.enabled = l.boolean_or("enabled", c.enabled);
    c.max_lead_kPa = l.number_or("max_lead_kPa", c.max_lead_kPa, 0, 100);
    c.min_r_squared = l.number_or("min_r_squared", c.min_r_squared, kLowestMinDynamicsRSquared, 1);
    c.anticipate_edges = l.boolean_or("anticipate_edges", c.anticipate_edges);
    if (c.enabled) {
      bool any = false;
      for (const auto& d : cal.dynamics) any = any || d.has_value();
      if (!any)
        l.fail("enabled",
               "identified regulator dynamics (channels[].dynamics, from calibrate sweep --excitation "
               "...,step,chirp and calibrate fit) before lag compensation is enabled");
    }
    l.refuse_unknown();
  }
  root.refuse_unknown();
  return cal;
}

void check_calibration_matches(const CalibrationModels& cal, const std::string& rig_id, const std::string& rig_source) {
  if (cal.rig_id != "*" && cal.rig_id != rig_id)
    throw InputError(
        cal.source, "rig_id",
        "the id of the rig in use (\"" + rig_id + "\" from " + rig_source + "), got \"" + cal.rig_id + "\"");
}

}  // namespace palprig
