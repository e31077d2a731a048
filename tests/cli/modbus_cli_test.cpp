// End to end over loopback with real processes: `palprig run` drives `palprig sim-rig`; the
// simulator is killed, stopped and continued with real signals mid-run.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "tests/support/modbus_process_support.hpp"
#include "tests/support/modbus_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig::test_support;

namespace {

const std::string kScene = std::string(PALPRIG_SOURCE_DIR) + "/data/scenes/phantom_abc.json";

// The WAGO example with three different encodings, one per channel, so the network path is
// checked for each: 15-bit unsigned, signed int16 over +/-10 V, and 12-bit unsigned.
nlohmann::json mixed_map_rig(int port) {
  auto rig = rig_on_port(read_json(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json"), port);
  rig["channels"][1]["output"]["signed"] = true;
  rig["channels"][1]["output"]["volts_span"] = {-10, 10};
  rig["channels"][2]["output"]["raw_full_scale"] = 4095;
  rig["modbus"]["reconnect_backoff_ms"] = {50, 400};
  rig["modbus"]["io_thread_fifo_priority"] = 0;
  // The killed simulator is restarted by the test; a sanitizer build on a busy machine can
  // take longer than the shipped 2 s outage limit to start it (that limit has its own tests).
  rig["modbus"]["max_outage_s"] = 120;
  // These tests are about the link, not about deadlines: a test machine busy with other work
  // must not end the run with the overrun limit.
  rig["safety"]["max_consecutive_overruns"] = 1000000;
  rig["safety"]["max_lost_time_s"] = 10;
  return rig;
}

// Pen held at tumor B's centre pressing 4 N: finger 1 over the tumor, 2 and 3 on soft tissue.
std::string write_hold_trace(const TempDir& dir, double seconds) {
  return dir.write("hold.csv", "t_s,x_mm,y_mm,force_N\n0,110,50,4\n" + std::to_string(seconds) + ",110,50,4\n")
      .string();
}

struct RunResult {
  int exit_code;
  nlohmann::json summary;
  std::string err;
};

std::unique_ptr<WatchedProcess> start_run(const TempDir& dir, const std::string& rig, const std::string& trace,
                                          double seconds) {
  return std::make_unique<WatchedProcess>(
      std::vector<std::string>{palprig_bin(), "run", "--realtime", "--no-fifo", "--rig", rig, "--scene", kScene,
                               "--input", "trace:" + trace, "--duration-s", std::to_string(seconds), "--telemetry",
                               (dir.path() / "telemetry.csv").string(), "--json"},
      (dir.path() / "run.err").string());
}

RunResult finish_run(WatchedProcess& run, const TempDir& dir) {
  RunResult r;
  r.exit_code = run.wait();
  r.err = read_file(dir.path() / "run.err");
  std::string out = run.all_output();
  // all_output only holds what was read; read the rest of the pipe now that it closed.
  try {
    run.wait_for_line(std::regex("^\\}$"), 5.0);
    out = run.all_output();
  } catch (const std::exception&) {
    out = run.all_output();
  }
  r.summary = nlohmann::json::parse(out);
  return r;
}

// The highest pressure the simulated module has received on any channel so far.
double max_kPa_written(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);  // header
  double top = 0;
  while (std::getline(in, line)) {
    // t_s,channel,word,kPa,mono_ns; a line still being written has no mono_ns yet
    std::size_t c = 0, pos = 0;
    for (; c < 3 && (pos = line.find(',', pos)) != std::string::npos; ++c) ++pos;
    if (c == 3 && line.find(',', pos) != std::string::npos) top = std::max(top, std::stod(line.substr(pos)));
  }
  return top;
}

bool file_has(const std::filesystem::path& p, const std::string& text) {
  return read_file(p).find(text) != std::string::npos;
}

int word_unsigned(double volts, double lo, double hi, int full_scale) {
  return int(std::lround((volts - lo) / (hi - lo) * full_scale));
}

}  // namespace

TEST(ModbusEndToEnd, RunDrivesSimRigWithTheExactWordsOfTheMap) {
  TempDir dir;
  std::unique_ptr<WatchedProcess> sim;
  const std::string log = (dir.path() / "writes.csv").string();
  // The simulator serves the same map (its own address in the file is overridden by --listen).
  const auto sim_rig = dir.write("sim_rig.json", mixed_map_rig(1).dump(2)).string();
  const int port = start_sim_rig(sim, palprig_bin(), sim_rig, 0, log, (dir.path() / "sim.err").string());
  ASSERT_GT(port, 0);
  const auto rig = dir.write("rig.json", mixed_map_rig(port).dump(2)).string();
  auto run = start_run(dir, rig, write_hold_trace(dir, 2.0), 1.2);
  const RunResult r = finish_run(*run, dir);
  sim->signal(SIGTERM);
  EXPECT_EQ(sim->wait(), 0);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.summary["fault"].is_null()) << r.summary.dump();
  EXPECT_EQ(r.summary["link_outages"], 0);
  EXPECT_NE(r.summary["backend"].get<std::string>().find("modbus tcp 127.0.0.1:" + std::to_string(port)),
            std::string::npos);

