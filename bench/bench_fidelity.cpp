// Over 400 lines: both plants, their calibration by the recipe and the report in one program.
// Haptic fidelity: does a fingertip get the pressure the model asks for while the pen moves?
// RMS(monitor - target) over the demo pass (the bundled phantom, the recorded pen pass, fingers 1
// and 2, every tick the pen pressed), with and without lag compensation, on
//   - the shipped simulated rig with its shipped calibration (data/rigs/simulated.json,
//     data/calibration/sim-default.json), and
//   - a heavier plant: hysteresis x1.7, dead time and lag x1.4, calibrated here by the documented
//     recipe (palprig calibrate sweep --excitation staircase,random,sine,step,chirp, then
//     calibrate fit; the palprig command itself, as a user types it), and
//   - the shipped asymmetric regulator (data/rigs/simulated_asymmetric.json: 3 kPa play rising,
//     1 kPa falling, separate fill and exhaust lags, a saturating gain), calibrated the same way.
// Goals (the goal column of the README's fidelity table): RMS <= 0.25 kPa on the shipped
// simulated rig and <= 0.5 kPa on every other plant, monitor/target over tumors >= 0.97, no
// setpoint above p_max, no overshoot over soft tissue above 0.5 kPa.
//
//   build/bin/bench_fidelity                        the table (Markdown), runs in a few seconds
//   build/bin/bench_fidelity --json                 the same as JSON
//   build/bin/bench_fidelity --figure FILE.png      also the figure: target, monitor without and
//                                                   with compensation over one tumor crossing
//   build/bin/bench_fidelity --telemetry RUN.csv [--label TEXT]
//                                                   the same measures of a run's telemetry (the
//                                                   Modbus peer in real time: bench/fidelity_modbus.sh)
//
// Measures, per tick of fingers 1 and 2 while the pen pressed (in contact), target and monitor
// from the telemetry record:
//   RMS      sqrt(mean((monitor - target)^2))
//   tumors   sum(monitor) / sum(target) over finger-ticks within a tumor's radius (the demo's regions)
//   soft     the largest monitor - target over soft tissue (further than radius + 8 mm from every
//            tumor, as the demo's table), and the same less the monitor's noise (3 sd)
//   setpoint the largest setpoint sent, against p_max
// The simulated plant is seeded, so the figures do not depend on the machine.
// Over 400 lines: the pass, its meter, the heavier plant's calibration recipe and the Modbus run
// are one measurement, printed as one table.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <boost/math/distributions/normal.hpp>
#include <nlohmann/json.hpp>

#include "calibration/tracking_bound.hpp"
#include "core/error.hpp"
#include "controller/run_setup.hpp"
#include "formats/scene_file.hpp"

#include "charts/chart_png.hpp"

using namespace palprig;
namespace fs = std::filesystem;

namespace {

constexpr double kSoftMargin_mm = 8.0;  // the demo's table: soft tissue is this far from every tumor
constexpr std::size_t kFingers = 2;     // fingers 1 and 2 (the pass runs finger 3 off the phantom)

struct Metrics {
  std::size_t n = 0, n_tumor = 0, n_soft = 0;
  double sum_sq = 0, tumor_monitor = 0, tumor_target = 0;
  double soft_overshoot_kPa = -1e300;
  double max_setpoint_kPa = 0;
  double rms() const { return n ? std::sqrt(sum_sq / double(n)) : 0; }
  double tumor_ratio() const { return tumor_target > 0 ? tumor_monitor / tumor_target : 0; }
};

// One tick's record, as the telemetry has it.
struct Tick {
  double t_s = 0, x_mm = 0, y_mm = 0;
  bool in_contact = false;
  bool vented = false;  // a link outage or a disarmed rig
  double target[kFingerCount]{}, setpoint[kFingerCount]{}, monitor[kFingerCount]{};
  // From the record's flags. A tick of a link outage or a disarmed rig is no fidelity figure: the
  // rig was vented.
  void set_flags(unsigned flags) {
    vented = (flags & (kVented | kDisarmed)) != 0;
    in_contact = (flags & kInContact) != 0 && !vented;
  }
};

class Meter {
 public:
  Meter(std::vector<TumorTruth> tumors, FingerLayout layout) : tumors_(std::move(tumors)), layout_(layout) {}
  void add(const Tick& r) {
    for (std::size_t f = 0; f < kFingerCount; ++f) m_.max_setpoint_kPa = std::max(m_.max_setpoint_kPa, r.setpoint[f]);
    if (!r.in_contact) return;
    const auto centres = layout_.centres(r.x_mm, r.y_mm);
    for (std::size_t f = 0; f < kFingers; ++f) {
      const double e = r.monitor[f] - r.target[f];
      ++m_.n;
      m_.sum_sq += e * e;
      bool inside = false, near = false;
      for (const TumorTruth& t : tumors_) {
        const double d = std::hypot(centres[f].x_mm - t.x_mm, centres[f].y_mm - t.y_mm);
        inside = inside || d <= t.radius_mm;
        near = near || d <= t.radius_mm + kSoftMargin_mm;
      }
      if (inside) {
        ++m_.n_tumor;
        m_.tumor_monitor += r.monitor[f];
        m_.tumor_target += r.target[f];
      }
      if (!near) {
        ++m_.n_soft;
        m_.soft_overshoot_kPa = std::max(m_.soft_overshoot_kPa, e);
      }
    }
  }
  const Metrics& metrics() const { return m_; }

