// `experiment run` with a simulated participant on a hardware (Modbus) rig runs in real time,
// as `palprig run` insists: against a real `palprig sim-rig` server on loopback, a session of
// 32 trials (minutes of stimuli) must still be at its first trials after a few seconds, not
// completed in a handful of bus cycles on simulated time.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "store/sqlite_trial_store.hpp"
#include "tests/support/modbus_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

namespace ts = palprig::test_support;

TEST(experiments_hardware_clock, simulated_participant_on_a_modbus_rig_runs_in_real_time) {
  ts::TempDir dir;
  std::unique_ptr<ts::WatchedProcess> sim;
  const std::string wago = std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json";
  const int port = ts::start_sim_rig(sim, ts::palprig_bin(), wago, 0, (dir.path() / "writes.csv").string(),
                                     (dir.path() / "sim.err").string());
  ASSERT_GT(port, 0);
  auto rig = ts::rig_on_port(ts::read_json(wago), port);
  rig["modbus"]["io_thread_fifo_priority"] = 0;
  rig["safety"]["max_consecutive_overruns"] = 1000000;  // a busy test machine must not end the run
  rig["safety"]["max_lost_time_s"] = 10;
  const auto rig_file = dir.write("rig.json", rig.dump(2)).string();
  const std::string db = (dir.path() / "hw.db").string();
  const std::string protocol = std::string(PALPRIG_SOURCE_DIR) + "/data/protocols/discrimination_002.json";

  ts::WatchedProcess run({ts::palprig_bin(), "experiment", "run", "--protocol", protocol, "--participant", "sim:3",
                          "--db", db, "--rig", rig_file},
                         (dir.path() / "run.err").string());
  run.wait_for_line(std::regex("real time \\(hardware rig\\)"), 20.0);
  const auto started = std::chrono::steady_clock::now();
  // Still running after 4 s of wall time (on simulated time the whole session took < 1 s).
  std::this_thread::sleep_for(std::chrono::seconds(4));
  int status = 0;
  ASSERT_EQ(::waitpid(run.pid(), &status, WNOHANG), 0)
      << "the session ended within seconds: " << run.all_output() << ts::read_file(dir.path() / "run.err");
  run.signal(SIGTERM);
  EXPECT_EQ(run.wait(), 1) << "a stopped session exits 1 (resumable)";
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string err = ts::read_file(dir.path() / "run.err");
  EXPECT_NE(err.find("continue with --resume"), std::string::npos) << err;

  // Trials committed in those seconds began no later than the wall time elapsed.
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
  auto q = store.database().prepare("SELECT count(*), COALESCE(MAX(onset_s), 0) FROM trials");
  ASSERT_TRUE(q.step());
  EXPECT_LT(q.integer(0), 32);
  EXPECT_LE(q.real(1), wall_s + 1.0) << "trial onsets ran ahead of the wall clock";
  sim->signal(SIGTERM);
  sim->wait();
}

TEST(experiments_hardware_clock, a_speed_other_than_real_time_is_refused_on_hardware) {
  ts::TempDir dir;
  const std::string protocol = std::string(PALPRIG_SOURCE_DIR) + "/data/protocols/discrimination_002.json";
  const std::string wago = std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json";
  const std::string db = (dir.path() / "hw.db").string();
  const auto r = ts::run_process(ts::palprig_bin() + " experiment run --protocol " + protocol +
                                 " --participant sim:3 --db " + db + " --rig " + wago + " --speed 10");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--speed"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(db)) << "nothing is stored before the refusal";
}

}  // namespace
}  // namespace palprig