  // The steady setpoints the tick computed (finger 1 is paper 002's hard nodule at 2x the
  // reference force: 2 x 11.75 = 23.5 kPa).
  const double s1 = r.summary["setpoint_kPa"][0]["max"], s2 = r.summary["setpoint_kPa"][1]["max"],
               s3 = r.summary["setpoint_kPa"][2]["max"];
  EXPECT_NEAR(s1, 23.5, 1e-9);
  // The words the simulated module received, hand-encoded: 2.35 V of 0..10 V in 32767 counts
  // = 7700.2 -> 7700; finger 2 signed over -10..10 V; finger 3 in 4095 counts.
  const int w1 = 7700;
  const int w2 = int(std::lround(s2 / 10.0 / 10.0 * 32767));
  const int w3 = word_unsigned(s3 / 10.0, 0, 10, 4095);
  const auto writes = read_csv(log);
  ASSERT_GT(writes.rows.size(), 30u);
  const std::size_t ch = writes.col("channel"), word = writes.col("word"), kpa = writes.col("kPa");
  std::array<int, 3> max_word{};
  for (const auto& row : writes.rows) {
    const auto c = std::size_t(row[ch]) - 1;
    max_word[c] = std::max(max_word[c], int(row[word]));
  }
  EXPECT_EQ(max_word[0], w1);
  EXPECT_EQ(max_word[1], w2);
  EXPECT_EQ(max_word[2], w3);
  // What the module saw per channel: 0 kPa at open, a rise that never overshoots, then only
  // setpoints some tick computed (within one count: the telemetry keeps 4 decimals), and 0 kPa
  // again at the end.
  const auto tel = read_csv((dir.path() / "telemetry.csv").string());
  const std::size_t sp[3] = {tel.col("setpoint_kPa_1"), tel.col("setpoint_kPa_2"), tel.col("setpoint_kPa_3")};
  const double count_kPa[3] = {10.0 * 10.0 / 32767, 10.0 * 20.0 / 32767, 10.0 * 10.0 / 4095};
  const int top[3] = {w1, w2, w3};
  std::array<bool, 3> reached{}, ended{};
  std::array<int, 3> previous{};
  for (const auto& row : writes.rows) {
    const auto c = std::size_t(row[ch]) - 1;
    const int w = int(row[word]);
    if (!reached[c]) {
      EXPECT_GE(w, previous[c]) << "channel " << c + 1 << " fell while rising";
      EXPECT_LE(w, top[c]);
      reached[c] = w == top[c];
    } else if (w == 0) {
      ended[c] = true;  // vented at the end of the run
    } else {
      EXPECT_FALSE(ended[c]) << "channel " << c + 1 << " pressurised again after the final vent";
      bool found = false;
      for (const auto& t : tel.rows) found = found || std::fabs(t[sp[c]] - row[kpa]) <= count_kPa[c];
      EXPECT_TRUE(found) << "channel " << c + 1 << " got " << row[kpa] << " kPa, which no tick computed";
    }
    previous[c] = w;
  }
  for (std::size_t c = 0; c < 3; ++c) EXPECT_TRUE(reached[c] && ended[c]) << "channel " << c + 1;
}