 private:
  std::vector<TumorTruth> tumors_;
  FingerLayout layout_;
  Metrics m_;
};

Tick tick_of(const TelemetryRecord& r) {
  Tick t;
  t.t_s = r.t_s;
  t.x_mm = r.x_mm;
  t.y_mm = r.y_mm;
  t.set_flags(r.flags);
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    t.target[f] = r.target_kPa[f];
    t.setpoint[f] = r.setpoint_kPa[f];
    t.monitor[f] = r.monitor_kPa[f];
  }
  return t;
}

class Recorder final : public TickObserver {
 public:
  void on_tick(const TelemetryRecord& r) noexcept override { ticks.push_back(tick_of(r)); }
  std::vector<Tick> ticks;
};

// The floor under the RMS (calibration/tracking_bound.hpp): the least RMS of the regulator's own
// pressure against the targets that any controller could reach, knowing every target in advance
// and filling instantly, bounded only by the regulator's fastest exhaust; over the same
// finger-ticks as the Meter. A lower bound for the pressure, which the monitor reads with noise:
// `monitor_kPa` is what that best pressure would score read through the monitor (its noise, and
// the reading clamped at min_kPa as the simulated regulator clamps it), an expectation for that
// one clairvoyant controller, not a bound (a clamped reading can even score below its pressure).
struct Floor {
  double pressure_kPa = -1, monitor_kPa = -1;
  std::string why_not;  // why there is none (the run vented, a plant the bound does not hold for, ...)
};

// E[(max(min, p + n) - r)^2] for n ~ N(0, sd^2): the reading clamped below as the plant clamps it
// (the upper clamp, 100 kPa, is never near a target). With a = (min - p) / sd, m = p - r and the
// standard normal's pdf phi and cdf Phi: (min - r)^2 Phi(a) + m^2 (1 - Phi(a)) + 2 m sd phi(a)
// + sd^2 (1 - Phi(a) + a phi(a)).
double expected_clamped_square(double p, double r, double sd, double min_kPa) {
  if (sd <= 0) return (std::max(min_kPa, p) - r) * (std::max(min_kPa, p) - r);
  const double a = (min_kPa - p) / sd, m = p - r;
  const boost::math::normal standard;
  const double Phi = boost::math::cdf(standard, a), phi = boost::math::pdf(standard, a);
  return (min_kPa - r) * (min_kPa - r) * Phi + m * m * (1 - Phi) + 2 * m * sd * phi + sd * sd * (1 - Phi + a * phi);
}

