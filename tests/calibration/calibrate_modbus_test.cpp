// A calibration sweep on real hardware's path: `palprig calibrate sweep` drives the WAGO rig
// file's Modbus TCP backend against a real `palprig sim-rig` server on 127.0.0.1, in real time.
#include <gtest/gtest.h>

#include <fstream>

#include "calibration/sweep_csv.hpp"
#include "tests/support/modbus_support.hpp"
#include "tests/support/run_process.hpp"

using namespace palprig;
using namespace palprig::test_support;

TEST(CalibrateOverModbus, StaircaseThroughARealTcpServerSettlesOnThePlantsHysteresis) {
  TempDir dir;
  const std::string rig_src = source_dir() + "/data/rigs/wago_750_559.json";
  std::unique_ptr<WatchedProcess> sim;
  const std::string writes = (dir.path() / "writes.csv").string();
  const int port = start_sim_rig(sim, palprig_bin(), rig_src, 0, writes, (dir.path() / "sim.err").string());
  const auto rig = dir.path() / "rig.json";
  std::ofstream(rig) << rig_on_port(read_json(rig_src), port).dump(2);

  const std::string data = (dir.path() / "data.csv").string();
  // 10, 35, 60 kPa up and down: eight holds, a few seconds in real time.
  const ProcessResult r = run_process(palprig_bin() + " calibrate sweep --rig " + rig.string() +
                                      " --repeats 1 --step-kPa 25 --quiet --out " + data);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("rig wago-750-559 (modbus"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("real time"), std::string::npos) << r.out;
  // Every hold settled; on a loaded machine a hold may be redone after a link outage, which the
  // same parenthesis then says (", 2 redone after a link outage"): still eight settled holds.
  EXPECT_NE(r.out.find("8 of 8 holds (0 not settled"), std::string::npos) << r.out;

  const SweepData d = read_sweep_csv(data);
  EXPECT_EQ(d.info.rig_id, "wago-750-559");
  EXPECT_EQ(d.info.backend.rfind("modbus", 0), 0u) << d.info.backend;
  std::size_t checked = 0;
  for (const HoldPoint& p : d.points) {
    if (p.segment != SweepSegment::staircase || p.command_kPa == 60) continue;
    // The served plant's 2 kPa play, read back through the register map's 0-10 V scaling.
    const double expected = p.command_kPa + (p.branch == SweepBranch::inflation ? -2.0 : 2.0);
    EXPECT_NEAR(p.monitor_kPa, expected, 0.3)
        << "channel " << p.channel << " " << to_string(p.branch) << " " << p.command_kPa;
    ++checked;
  }
  EXPECT_EQ(checked, 3u * 4u);
  // Nothing above the rig's p_max reached the modules (the simulator's log of every write,
  // complete once it has stopped).
  sim->signal(SIGINT);
  EXPECT_EQ(sim->wait(), 0);
  double most = 0;
  const CsvTable log = read_csv(writes);
  ASSERT_FALSE(log.rows.empty());
  for (const auto& row : log.rows) most = std::max(most, row[log.col("kPa")]);
  EXPECT_GT(most, 59.0);
  EXPECT_LE(most, 60.0 + 1e-3);
}
