// `palprig calibrate evaluate` over a real Modbus TCP link (`palprig sim-rig` on loopback, in real
// time) says what it is doing: a progress line with the time left at least every 5 s (it printed
// nothing for 4 min 39 s before), and a dip of the plant away from its command is reported with
// its time even though no outage is counted (a 16 kPa dip at t = 20 s went unsaid). The dip is
// made for real: palprig is stopped (SIGSTOP) for half a second mid-run, the simulator's module
// watchdog sends the outputs to 0 kPa as a module does when its master falls silent, and the
// plant falls until palprig writes again.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <thread>

#include "tests/support/modbus_support.hpp"
#include "tests/support/run_process.hpp"

using namespace palprig;
using namespace palprig::test_support;

TEST(EvaluateOverModbus, ProgressAtLeastEveryFiveSecondsAndADipIsReportedWithItsTime) {
  TempDir dir;
  const std::string rig_src = source_dir() + "/data/rigs/wago_750_559.json";
  std::unique_ptr<WatchedProcess> sim;
  const int port = start_sim_rig(sim, palprig_bin(), rig_src, 0, (dir.path() / "writes.csv").string(),
                                 (dir.path() / "sim.err").string(), {"--watchdog-ms", "40"});
  const auto rig = dir.path() / "rig.json";
  std::ofstream(rig) << rig_on_port(read_json(rig_src), port).dump(2);
  // The shipped simulated rig's calibration, for this rig (the served plant is the same model).
  nlohmann::json cal = read_json(source_dir() + "/data/calibration/sim-default.json");
  cal["rig_id"] = "wago-750-559";
  const auto cal_file = dir.path() / "cal.json";
  std::ofstream(cal_file) << cal.dump(2);

  // Two runs of 1 s rest + 2 s approach + 8 s scored, standard error with standard output.
  const std::string command = "exec " + palprig_bin() + " calibrate evaluate --rig " + rig.string() + " --cal " +
                              cal_file.string() +
                              " --channels 2,3 --from-kPa 10 --ramp-kPa-per-s 5 --duration-s 8 2>&1";
  WatchedProcess evaluate({"/bin/sh", "-c", command}, (dir.path() / "sh.err").string());
  const std::regex progress("^evaluate: (uncompensated|compensated) run, ([0-9]+) % done");
  std::vector<double> arrivals;
  const auto start = std::chrono::steady_clock::now();
  auto now_s = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  bool stalled = false;
  std::string output;
  try {
    for (;;) {
      evaluate.wait_for_line(progress, 30.0);
      arrivals.push_back(now_s());
      // The second line of the first run comes 5 s in, within its scored part: stall there.
      if (!stalled && arrivals.size() == 2) {
        evaluate.signal(SIGSTOP);
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        evaluate.signal(SIGCONT);
        stalled = true;
      }
    }
  } catch (const std::runtime_error&) {
    // The process ended (its last lines are in the output).
  }
  output = evaluate.all_output();
  const int code = evaluate.wait();
  EXPECT_TRUE(stalled) << output;
  // Lines at each run's start and then at most 5 s apart (plus the check's own period under load).
  ASSERT_GE(arrivals.size(), 4u) << output;
  double widest = 0;
  for (std::size_t i = 1; i < arrivals.size(); ++i) widest = std::max(widest, arrivals[i] - arrivals[i - 1]);
  EXPECT_LE(widest, 5.5) << output;
  EXPECT_NE(output.find("left"), std::string::npos) << output;
  // The dip: said with its channel, its size and its time, and a warning; exit 1 only if the
  // run could not finish.
  EXPECT_TRUE(std::regex_search(output, std::regex("excursions beyond 3 kPa of the target: [1-9]"))) << output;
  EXPECT_TRUE(std::regex_search(
      output, std::regex("uncompensated run, channel [23]: [0-9.]+ kPa below the command at [0-9.]+ s")))
      << output;
  EXPECT_NE(output.find("palprig: warning: "), std::string::npos) << output;
  EXPECT_TRUE(code == 0 || code == 1) << code << "\n" << output;
}
