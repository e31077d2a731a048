// One program drives a rig at a time: a second `palprig run` on the Modbus module a first one
// drives (a real `palprig sim-rig` on loopback) is refused before anything moves, naming the
// first; once the first has ended (here killed for real, so its lock is the kernel's to drop),
// the module can be taken again.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

#include "tests/support/modbus_process_support.hpp"

using namespace palprig::test_support;

namespace {

std::string run_briefly(const std::string& rig) {
  return palprig_bin() + " run --realtime --no-fifo --rig " + rig + " --scene " + kPhantom +
         " --input sweep --duration-s 0.3";
}

TEST(RigOwnerCli, ASecondProgramOnTheSameModbusModuleIsRefusedUntilTheFirstIsGone) {
  TempDir dir;
  // The machine-wide locks in this test's own folder, not /run/lock (parallel tests, CI).
  ::setenv("PALPRIG_LOCK_DIR", dir.path().c_str(), 1);
  std::unique_ptr<WatchedProcess> sim;
  const int port = start_sim_rig(sim, palprig_bin(), kWagoRig, 0, (dir.path() / "writes.csv").string(),
                                 (dir.path() / "sim.err").string());
  const std::string rig = dir.write("rig.json", wago_on_port(port).dump(2)).string();

  auto first = start_palprig_run(dir, rig, 60.0);
  ASSERT_TRUE(poll_until([&] { return line_count(dir.path() / "telemetry.csv") > 20; }, 30.0))
      << read_file(dir.path() / "run.err");

  const ProcessResult second = run_process(run_briefly(rig));
  EXPECT_EQ(second.exit_code, 1) << second.err;
  EXPECT_NE(second.err.find("is in use by another palprig (pid " + std::to_string(first->pid())), std::string::npos)
      << second.err;
  EXPECT_NE(second.err.find("one program drives a rig at a time"), std::string::npos) << second.err;
  EXPECT_EQ(std::count(second.err.begin(), second.err.end(), '\n'), 1) << "one line: " << second.err;
  EXPECT_TRUE(second.out.empty()) << "nothing ran: " << second.out;

  first->signal(SIGKILL);  // a crash: the kernel drops its lock with the process
  first->wait();
  const ProcessResult third = run_process(run_briefly(rig));
  EXPECT_EQ(third.exit_code, 0) << third.err;
  ::unsetenv("PALPRIG_LOCK_DIR");
}

}  // namespace