Floor floor_of(const std::vector<Tick>& ticks, const RigConfig& rig) {
  Floor out;
  std::vector<double> t, target, best;
  std::vector<std::uint8_t> counted;
  std::vector<TrackingBound> fingers;
  double monitor_sq_sum = 0;
  for (const Tick& k : ticks)
    if (k.vented) {
      out.why_not = "the run vented";  // a vent empties faster than the regulator's exhaust
      return out;
    }
  for (std::size_t f = 0; f < kFingers; ++f) {
    const PlantParams& plant = rig.plants[f];
    if (plant.min_kPa < 0) {
      out.why_not = "the plant's min_kPa is below 0 kPa";  // a command below 0 could empty it faster
      return out;
    }
    t.clear();
    target.clear();
    counted.clear();
    for (const Tick& k : ticks) {
      t.push_back(k.t_s);
      target.push_back(k.target[f]);
      counted.push_back(k.in_contact ? 1 : 0);
    }
    // The regulator's fastest exhaust over the pressures that matter: none above the highest
    // target R (a pressure clipped at R stays reachable, since p exp(-dt / tau(p)) grows with p,
    // and is no further from any target), and the exhaust lag is monotone in the pressure, so its
    // least over [0, R] is at one end (near 0 kPa it is slower where exhaust_lag_factor_at_0 > 1).
    double highest_kPa = 0;
    for (std::size_t k = 0; k < target.size(); ++k)
      if (counted[k]) highest_kPa = std::max(highest_kPa, target[k]);
    const double fastest_exhaust_s =
        std::min(plant.exhaust_time_constant_at(0.0), plant.exhaust_time_constant_at(highest_kPa));
    if (fastest_exhaust_s > 0) {
      fingers.push_back(least_tracking_error(t, target, counted, fastest_exhaust_s, &best));
    } else {  // an instant exhaust follows every target
      best = target;
      fingers.push_back({0.0, std::size_t(std::count(counted.begin(), counted.end(), std::uint8_t{1}))});
    }
    for (std::size_t k = 0; k < target.size(); ++k)
      if (counted[k]) monitor_sq_sum += expected_clamped_square(best[k], target[k], plant.noise_sd_kPa, plant.min_kPa);
  }
  const TrackingBound all = pooled(fingers);
  if (all.samples == 0) {
    out.why_not = "no finger-tick pressed";
    return out;
  }
  out.pressure_kPa = all.rms_kPa();
  out.monitor_kPa = std::sqrt(monitor_sq_sum / double(all.samples));
  return out;
}

struct Case {
  std::string rig_name;
  Floor floor;
  bool compensated = false;
  Metrics metrics;
  double p_max_kPa = 0;
  std::string identified;  // the dynamics calibration identified
  std::vector<Tick> ticks;
};

std::string fixed(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

Case run_pass(const std::string& name, const fs::path& rig, const fs::path& cal, bool compensate) {
  const fs::path data = fs::path(PALPRIG_SOURCE_DIR) / "data";
  RunFiles files;
  files.scene = data / "scenes" / "phantom_abc.json";
  files.input = "trace:" + (data / "traces" / "phantom_abc_pass.csv").string();
  files.rig = rig;
  files.calibration = cal;
  files.compensate_lag = compensate;
  LoadedRun run = load_run(files);
  Recorder rec;
  RunOptions opt;
  opt.rate_hz = 1000;
  opt.duration_s = run.input->duration_s();
  opt.mode = LoopMode::replay;
  opt.observer = &rec;
  const RunSummary s = execute_run(run, opt);
  if (s.fault != FaultCode::none) throw palprig::Error(name + ": the run faulted: " + to_string(s.fault));
  Meter meter(run.scene.tumors, run.config.layout);
  for (const Tick& t : rec.ticks) meter.add(t);
  Case c;
  c.rig_name = name;
  c.compensated = compensate;
  c.metrics = meter.metrics();
  c.p_max_kPa = run.rig.safety.p_max_kPa;
  for (std::size_t i = 0; i < kFingerCount; ++i)
    if (run.cal.dynamics[i])
      c.identified += (c.identified.empty() ? "" : "; ") + std::to_string(i + 1) + ": " +
                      fixed(run.cal.dynamics[i]->dead_time_s * 1000, 1) + " + " +
                      fixed(run.cal.dynamics[i]->time_constant_s * 1000, 1) + " ms, R^2 " +
                      fixed(run.cal.dynamics[i]->r_squared, 4);
  c.floor = floor_of(rec.ticks, run.rig);
  c.ticks = std::move(rec.ticks);
  return c;
}

void run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw palprig::Error("failed (" + std::to_string(status) + "): " + command);
}