TEST(ModbusEndToEnd, KilledServerVentsReportsAndReconnectsWithoutSpike) {
  TempDir dir;
  std::unique_ptr<WatchedProcess> sim;
  const std::string rig_file = PALPRIG_SOURCE_DIR + std::string("/data/rigs/wago_750_559.json");
  const auto writes1 = dir.path() / "writes1.csv", writes2 = dir.path() / "writes2.csv";
  const int port = start_sim_rig(sim, palprig_bin(), rig_file, 0, writes1.string(), (dir.path() / "sim1.err").string());
  const auto rig = dir.write("rig.json", mixed_map_rig(port).dump(2)).string();
  // Each step waits for what the previous one caused, never for a fixed time: a sanitizer
  // build on a busy machine starts and reconnects several times slower than a release build.
  // The run is long and ended by SIGTERM once the module is back and pressurised again.
  auto run = start_run(dir, rig, write_hold_trace(dir, 120.0), 120.0);
  ASSERT_TRUE(poll_until([&] { return max_kPa_written(writes1) >= 23.5 - 0.01; }, 60.0))
      << "the run never pressurised the module: " << read_file(dir.path() / "run.err");
  sim->signal(SIGKILL);
  sim->wait();
  ASSERT_TRUE(poll_until([&] { return file_has(dir.path() / "run.err", "lost"); }, 30.0))
      << read_file(dir.path() / "run.err");
  // The scenario: the module stays away for half a second (a deliberate outage, not a wait for
  // an event), so the run spends hundreds of ticks unlinked and retries with its backoff.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  std::unique_ptr<WatchedProcess> back;
  start_sim_rig(back, palprig_bin(), rig_file, port, writes2.string(), (dir.path() / "sim2.err").string());
  ASSERT_TRUE(poll_until([&] { return max_kPa_written(writes2) >= 23.5 - 0.01; }, 60.0))
      << "the run never pressurised the returning module: " << read_file(dir.path() / "run.err");
  run->signal(SIGTERM);
  const RunResult r = finish_run(*run, dir);
  back->signal(SIGTERM);
  back->wait();

  // A lost peer is an alarm, not the end of the run: the run ends only by the SIGTERM above.
  ASSERT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.summary["fault"]["reason"], "stopped by signal") << r.summary.dump();
  EXPECT_EQ(r.summary["link_outages"], 1) << r.summary.dump();
  EXPECT_GT(r.summary["unlinked_ticks"].get<int>(), 100);
  EXPECT_NE(r.err.find("lost"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("back after"), std::string::npos) << r.err;

  const auto tel = read_csv((dir.path() / "telemetry.csv").string());
  const std::size_t t = tel.col("t_s"), fault = tel.col("fault"), flags = tel.col("flags"),
                    mon = tel.col("monitor_kPa_1");
  const std::size_t sp[3] = {tel.col("setpoint_kPa_1"), tel.col("setpoint_kPa_2"), tel.col("setpoint_kPa_3")};
  std::size_t first_alarm = 0, back_at = 0;
  for (std::size_t i = 0; i < tel.rows.size(); ++i) {
    const bool alarm = tel.rows[i][fault] == 3;  // backend_error, not latched
    if (alarm && !first_alarm) first_alarm = i;
    if (!alarm && first_alarm && !back_at) back_at = i;
    if (alarm) {
      EXPECT_TRUE(int(tel.rows[i][flags]) & 8) << "alarm without the vented flag at t=" << tel.rows[i][t];
      for (auto c : sp) EXPECT_EQ(tel.rows[i][c], 0.0) << "pressure commanded while the link was down";
      EXPECT_TRUE(std::isnan(tel.rows[i][mon]));
    }
  }
  ASSERT_GT(first_alarm, 0u);
  ASSERT_GT(back_at, first_alarm) << "never reconnected";
  // Reported within the response timeout (50 ms) of the last fresh monitor reading, allowing
  // two bus periods and slack for a busy test machine (the bus thread runs at normal priority).
  std::size_t last_fresh = first_alarm - 1;
  // A NaN monitor before the alarm is the lost link's, published just before the link is marked
  // down (see SilentServerIsDetectedByTimeoutWithoutStallingTheLoop): not a reading.
  while (last_fresh > 0 && std::isnan(tel.rows[last_fresh][mon])) --last_fresh;
  while (last_fresh > 0 && tel.rows[last_fresh][mon] == tel.rows[last_fresh - 1][mon]) --last_fresh;
  EXPECT_LE(tel.rows[first_alarm][t] - tel.rows[last_fresh][t], 0.05 + 2.0 / 500 + 0.2);
  // No spike in what the tick commanded: never more than the slew limit per tick.
  for (std::size_t i = 1; i < tel.rows.size(); ++i)
    for (auto c : sp)
      EXPECT_LE(tel.rows[i][c] - tel.rows[i - 1][c], 2000.0 * (tel.rows[i][t] - tel.rows[i - 1][t]) + 1e-3)
          << "at t=" << tel.rows[i][t];
  // ... nor in what the returning module received: 0 kPa first, then a ramp up to the setpoint
  // (arrival times on the simulator's side: two bus periods and 10 ms of scheduling slack, as
  // in tests/rigs/modbus_loopback_test.cpp).
  const auto writes = read_csv(writes2.string());
  ASSERT_GT(writes.rows.size(), 10u);
  const std::size_t wt = writes.col("t_s"), wc = writes.col("channel"), wk = writes.col("kPa");
  std::array<double, 4> last_kPa{}, last_t{};
  std::array<bool, 4> seen{};
  for (const auto& row : writes.rows) {
    const auto c = std::size_t(row[wc]);
    if (!seen[c]) {
      EXPECT_EQ(row[wk], 0.0) << "the returning module's first write on channel " << c;
      seen[c] = true;
    } else {
      EXPECT_LE(row[wk] - last_kPa[c], 2000.0 * (row[wt] - last_t[c] + 2.0 / 500 + 0.010) + 0.01) << "at t=" << row[wt];
    }
    last_kPa[c] = row[wk];
    last_t[c] = row[wt];
    EXPECT_LE(row[wk], 23.5 + 0.01);
  }
}

