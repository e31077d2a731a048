// With the shipped max_outage_s (2 s, formats/modbus_register_map.hpp and the
// example rig files), a Modbus peer that stops answering ends the run: vented, exit 1, saying
// why, instead of running on vented to the end with exit 0.
#include <gtest/gtest.h>

#include <csignal>
#include <cmath>

#include "formats/rig_file.hpp"
#include "tests/support/modbus_process_support.hpp"

using namespace palprig;
using namespace palprig::test_support;

namespace {

// Start a run against a simulator, SIGSTOP the simulator once the run is writing, and let the
// run end on its own. Returns the finished run; `stopped_at_s` is the run's telemetry time of
// the last fresh monitor reading.
FinishedRun run_with_stopped_peer(TempDir& dir, nlohmann::json rig, double seconds) {
  std::unique_ptr<WatchedProcess> sim;
  const auto writes = dir.path() / "writes.csv";
  const int port = start_sim_rig(sim, palprig_bin(), kWagoRig, 0, writes.string(), (dir.path() / "sim.err").string());
  rig = rig_on_port(rig, port);
  const auto rig_file = dir.write("rig.json", rig.dump(2)).string();
  auto run = start_palprig_run(dir, rig_file, seconds);
  // Running: the simulator has logged the run's writes for a while (500 Hz bus).
  EXPECT_TRUE(poll_until([&] { return line_count(writes) > 200; }, 20.0)) << "the run never wrote";
  sim->signal(SIGSTOP);  // alive, connected, answers nothing: a hung module
  FinishedRun r = finish_palprig_run(*run, dir);
  sim->signal(SIGCONT);
  sim->signal(SIGTERM);
  sim->wait();
  return r;
}

void expect_ended_by_the_outage(const FinishedRun& r, const TempDir& dir, double seconds) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  ASSERT_TRUE(r.summary.is_object()) << r.err;
  ASSERT_TRUE(r.summary["fault"].is_object()) << r.summary.dump();
  EXPECT_EQ(r.summary["fault"]["reason"], "rig backend error") << r.summary.dump();
  EXPECT_NE(r.summary["fault"]["detail"].get<std::string>().find("max_outage_s = 2.000 s"), std::string::npos)
      << r.summary.dump();
  EXPECT_NE(r.err.find("lost"), std::string::npos) << r.err;
  // Ended about 2 s after the link was lost, well before the end of the run. The bus thread
  // dates the loss from the start of the cycle whose request then timed out (50 ms), so the
  // loop's first alarm comes up to a response timeout, a bus period and a late tick after it.
  const auto tel = read_csv((dir.path() / "telemetry.csv").string());
  ASSERT_FALSE(tel.rows.empty());
  const std::size_t t = tel.col("t_s"), fault = tel.col("fault"), flags = tel.col("flags");
  double first_alarm = -1;
  for (const auto& row : tel.rows)
    if (row[fault] == 3 && first_alarm < 0) first_alarm = row[t];
  ASSERT_GE(first_alarm, 0.0);
  const double fault_t = r.summary["fault"]["t_s"].get<double>();
  EXPECT_GE(fault_t - first_alarm, 2.0 - 0.1);
  EXPECT_LE(fault_t - first_alarm, 2.0 + 0.5);
  EXPECT_LT(fault_t, seconds - 1.0);
  // Vented: every command from the alarm on is 0 kPa, the last record says vented.
  for (const auto& row : tel.rows) {
    if (row[t] < first_alarm) continue;
    for (const char* c : {"setpoint_kPa_1", "setpoint_kPa_2", "setpoint_kPa_3"}) EXPECT_EQ(row[tel.col(c)], 0.0);
  }
  EXPECT_TRUE(int(tel.rows.back()[flags]) & 8);
}

}  // namespace

TEST(ModbusOutageDefault, TheBuiltInDefaultIsTwoSeconds) {
  auto rig = read_json(kWagoRig);
  rig["modbus"].erase("max_outage_s");
  TempDir dir;
  const RigConfig loaded = load_rig_file(dir.write("rig.json", rig.dump(2)));
  ASSERT_TRUE(loaded.modbus);
  EXPECT_EQ(loaded.modbus->max_outage_s, 2.0);
  EXPECT_EQ(load_rig_file(kWagoRig).modbus->max_outage_s, 2.0);  // and the shipped example says so
}

TEST(ModbusOutageDefault, AStoppedPeerEndsTheRunVentedWithExitOne) {
  TempDir dir;
  auto rig = wago_on_port(0);
  rig["modbus"].erase("max_outage_s");  // the built-in default
  const FinishedRun r = run_with_stopped_peer(dir, rig, 8.0);
  expect_ended_by_the_outage(r, dir, 8.0);
}