// A rig calibrated by the documented recipe with the palprig command; the calibration file.
fs::path recipe_calibration(const fs::path& work, const fs::path& rig, const std::string& name) {
  const std::string bin = PALPRIG_BIN;
  const fs::path sweep = work / (name + "_sweep.csv");
  fs::path cal = work / (name + "_cal.json");
  run_command(bin + " calibrate sweep --rig " + rig.string() +
              " --channels 1,2,3 --excitation staircase,random,sine,step,chirp --quiet --out " + sweep.string() +
              " > " + (work / (name + "_sweep.txt")).string() + " 2>&1");
  run_command(bin + " calibrate fit " + sweep.string() + " --out " + cal.string() + " > " +
              (work / (name + "_fit.txt")).string() + " 2>&1");
  return cal;
}

// The heavier plant, calibrated by the documented recipe with the palprig command.
fs::path heavy_rig(const fs::path& work, fs::path& cal) {
  const fs::path data = fs::path(PALPRIG_SOURCE_DIR) / "data";
  std::ifstream in(data / "rigs" / "simulated.json");
  nlohmann::json rig = nlohmann::json::parse(in);
  rig["id"] = "sim-heavy";
  auto& p = rig["plant"];
  p["hysteresis_kPa"] = p["hysteresis_kPa"].get<double>() * 1.7;
  p["dead_time_s"] = p["dead_time_s"].get<double>() * 1.4;
  p["time_constant_s"] = p["time_constant_s"].get<double>() * 1.4;
  fs::path path = work / "sim_heavy.json";
  std::ofstream(path) << rig.dump(2) << "\n";
  cal = recipe_calibration(work, path, "sim_heavy");
  return path;
}

// Telemetry CSV of a run (palprig run --telemetry): the same measures.
Metrics metrics_of_telemetry(const fs::path& csv, const fs::path& scene_file, const fs::path& rig_file,
                             std::vector<Tick>& ticks) {
  const SceneFile scene = load_scene_file(scene_file);
  const RigConfig rig = load_rig_file(rig_file);
  Meter meter(scene.tumors, rig.layout);
  std::ifstream in(csv);
  if (!in) throw palprig::Error("cannot read " + csv.string());
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::size_t> col;
  {
    std::istringstream h(line);
    std::string name;
    for (std::size_t i = 0; std::getline(h, name, ','); ++i) col[name] = i;
  }
  for (const char* need : {"t_s", "x_mm", "y_mm", "flags", "target_kPa_1", "setpoint_kPa_1", "monitor_kPa_1"})
    if (!col.count(need)) throw palprig::Error(csv.string() + ": no column " + need);
  std::vector<double> cells;
  while (std::getline(in, line)) {
    cells.clear();
    std::istringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ',')) cells.push_back(std::strtod(cell.c_str(), nullptr));
    if (cells.size() < col.size()) continue;
    Tick t;
    t.t_s = cells[col["t_s"]];
    t.x_mm = cells[col["x_mm"]];
    t.y_mm = cells[col["y_mm"]];
    t.set_flags(unsigned(cells[col["flags"]]));
    for (std::size_t f = 0; f < kFingerCount; ++f) {
      const std::string n = std::to_string(f + 1);
      t.target[f] = cells[col["target_kPa_" + n]];
      t.setpoint[f] = cells[col["setpoint_kPa_" + n]];
      t.monitor[f] = cells[col["monitor_kPa_" + n]];
    }
    meter.add(t);
    ticks.push_back(t);
  }
  return meter.metrics();
}

nlohmann::json metrics_json(const Metrics& m, double p_max, const Floor& floor) {
  return {{"rms_kPa", m.rms()},
          {"least_possible_pressure_rms_kPa",
           floor.pressure_kPa < 0 ? nlohmann::json(nullptr) : nlohmann::json(floor.pressure_kPa)},
          {"that_pressure_read_through_the_monitor_rms_kPa",
           floor.monitor_kPa < 0 ? nlohmann::json(nullptr) : nlohmann::json(floor.monitor_kPa)},
          {"tumor_monitor_over_target", m.tumor_ratio()},
          {"soft_overshoot_kPa", m.soft_overshoot_kPa},
          {"max_setpoint_kPa", m.max_setpoint_kPa},
          {"p_max_kPa", p_max},
          {"finger_ticks", m.n},
          {"tumor_finger_ticks", m.n_tumor},
          {"soft_finger_ticks", m.n_soft}};
}

std::string met(bool ok) { return ok ? "met" : "NOT met"; }

