// Why did it vent: a `palprig run` driving a real `palprig sim-rig` on loopback loses its peer
// (killed for real, SIGKILL) mid-run; the run faults once the link has been down longer than
// max_outage_s, and the ticks before the fault are in a file beside the run, named in the run's
// one-line message, whether or not telemetry was on.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "tests/support/modbus_process_support.hpp"

using namespace palprig::test_support;

namespace {

// A rig whose outage limit is short, so the run faults soon after its peer is gone.
std::string short_outage_rig(const TempDir& dir, int port) {
  auto rig = wago_on_port(port);
  rig["modbus"]["max_outage_s"] = 0.3;
  rig["modbus"]["reconnect_backoff_ms"] = {20, 100};
  return dir.write("rig.json", rig.dump(2)).string();
}

struct FaultFile {
  std::vector<std::string> comments;
  CsvTable table;
};

FaultFile read_fault_file(const std::filesystem::path& path) {
  FaultFile f;
  std::ifstream in(path);
  std::string line, csv;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '#')
      f.comments.push_back(line);
    else
      csv += line + "\n";
  }
  const auto body = path.string() + ".body.csv";
  std::ofstream(body) << csv;
  f.table = read_csv(body);
  return f;
}

void expect_the_ticks_before_the_fault(const FaultFile& f) {
  ASSERT_GE(f.comments.size(), 2u);
  EXPECT_NE(f.comments[1].find("# fault: rig backend error at t="), std::string::npos) << f.comments[1];
  EXPECT_NE(f.comments[1].find("max_outage_s"), std::string::npos) << f.comments[1];
  const CsvTable& t = f.table;
  ASSERT_EQ(t.rows.size(), 2000u) << "the ring holds the last 2000 ticks";
  const std::size_t tick = t.col("tick"), fault = t.col("fault"), flags = t.col("flags");
  for (std::size_t i = 1; i < t.rows.size(); ++i) ASSERT_EQ(t.rows[i][tick], t.rows[i - 1][tick] + 1) << i;
  const auto& last = t.rows.back();
  EXPECT_EQ(int(last[fault]), 3) << "backend_error";
  EXPECT_TRUE(int(last[flags]) & 8) << "vented";
  for (const char* name : {"setpoint_kPa_1", "setpoint_kPa_2", "setpoint_kPa_3"}) EXPECT_EQ(last[t.col(name)], 0.0);
  // Before the peer went, the rig pressed (the sweep crosses the tumors) without a fault.
  double most = 0;
  for (const auto& row : t.rows)
    if (row[fault] == 0) most = std::max(most, row[t.col("setpoint_kPa_1")]);
  EXPECT_GT(most, 0.0) << "the record must hold ticks from before the fault, not only vented ones";
}

TEST(FaultRecordCli, AModbusPeerKilledMidRunLeavesTheTicksBeforeTheFaultBesideTheTelemetry) {
  TempDir dir;
  ::setenv("PALPRIG_LOCK_DIR", dir.path().c_str(), 1);
  std::unique_ptr<WatchedProcess> sim;
  const int port = start_sim_rig(sim, palprig_bin(), kWagoRig, 0, (dir.path() / "writes.csv").string(),
                                 (dir.path() / "sim.err").string());
  auto run = start_palprig_run(dir, short_outage_rig(dir, port), 60.0);
  ASSERT_TRUE(poll_until([&] { return line_count(dir.path() / "telemetry.csv") > 2500; }, 60.0))
      << read_file(dir.path() / "run.err");
  sim->signal(SIGKILL);
  const FinishedRun r = finish_palprig_run(*run, dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto record = dir.path() / "telemetry.fault.csv";
  EXPECT_NE(r.err.find("the last 2000 ticks before it: " + record.string()), std::string::npos) << r.err;
  ASSERT_TRUE(std::filesystem::exists(record)) << r.err;
  expect_the_ticks_before_the_fault(read_fault_file(record));
  ::unsetenv("PALPRIG_LOCK_DIR");
}

TEST(FaultRecordCli, WithoutTelemetryTheRecordGoesToTheWorkingFolder) {
  TempDir dir;
  ::setenv("PALPRIG_LOCK_DIR", dir.path().c_str(), 1);
  std::unique_ptr<WatchedProcess> sim;
  const int port = start_sim_rig(sim, palprig_bin(), kWagoRig, 0, (dir.path() / "writes.csv").string(),
                                 (dir.path() / "sim.err").string());
  const std::string rig = short_outage_rig(dir, port);
  // The peer is killed 3 s into the run, from beside it, as a crash would take it.
  const ProcessResult r =
      run_process("cd " + dir.path().string() + " && (sleep 3; kill -KILL " + std::to_string(sim->pid()) + ") & cd " +
                  dir.path().string() + " && " + palprig_bin() + " run --realtime --no-fifo --rig " + rig +
                  " --scene " + kPhantom + " --input sweep --duration-s 60");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  std::filesystem::path record;
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    if (e.path().filename().string().rfind("palprig-fault-", 0) == 0) record = e.path();
  ASSERT_FALSE(record.empty()) << r.err;
  EXPECT_NE(r.err.find("the last 2000 ticks before it: " + record.string()), std::string::npos) << r.err;
  // The fault and its record on one line (the link's own lines, lost and its cycle statistics, come beside it).
  const std::size_t at = r.err.find("the last 2000 ticks before it: ");
  const std::size_t line_start = r.err.rfind('\n', at) == std::string::npos ? 0 : r.err.rfind('\n', at) + 1;
  EXPECT_EQ(r.err.compare(line_start, 20, "palprig: fault at t="), 0)
      << "one line names the fault and its record: " << r.err;
  EXPECT_NE(r.err.substr(line_start, at - line_start).find("rig backend error"), std::string::npos) << r.err;
  expect_the_ticks_before_the_fault(read_fault_file(record));
  ::unsetenv("PALPRIG_LOCK_DIR");
}

}  // namespace
