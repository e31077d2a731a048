// How well the rig renders the pulse: the correlation between the pulse a finger should feel
// and the pressure the simulated regulator actually delivers, with and without the lag
// pre-compensation, at 60, 100 and 160 BPM (goal >= 0.95 up to 100 BPM).
//
//   build/bin/bench_pulse_correlation            the table (Markdown) for README.md
//   build/bin/bench_pulse_correlation --json     the same numbers as JSON
//
// Set-up: the shipped brachial scene (data/scenes/brachial_pulse.json), the pen still with
// finger 1 over the artery at 2.0 N (force factor 0.78 of the window 0.6..2.4 N), the full tick
// (stress, actuator, pulse stage, safety with its 2000 kPa/s slew limit and 60 kPa p_max) at
// 1 kHz, and the plant of data/rigs/simulated.json: 5 ms dead time, 50 ms first-order lag,
// 2000 kPa/s slew, and its 2 kPa play (hysteresis), with and without that play (the play is
// the calibration's hysteresis inverse's job, not the pulse compensator's). The pulse shapes:
// rectangular D = 0.2 (papers 000, 004), saw-tooth (003) and the scene's lookup table (004).
//
// r is Pearson's correlation at zero lag between the intended pulse (TickResult::pulse_kPa) and
// the regulator output, over 20 s after 3 s of settling; "best lag" is the delay that would
// maximise it (how late the felt pulse is).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "controller/rig_step.hpp"
#include "models/tissue_scene.hpp"

using namespace palprig;