// The RMS goal: 0.25 kPa on the shipped simulated rig (the plant palprig's own model describes),
// 0.5 kPa on any other.
double rms_goal_kPa(const std::string& rig) { return rig == "shipped simulated rig" ? 0.25 : 0.5; }

std::string floor_text(const Floor& f) {
  if (f.pressure_kPa < 0) return "n/a (" + f.why_not + ")";
  return fixed(f.pressure_kPa, 3) + " (read through the monitor " + fixed(f.monitor_kPa, 3) + ")";
}

void print_row(const std::string& rig, const std::string& comp, const Metrics& m, double p_max, const Floor& floor) {
  const double goal = rms_goal_kPa(rig);
  std::printf("| %s | %s | %s (%s%s) | %s | %s (%s) | %s (%s) | %s / %s (%s) |\n", rig.c_str(), comp.c_str(),
              fixed(m.rms(), 3).c_str(), goal < 0.5 ? "goal 0.25: " : "", met(m.rms() <= goal).c_str(),
              floor_text(floor).c_str(), fixed(m.tumor_ratio(), 3).c_str(), met(m.tumor_ratio() >= 0.97).c_str(),
              fixed(m.soft_overshoot_kPa, 2).c_str(), met(m.soft_overshoot_kPa <= 0.5).c_str(),
              fixed(m.max_setpoint_kPa, 2).c_str(), fixed(p_max, 0).c_str(), met(m.max_setpoint_kPa <= p_max).c_str());
}

