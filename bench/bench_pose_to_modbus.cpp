// End-to-end latency, tracker pose to regulator register: from the moment a
// tracker's OpenIGTLink server sends a pose (a TRANSFORM message, stamped on CLOCK_MONOTONIC
// by the server just after its send() returns) to the arrival of the Modbus write that carries
// the resulting setpoint at a `palprig sim-rig` process on loopback (its --write-log stamps
// each write on the same clock). The pen's figure (bench_pen_to_modbus) is beside it in
// docs/benchmarks.md.
//
// The path measured is the one a lab's rig runs: TCP (loopback) -> tracker reader thread
// (FIFO 60: poll, decode, fingertip p = o + R p_local, registration) -> LatestValue -> loop
// tick at 1 kHz (FIFO 80) with the force from the rig's load cell (a Modbus input register
// the bus thread reads) -> ModbusRig bus thread at the rig's io_rate_hz (FIFO 70) -> FC16 over
// TCP -> sim-rig. The tracked finger 1 presses on tumor B of the phantom throughout (sim-rig
// serves its load cell with 2 N resting on it); every 125 ms, at a pseudo-random phase, the
// tracker moves it between tumor B and the soft tissue that lies 30 mm beside it. Each move onto B is
// matched with the first write of finger 1's output above the soft-tissue value after it,
// each move off with the first write below the value held at the move (the setpoint then
// ramps under the slew limit, 2000 kPa/s).
//   build/bin/bench_pose_to_modbus [SECONDS=20]   (root, or an rtprio limit, for chrt and FIFO)
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench/sim_rig_child.hpp"
#include "core/error.hpp"
#include "controller/backend_factory.hpp"
#include "controller/loop_runner.hpp"
#include "controller/tick_setup.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "inputs/igtl_input.hpp"
#include "inputs/igtl_pose_server.hpp"
#include "runtime/monotonic_clock.hpp"
#include "controller/rig_lease.hpp"

extern char** environ;
using namespace palprig;

