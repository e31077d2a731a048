// End-to-end latency, pen event to regulator register: from the time a pen event is stamped
// (for a live tablet, the kernel's evdev timestamp; here, the CLOCK_MONOTONIC time an evemu
// recording's event comes due, which is when the replaying reader hands it over) to the
// arrival of the Modbus write that carries the resulting setpoint at a `palprig sim-rig`
// process on loopback (its --write-log stamps each write on the same clock).
//
// The path measured is the one a rig runs: tablet reader thread (FIFO 60) -> LatestValue ->
// loop tick at 1 kHz (FIFO 80) -> ModbusRig bus thread at the rig's io_rate_hz (FIFO 70) ->
// FC16 over TCP -> sim-rig. The recording presses the pen down on tumor B of the bundled
// phantom and lifts it again, every 250 ms; each press is matched with the first non-zero write
// of finger 1's output after it, each lift with the first write below the value held at the
// lift (the setpoint then ramps down under the rig's slew limit, 2000 kPa/s).
// sim-rig runs under `chrt -f 50`: a real module is hardware that the machine's other work
// cannot delay, so the simulator must not be the part that waits for the CPU.
//   build/bin/bench_pen_to_modbus [SECONDS=20]   (root, or an rtprio limit, for chrt and FIFO)
// (No /dev/uinput on the development machine, so no kernel-stamped events could be injected;
// with a live tablet the reader's own wake-up adds to the figure.)
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <iterator>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/sim_rig_child.hpp"
#include "core/error.hpp"
#include "controller/backend_factory.hpp"
#include "controller/loop_runner.hpp"
#include "controller/tick_setup.hpp"
#include "formats/modbus_register_map.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "inputs/tablet_input.hpp"
#include "inputs/tablet_source.hpp"
#include "runtime/latency_histogram.hpp"
#include "controller/rig_lease.hpp"

extern char** environ;
using namespace palprig;