// Finger 1 over tumor B: the target, the monitor without and with compensation.
void write_figure(const fs::path& png, const Case& off, const Case& on, const std::vector<TumorTruth>& tumors,
                  const FingerLayout& layout) {
  const TumorTruth* b = nullptr;
  for (const auto& t : tumors)
    if (!b || t.radius_mm > b->radius_mm) b = &t;
  // The first crossing of the largest tumor by finger 1: from 150 ms before it enters to 300 ms after it leaves.
  double enter = -1, leave = -1;
  for (const Tick& t : off.ticks) {
    if (!t.in_contact) continue;
    const auto c = layout.centres(t.x_mm, t.y_mm)[0];
    const bool inside = std::hypot(c.x_mm - b->x_mm, c.y_mm - b->y_mm) <= b->radius_mm;
    if (inside && enter < 0) enter = t.t_s;
    if (!inside && enter >= 0) {
      leave = t.t_s;
      break;
    }
  }
  if (enter < 0 || leave < 0) throw palprig::Error("finger 1 never crosses tumor " + b->name);
  const double from = enter - 0.15, to = leave + 0.3;
  charts::Chart chart;
  chart.title = "Finger 1 crossing tumor " + b->name + " (demo pass, " + off.rig_name + ")";
  chart.x_label = "time (s)";
  chart.y_label = "pressure (kPa)";
  charts::ChartSeries target, plain, comp;
  target.label = "target (the model)";
  plain.label = "monitor, no lag compensation";
  comp.label = "monitor, lag compensation";
  target.color_rgb = 0x202020;
  plain.color_rgb = 0xd62728;
  comp.color_rgb = 0x1f77b4;
  for (std::size_t k = 0; k < off.ticks.size() && k < on.ticks.size(); ++k) {
    const double t = off.ticks[k].t_s;
    if (t < from || t > to) continue;
    target.x.push_back(t);
    target.y.push_back(off.ticks[k].target[0]);
    plain.x.push_back(t);
    plain.y.push_back(off.ticks[k].monitor[0]);
    comp.x.push_back(t);
    comp.y.push_back(on.ticks[k].monitor[0]);
  }
  chart.series = {target, plain, comp};
  chart.width_px = 1000;
  chart.height_px = 500;
  charts::write_chart_png(chart, png);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    bool json_out = false;
    std::string figure, telemetry, label = "run", scene_arg, rig_arg;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw palprig::Error(a + " needs a value");
        return argv[++i];
      };
      if (a == "--json")
        json_out = true;
      else if (a == "--figure")
        figure = next();
      else if (a == "--telemetry")
        telemetry = next();
      else if (a == "--label")
        label = next();
      else if (a == "--scene")
        scene_arg = next();
      else if (a == "--rig")
        rig_arg = next();
      else if (a.rfind("--benchmark", 0) == 0)
        continue;  // bench/run_all.sh passes Google Benchmark's flags
      else
        throw palprig::Error("unknown argument " + a);
    }
    const fs::path data = fs::path(PALPRIG_SOURCE_DIR) / "data";
    if (!telemetry.empty()) {
      const fs::path rig = rig_arg.empty() ? data / "rigs" / "simulated.json" : fs::path(rig_arg);
      const RigConfig rc = load_rig_file(rig);
      std::vector<Tick> ticks;
      const Metrics m = metrics_of_telemetry(
          telemetry, scene_arg.empty() ? data / "scenes" / "phantom_abc.json" : fs::path(scene_arg), rig, ticks);
      Floor floor;
      try {
        floor = floor_of(ticks, rc);  // from the rig file's plant section: a model of the regulator
      } catch (const palprig::Error& e) {
        floor.why_not = e.what();
      }
      if (json_out)
        std::cout << metrics_json(m, rc.safety.p_max_kPa, floor).dump(2) << "\n";
      else
        print_row(label, "", m, rc.safety.p_max_kPa, floor);
      return 0;
    }
    const fs::path work = fs::temp_directory_path() / ("palprig-bench-fidelity-" + std::to_string(::getpid()));
    fs::create_directories(work);
    std::vector<Case> cases;
    const fs::path shipped_rig = data / "rigs" / "simulated.json",
                   shipped_cal = data / "calibration" / "sim-default.json";
    cases.push_back(run_pass("shipped simulated rig", shipped_rig, shipped_cal, false));
    cases.push_back(run_pass("shipped simulated rig", shipped_rig, shipped_cal, true));
    fs::path heavy_cal;
    const fs::path heavy = heavy_rig(work, heavy_cal);
    cases.push_back(run_pass("hysteresis x1.7, lag x1.4", heavy, heavy_cal, false));
    cases.push_back(run_pass("hysteresis x1.7, lag x1.4", heavy, heavy_cal, true));
    const fs::path asymmetric = data / "rigs" / "simulated_asymmetric.json";
    const fs::path asymmetric_cal = recipe_calibration(work, asymmetric, "sim_asymmetric");
    cases.push_back(run_pass("asymmetric regulator", asymmetric, asymmetric_cal, false));
    cases.push_back(run_pass("asymmetric regulator", asymmetric, asymmetric_cal, true));
    if (json_out) {
      nlohmann::json all = nlohmann::json::array();
      for (const Case& c : cases) {
        nlohmann::json j = metrics_json(c.metrics, c.p_max_kPa, c.floor);
        j["rig"] = c.rig_name;
        j["rms_goal_kPa"] = rms_goal_kPa(c.rig_name);
        j["lag_compensation"] = c.compensated;
        j["identified"] = c.identified;
        all.push_back(j);
      }
      std::cout << all.dump(2) << "\n";
    } else {
      std::printf(
          "| plant | lag compensation | RMS(monitor - target) kPa, goal <= 0.5 (0.25 on the shipped simulated rig) | "
          "floor: least RMS of the pressure itself, any controller knowing every target in advance (the rig "
          "file's plant) | "
          "monitor/target over tumors, goal >= "
          "0.97 | "
          "largest monitor - target over soft tissue kPa, goal <= 0.5 | largest setpoint / p_max kPa |\n");
      std::printf("|---|---|---|---|---|---|---|\n");
      for (const Case& c : cases) print_row(c.rig_name, c.compensated ? "on" : "off", c.metrics, c.p_max_kPa, c.floor);
      std::printf("\nIdentified dynamics (dead time + lag): shipped: %s\n  heavier plant: %s\n  asymmetric: %s\n",
                  cases[0].identified.c_str(), cases[2].identified.c_str(), cases[4].identified.c_str());
    }
    if (!figure.empty()) {
      const SceneFile scene = load_scene_file(data / "scenes" / "phantom_abc.json");
      const RigConfig rig = load_rig_file(shipped_rig);
      write_figure(figure, cases[0], cases[1], scene.tumors, rig.layout);
      std::fprintf(stderr, "bench_fidelity: figure %s\n", figure.c_str());
    }
    std::error_code ec;
    fs::remove_all(work, ec);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_fidelity: %s\n", e.what());
    return 1;
  }
}