namespace {

const std::string kSource = PALPRIG_SOURCE_DIR;

struct Move {
  std::size_t row;  // the recording row that makes it
  bool onto_tumor;
};

// Finger 1 alone (per_finger placement; fingers 2 and 3 have no tool), tip at the tool's
// origin, tracker frame = scene frame. 200 poses a second so a move is sent within 5 ms of its
// phase; the move itself is one pose.
std::vector<RecordedPose> recording(double seconds, std::vector<Move>& moves) {
  std::vector<RecordedPose> rec;
  std::uint32_t lcg = 12345;
  auto phase_s = [&] {
    lcg = lcg * 1664525u + 1013904223u;
    return double(lcg >> 8) / double(1u << 24) * 0.004;
  };
  double next_move = 0.2 + phase_s();
  bool on_tumor = false;
  for (double t = 0; t < seconds; t += 0.005) {
    if (t >= next_move) {
      on_tumor = !on_tumor;
      moves.push_back({rec.size(), on_tumor});
      next_move += 0.125 + phase_s();
    }
    RecordedPose p;
    p.t_s = t;
    p.tool = "Finger1ToTracker";
    p.pose.translation_mm = {on_tumor ? 110.0 : 140.0, 50.0, -4.0};
    rec.push_back(p);
  }
  return rec;
}

// The WAGO rig file with a load cell on the coupler's fourth analog input (750-459 channel 4,
// input register 3), for every finger, and the simulator's port.
std::string rig_text(int port) {
  std::ifstream in(kSource + "/data/rigs/wago_750_559.json");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  text.replace(text.find("\"port\": 1502"), 12, "\"port\": " + std::to_string(port));
  const std::string cells =
      ",\n  \"load_cells\": {\"fingers\": \"all\", \"channels\": [{\"tare_V\": 0.1, \"N_per_V\": 2.0, \"input\": "
      "{\"register\": 3, \"function\": \"input\", \"raw_full_scale\": 32767, \"volts_span\": [0, 10]}}]}\n}";
  text.replace(text.rfind('}'), 1, cells);
  return text;
}

int run_benchmark(int argc, char** argv) {
  // bench/run_all.sh passes Google Benchmark flags to every program: only a number is a length.
  const double seconds = argc > 1 && std::atof(argv[1]) > 0 ? std::atof(argv[1]) : 20.0;
  const std::string dir = "/tmp/palprig-bench-pose-" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  const std::string write_log = dir + "/writes.csv", rig_path = dir + "/rig.json";
  std::ofstream(rig_path) << rig_text(1502);  // the simulator reads the map; the port is its own
  bench::SimRigChild sim = bench::spawn_sim_rig(rig_path, write_log, {"--load-N", "2"});
  const int port = sim.wait_for_port();
  if (port == 0) {
    std::cerr << "bench_pose_to_modbus: sim-rig did not start\n";
    return 1;
  }
  std::ofstream(rig_path) << rig_text(port);

  std::vector<Move> moves;
  PoseServerOptions options;
  options.port = 0;
  IgtlPoseServer server(recording(seconds, moves), options);
  server.record_sends(true);
  server.start();

  const RigConfig rig = load_rig_file(rig_path);
  const SceneFile scene = load_scene_file(kSource + "/data/scenes/phantom_abc.json");
  TickConfig config = make_tick_config(rig, CalibrationModels{});
  config.safety.max_lost_time_s = 1e9;  // a latency measurement: a stalled VM must not end it
  TrackingConfig tracking;
  tracking.placement = TrackedPlacement::per_finger;
  tracking.tools = {TrackedTool{"Finger1ToTracker", 0, {}}};
  auto input =
      std::make_unique<IgtlInput>(IgtlEndpoint{"127.0.0.1", server.port()}, tracking, rig.safety.max_input_age_s);
  std::unique_ptr<Rig> opened = open_rig(rig);
  RigLease lease = opened->lease("the pose-to-Modbus benchmark");
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.rate_hz = 1000;
  opt.duration_s = seconds;
  // Moves sent while the loop ran (not before it armed, nor after it ended) are the ones timed.
  const std::int64_t loop_start_ns = mono_ns();
  const RunSummary s = run_loop(config, *scene.scene, *input, lease, opt);
  const std::int64_t loop_end_ns = mono_ns();
  lease.release();
  opened.reset();
  input.reset();  // the client leaves before the server stops
  server.stop();
  sim.stop();

  std::vector<std::int64_t> sent_ns(server.sends().size() ? server.sends().back().first + 1 : 0, 0);
  for (const auto& [row, ns] : server.sends())
    if (row < sent_ns.size() && sent_ns[row] == 0) sent_ns[row] = ns;
  std::vector<std::pair<long long, unsigned>> writes;  // finger 1's output: (arrival ns, word)
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
  // The soft-tissue word: what finger 1 is held at before the first move onto B.
  std::vector<double> onto_ms, off_ms;
  std::size_t unmatched = 0;
  std::size_t outside = 0;
  for (const Move& m : moves) {
    if (m.row >= sent_ns.size() || sent_ns[m.row] == 0 || sent_ns[m.row] < loop_start_ns + 200'000'000 ||
        sent_ns[m.row] > loop_end_ns - 150'000'000) {
      ++outside;
      continue;
    }
    const long long due = sent_ns[m.row];
    auto first = std::find_if(writes.begin(), writes.end(), [&](const auto& w) { return w.first >= due; });
    const unsigned held = first == writes.begin() ? 0u : std::prev(first)->second;
    auto it = std::find_if(first, writes.end(),
                           [&](const auto& w) { return m.onto_tumor ? w.second > held : w.second < held; });
    if (it == writes.end() || double(it->first - due) > 100e6) {
      ++unmatched;
      continue;
    }
    (m.onto_tumor ? onto_ms : off_ms).push_back(double(it->first - due) / 1e6);
  }
  std::vector<double> all = onto_ms;
  all.insert(all.end(), off_ms.begin(), off_ms.end());
  std::printf(
      "tracker pose sent -> Modbus register write at sim-rig on loopback, %.0f s, tracker 200 Hz, loop 1 kHz, bus %g "
      "Hz (%s)\n",
      seconds, rig.modbus->io_rate_hz, s.realtime_practices.c_str());
  std::printf("  onto tumor %zu: p50 %.2f ms, p99 %.2f ms, max %.2f ms\n", onto_ms.size(),
              bench::percentile(onto_ms, .5), bench::percentile(onto_ms, .99), bench::percentile(onto_ms, 1.0));
  std::printf("  off tumor  %zu: p50 %.2f ms, p99 %.2f ms, max %.2f ms\n", off_ms.size(), bench::percentile(off_ms, .5),
              bench::percentile(off_ms, .99), bench::percentile(off_ms, 1.0));
  std::printf(
      "  all        %zu: p50 %.2f ms, p99 %.2f ms (regulator response: 50 ms time constant); %zu moves unmatched, "
      "%zu outside the run\n",
      all.size(), bench::percentile(all, .5), bench::percentile(all, .99), unmatched, outside);
  std::printf("  loop: %llu ticks, %llu overruns, wake-up p50/p99 %.0f/%.0f us; fault: %s %s\n",
              static_cast<unsigned long long>(s.ticks), static_cast<unsigned long long>(s.overruns),
              s.wake_latency.p50_us, s.wake_latency.p99_us, to_string(s.fault), s.fault.detail().c_str());
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
    std::fprintf(stderr, "bench_pose_to_modbus: %s\n", e.what());
    return 1;
  }
}