namespace {

const std::string kSource = PALPRIG_SOURCE_DIR;

struct PenEdge {
  double t_s;
  bool press;
};

// The device description of the bundled synthesised recording, then presses and lifts.
std::vector<PenEdge> write_recording(const std::string& path, double seconds) {
  std::ifstream in(kSource + "/tests/fixtures/evemu/pen_stroke.evemu");
  std::ofstream out(path);
  std::string line;
  while (std::getline(in, line) && line.rfind("E:", 0) != 0) out << line << "\n";
  auto ev = [&](double t, int type, int code, int value) {
    char b[64];
    std::snprintf(b, sizeof b, "E: %.6f %04x %04x %04d\n", t, type, code, value);
    out << b;
  };
  // In proximity over tumor B (110, 50 mm; 100 units/mm), pen up.
  ev(0.0, 1, 0x140, 1);
  ev(0.0, 3, 0x00, 11000);
  ev(0.0, 3, 0x01, 5000);
  ev(0.0, 0, 0, 0);
  std::vector<PenEdge> edges;
  // Each edge lands at a pseudo-random phase within 4 ms (two bus periods, four loop periods),
  // so the figures cover every phase of the pen against the loop and the bus, not one.
  std::uint32_t lcg = 12345;
  auto phase_s = [&] {
    lcg = lcg * 1664525u + 1013904223u;
    return double(lcg >> 8) / double(1u << 24) * 0.004;
  };
  for (double t = 0.1; t + 0.25 < seconds; t += 0.25) {
    const double down = t + phase_s(), up = t + 0.125 + phase_s();
    ev(down, 1, 0x14a, 1), ev(down, 3, 0x18, 3072), ev(down, 0, 0, 0);
    edges.push_back({down, true});
    ev(up, 1, 0x14a, 0), ev(up, 3, 0x18, 0), ev(up, 0, 0, 0);
    edges.push_back({up, false});
  }
  // Stay in proximity, pen up, until the end (heartbeats keep the sample fresh).
  ev(seconds, 3, 0x00, 11001), ev(seconds, 0, 0, 0);
  return edges;
}

int run_benchmark(int argc, char** argv) {
  // bench/run_all.sh passes Google Benchmark flags to every program: only a number is a length.
  const double seconds = argc > 1 && std::atof(argv[1]) > 0 ? std::atof(argv[1]) : 20.0;
  const std::string dir = "/tmp/palprig-bench-e2e-" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  const std::string recording = dir + "/presses.evemu", write_log = dir + "/writes.csv", rig_path = dir + "/rig.json";
  const std::vector<PenEdge> edges = write_recording(recording, seconds);

  const std::string wago = kSource + "/data/rigs/wago_750_559.json";
  bench::SimRigChild sim = bench::spawn_sim_rig(wago, write_log);
  const int port = sim.wait_for_port();
  if (port == 0) {
    std::cerr << "bench_pen_to_modbus: sim-rig did not start\n";
    return 1;
  }
  {  // the rig file, pointed at the simulator's port
    std::ifstream in(wago);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    text.replace(text.find("\"port\": 1502"), 12, "\"port\": " + std::to_string(port));
    std::ofstream(rig_path) << text;
  }

  const RigConfig rig = load_rig_file(rig_path);
  const SceneFile scene = load_scene_file(kSource + "/data/scenes/phantom_abc.json");
  TickConfig config = make_tick_config(rig, CalibrationModels{});
  config.safety.max_lost_time_s = 1e9;  // a latency measurement: a stalled VM must not end it
  auto source = std::make_unique<EvemuPenSource>(recording);
  EvemuPenSource* replay = source.get();
  TabletInput pen(std::move(source), rig.tablet);
  std::unique_ptr<Rig> opened = open_rig(rig);
  RigLease lease = opened->lease("the pen-to-Modbus benchmark");
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.rate_hz = 1000;
  opt.duration_s = seconds;
  const RunSummary s = run_loop(config, *scene.scene, pen, lease, opt);
  lease.release();
  opened.reset();
  sim.stop();

  // Writes of finger 1's output: (arrival ns, word).
  std::vector<std::pair<long long, unsigned>> writes;
  std::ifstream log(write_log);
  std::string line;
  std::getline(log, line);
  while (std::getline(log, line)) {
    double t, kPa;
    unsigned ch, word;
    long long ns;
    if (std::sscanf(line.c_str(), "%lf,%u,%u,%lf,%lld", &t, &ch, &word, &kPa, &ns) == 5 && ch == 1)
      writes.push_back({ns, word});
  }
  const std::int64_t start = replay->start_ns();
  std::vector<double> press_ms, lift_ms;
  std::size_t unmatched = 0;
  for (const auto& e : edges) {
    const long long due = start + static_cast<long long>(e.t_s * 1e9);  // the recording's first event is at 0
    // The setpoint moves under the rig's slew limit in both directions, so the pen's effect
    // arrives with the first write that moves the output its way: up from 0 after a press,
    // down from the value held at the lift.
    auto first = std::find_if(writes.begin(), writes.end(), [&](const auto& w) { return w.first >= due; });
    const unsigned held = first == writes.begin() ? 0u : std::prev(first)->second;
    auto it =
        std::find_if(first, writes.end(), [&](const auto& w) { return e.press ? w.second > 0 : w.second < held; });
    if (it == writes.end() || double(it->first - due) > 100e6) {
      ++unmatched;
      continue;
    }
    (e.press ? press_ms : lift_ms).push_back(double(it->first - due) / 1e6);
  }
  std::vector<double> all = press_ms;
  all.insert(all.end(), lift_ms.begin(), lift_ms.end());
  std::printf("pen event -> Modbus register write at sim-rig on loopback, %.0f s, loop 1 kHz, bus %g Hz (%s)\n",
              seconds, rig.modbus->io_rate_hz, s.realtime_practices.c_str());
  std::printf("  presses %zu: p50 %.2f ms, p99 %.2f ms, max %.2f ms\n", press_ms.size(),
              bench::percentile(press_ms, .5), bench::percentile(press_ms, .99), bench::percentile(press_ms, 1.0));
  std::printf("  lifts   %zu: p50 %.2f ms, p99 %.2f ms, max %.2f ms\n", lift_ms.size(), bench::percentile(lift_ms, .5),
              bench::percentile(lift_ms, .99), bench::percentile(lift_ms, 1.0));
  std::printf(
      "  all     %zu: p50 %.2f ms, p99 %.2f ms (regulator response: 50 ms time constant); %zu edges unmatched\n",
      all.size(), bench::percentile(all, .5), bench::percentile(all, .99), unmatched);
  std::printf("  loop: %llu ticks, %llu overruns, wake-up p50/p99 %.0f/%.0f us; fault: %s\n",
              static_cast<unsigned long long>(s.ticks), static_cast<unsigned long long>(s.overruns),
              s.wake_latency.p50_us, s.wake_latency.p99_us, to_string(s.fault));
  std::filesystem::remove_all(dir);
  return unmatched == 0 && s.fault == FaultCode::none ? 0 : 1;
}

}  // namespace

// A failure (a file, the simulator, the rig) ends the benchmark with one line and exit 1, not
// with std::terminate.
int main(int argc, char** argv) {
  try {
    return run_benchmark(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pen_to_modbus: %s\n", e.what());
    return 1;
  }
}