TEST(ModbusEndToEnd, SilentServerIsDetectedByTimeoutWithoutStallingTheLoop) {
  TempDir dir;
  std::unique_ptr<WatchedProcess> sim;
  const auto writes = dir.path() / "writes.csv";
  const auto run_err = dir.path() / "run.err";
  const int port = start_sim_rig(sim, palprig_bin(), PALPRIG_SOURCE_DIR + std::string("/data/rigs/wago_750_559.json"),
                                 0, writes.string(), (dir.path() / "sim.err").string());
  const auto rig = dir.write("rig.json", mixed_map_rig(port).dump(2)).string();
  // As above: each step waits for what the previous one caused; SIGTERM ends the run.
  auto run = start_run(dir, rig, write_hold_trace(dir, 120.0), 120.0);
  ASSERT_TRUE(poll_until([&] { return max_kPa_written(writes) >= 23.5 - 0.01; }, 60.0)) << read_file(run_err);
  sim->signal(SIGSTOP);  // alive and connected, but answers nothing: a pulled cable, a hung module
  ASSERT_TRUE(poll_until([&] { return file_has(run_err, "Connection timed out"); }, 30.0)) << read_file(run_err);
  const std::size_t writes_before = line_count(writes);
  sim->signal(SIGCONT);
  ASSERT_TRUE(
      poll_until([&] { return file_has(run_err, "back after") && line_count(writes) > writes_before + 30; }, 60.0))
      << read_file(run_err);
  run->signal(SIGTERM);
  const RunResult r = finish_run(*run, dir);
  sim->signal(SIGTERM);
  sim->wait();
  ASSERT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.summary["fault"]["reason"], "stopped by signal") << r.summary.dump();
  EXPECT_GE(r.summary["link_outages"].get<int>(), 1) << r.summary.dump();
  const auto tel = read_csv((dir.path() / "telemetry.csv").string());
  const std::size_t t = tel.col("t_s"), fault = tel.col("fault"), mon = tel.col("monitor_kPa_1");
  std::size_t first_alarm = 0;
  bool back = false;
  for (std::size_t i = 0; i < tel.rows.size(); ++i) {
    if (tel.rows[i][fault] == 3 && !first_alarm) first_alarm = i;
    if (first_alarm && tel.rows[i][fault] == 0) back = true;
  }
  ASSERT_GT(first_alarm, 0u);
  EXPECT_TRUE(back) << "never reconnected after SIGCONT";
  std::size_t last_fresh = first_alarm - 1;
  // The bus thread publishes the lost link's monitors as NaN just before it marks the link down,
  // so a tick between the two reads NaN with no alarm yet: not a reading (and NaN equals nothing,
  // which once stopped the walk below at the alarm's own tick: a silence of 1 ms, in a cold
  // make test beside the style gate).
  while (last_fresh > 0 && std::isnan(tel.rows[last_fresh][mon])) --last_fresh;
  while (last_fresh > 0 && tel.rows[last_fresh][mon] == tel.rows[last_fresh - 1][mon]) --last_fresh;
  // The response timeout is 50 ms: the alarm comes after it, and not much later. Both ends are
  // seen by the loop's ticks, so a tick that ran late on a busy machine (a sanitizer build
  // beside other suites) sees the last fresh reading late and shortens the silence measured:
  // the lower bound allows 25 ms of that.
  const double silence = tel.rows[first_alarm][t] - tel.rows[last_fresh][t];
  EXPECT_GE(silence, 0.025);
  EXPECT_LE(silence, 0.05 + 2.0 / 500 + 0.2);
  // The loop never waited for the bus: its backend calls stayed far below the 50 ms the bus
  // thread spent waiting (a blocking design would show >= 50 ms here).
  EXPECT_LT(r.summary["io_time"]["max_us"].get<double>(), 25000.0) << r.summary["io_time"].dump();
}

TEST(ModbusEndToEnd, SimRigWantsOneListenAddressPerLink) {
  const auto r = run_process(palprig_bin() + " sim-rig --rig " + PALPRIG_SOURCE_DIR +
                             "/data/rigs/moxa_iologik_e1241.json --listen 127.0.0.1:0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("one HOST:PORT per link"), std::string::npos) << r.err;
  const auto s = run_process(palprig_bin() + " sim-rig --rig " + PALPRIG_SOURCE_DIR +
                             "/data/rigs/simulated.json --listen 127.0.0.1:0");
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("\"modbus\""), std::string::npos) << s.err;
}

TEST(ModbusEndToEnd, RunRefusesReplayOnHardware) {
  const auto r = run_process(palprig_bin() + " run --replay --rig " + PALPRIG_SOURCE_DIR +
                             "/data/rigs/wago_750_559.json --scene " + kScene + " --duration-s 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--realtime"), std::string::npos) << r.err;
}