namespace {

double pearson(const double* a, const double* b, std::size_t n) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= double(n);
  mb /= double(n);
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

struct Result {
  double r = 0, best_r = 0;
  int best_lag_ms = 0;
  double base_kPa = 0, pulse_peak_kPa = 0, max_setpoint_kPa = 0;
};

// The shipped scene with its artery's waveform and rate replaced.
std::unique_ptr<FunctionScene> scene_with(const FunctionScene& shipped, const PulseWaveform& wave, double bpm) {
  ArterySpec a = shipped.arteries().artery(0).spec();
  a.waveform = wave;
  a.rate_bpm = bpm;
  return std::make_unique<FunctionScene>(shipped.field().definition(), std::vector<ArterySpec>{a});
}

// How the plant's 2 kPa play is handled: left alone (the default calibration has no hysteresis
// model), cancelled by the calibration fitted on this rig (data/calibration/sim-default.json,
// the tick's hysteresis inverse), or absent (the lag alone).
// With the calibration, the lag compensator works on the pulse alone (the default) or, with lag
// compensation switched on (whole_target: calibration identified the regulators' dynamics), on
// the whole target, stiffness and pulse together: the same compensator either way.
enum class Play { uncompensated, calibrated, calibrated_whole, absent };
const char* to_string(Play p) {
  switch (p) {
    case Play::uncompensated: return "rig file, play not compensated";
    case Play::calibrated: return "rig file + sim-default.json calibration";
    case Play::calibrated_whole: return "same, whole target lag-compensated";
    case Play::absent: return "lag only (no play)";
  }
  return "";
}

Result measure(const FunctionScene& scene, const RigConfig& rig, const CalibrationModels& fitted, Play play,
               bool compensate) {
  RigConfig r = rig;
  for (PlantParams& p : r.plants) {
    p.noise_sd_kPa = 0;  // the actuator's own pressure, not a noisy monitor
    if (play == Play::absent) p.hysteresis_kPa = 0;
  }
  const bool calibrated = play == Play::calibrated || play == Play::calibrated_whole;
  TickConfig cfg = make_tick_config(r, calibrated ? fitted : CalibrationModels{});
  cfg.pulse.compensate_lag = compensate;
  cfg.lag_compensation.whole_target = compensate && play == Play::calibrated_whole;
  SimulatedRig backend(r.plants, r.safety.p_max_kPa);
  backend.open();
  RigStep step_rig(cfg, backend);
  step_rig.arm();
  // Finger 1 (16 mm along x from the pen) over the artery at x = 40 mm.
  const double x = 24, y = 60 - 2.0 * 40 / 90;
  std::vector<double> want, got;
  Result out;
  ChannelPressures monitor{};
  for (int k = 0; k < 23000; ++k) {
    const double t = k * 0.001;
    const StepResult& step = step_rig.step(scene, {t, x, y, 2.0, true}, t);
    const TickResult& tr = step.tick;
    monitor = step.monitor_kPa;
    if (k >= 3000) {
      want.push_back(tr.pulse_kPa[1]);
      got.push_back(monitor[1]);
      out.pulse_peak_kPa = std::max(out.pulse_peak_kPa, tr.pulse_kPa[1]);
      out.max_setpoint_kPa = std::max(out.max_setpoint_kPa, tr.setpoint_kPa[1]);
      if (tr.pulse_kPa[1] == 0 && !compensate) out.base_kPa = tr.record.target_kPa[1];
    }
  }
  const std::size_t n = want.size();
  out.r = pearson(want.data(), got.data(), n);
  for (int lag = 0; lag <= 150; ++lag) {
    const double c = pearson(want.data(), got.data() + lag, n - 150);
    if (c > out.best_r) out.best_r = c, out.best_lag_ms = lag;
  }
  return out;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

int run_benchmark(int argc, char** argv) {
  const bool json_out = argc > 1 && std::strcmp(argv[1], "--json") == 0;
  const std::string data = std::string(PALPRIG_SOURCE_DIR) + "/data/";
  const RigConfig rig = load_rig_file(data + "rigs/simulated.json");
  const SceneFile sf = load_scene_file(data + "scenes/brachial_pulse.json");
  const auto& shipped = dynamic_cast<const FunctionScene&>(*sf.scene);
  const CalibrationModels fitted = load_calibration_file(data + "calibration/sim-default.json");

  struct Shape {
    const char* name;
    PulseWaveform wave;
  };
  const Shape shapes[] = {{"rectangular D=0.2", PulseWaveform::rectangular(0.2)},
                          {"saw-tooth", PulseWaveform::sawtooth(0.15)},
                          {"table (brachial beat)", shipped.arteries().artery(0).spec().waveform}};
  nlohmann::json all = nlohmann::json::array();
  if (!json_out) {
    std::printf("Machine: %s\n\n", cpu_model().c_str());
    std::printf("| waveform | BPM | plant | r without | r with | best-lag r without (lag) | best-lag r with (lag) |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
  }
  for (const Shape& s : shapes)
    for (double bpm : {60.0, 100.0, 160.0}) {
      const auto scene = scene_with(shipped, s.wave, bpm);
      for (Play play : {Play::uncompensated, Play::calibrated, Play::calibrated_whole, Play::absent}) {
        const Result raw = measure(*scene, rig, fitted, play, false), comp = measure(*scene, rig, fitted, play, true);
        const char* plant = to_string(play);
        if (json_out) {
          all.push_back({{"waveform", s.name},
                         {"bpm", bpm},
                         {"plant", plant},
                         {"r_without", raw.r},
                         {"r_with", comp.r},
                         {"best_lag_r_without", raw.best_r},
                         {"best_lag_ms_without", raw.best_lag_ms},
                         {"best_lag_r_with", comp.best_r},
                         {"best_lag_ms_with", comp.best_lag_ms},
                         {"base_kPa", comp.base_kPa},
                         {"pulse_peak_kPa", comp.pulse_peak_kPa},
                         {"max_setpoint_kPa_with", comp.max_setpoint_kPa}});
        } else {
          std::printf("| %s | %.0f | %s | %.3f | **%.3f** | %.3f (%d ms) | %.3f (%d ms) |\n", s.name, bpm, plant, raw.r,
                      comp.r, raw.best_r, raw.best_lag_ms, comp.best_r, comp.best_lag_ms);
        }
        if (s.wave.shape() == WaveShape::rectangular && bpm == 60 && play == Play::uncompensated && !json_out)
          std::fprintf(
              stderr, "(stiffness pressure under the pulse %.2f kPa, pulse peak %.2f kPa, highest setpoint %.2f kPa)\n",
              raw.base_kPa, comp.pulse_peak_kPa, comp.max_setpoint_kPa);
      }
    }
  if (json_out) std::printf("%s\n", nlohmann::json{{"machine", cpu_model()}, {"results", all}}.dump(2).c_str());
  return 0;
}

}  // namespace

// A failure (a file, the simulator, the rig) ends the benchmark with one line and exit 1, not
// with std::terminate.
int main(int argc, char** argv) {
  try {
    return run_benchmark(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pulse_correlation: %s\n", e.what());
    return 1;
  }
}
