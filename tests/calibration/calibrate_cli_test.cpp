// `palprig calibrate` end to end with the real program: the workflow on the default simulated
// rig, the p_max clamp, Ctrl-C during a real-time sweep (a real SIGINT to a real process),
// and refused input (exit 2, one line).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/run_process.hpp"

using namespace palprig::test_support;

namespace {

std::string palprig_cmd() { return palprig_bin(); }

std::size_t count_lines(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

double highest_command(const std::string& csv) {
  std::istringstream in(csv);
  double top = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::istringstream row(line);
    std::string cell;
    for (int i = 0; i < 7; ++i) std::getline(row, cell, ',');  // command_kPa is the 7th
    top = std::max(top, std::stod(cell));
  }
  return top;
}

}  // namespace

TEST(CalibrateCli, SweepFitEvaluateOnTheDefaultSimulatedRig) {
  TempDir dir;
  const std::string data = (dir.path() / "data.csv").string(), cal = (dir.path() / "cal.json").string();
  const ProcessResult sweep =
      run_process(palprig_cmd() + " calibrate sweep --excitation staircase,random,sine --out " + data);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_NE(sweep.out.find("193 of 193 holds (0 not settled)"), std::string::npos) << sweep.out;
  EXPECT_NE(sweep.err.find("note: the rig's p_max is 60 kPa: sweep levels above it are clamped to 60 kPa"),
            std::string::npos);
  EXPECT_NE(sweep.err.find("sweep: staircase repeat 5/5"), std::string::npos) << sweep.err;
  EXPECT_DOUBLE_EQ(highest_command(read_file(data)), 60.0);

  const ProcessResult fit = run_process(palprig_cmd() + " calibrate fit " + data + " --out " + cal);
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.out.find("  all      both        180"), std::string::npos) << fit.out;
  EXPECT_EQ(count_lines(fit.out, "  channel 1: from monitor, 193 holds"), 1u) << fit.out;
  const auto doc = nlohmann::json::parse(read_file(cal));
  EXPECT_EQ(doc["rig_id"], "sim-default");
  EXPECT_EQ(doc["version"], 1);
  EXPECT_EQ(doc["channels"].size(), 3u);

  const ProcessResult ev =
      run_process(palprig_cmd() + " calibrate evaluate --cal " + cal + " --duration-s 60 --min-improvement 5 --json");
  ASSERT_EQ(ev.exit_code, 0) << ev.err << ev.out;
  const auto r = nlohmann::json::parse(ev.out);
  EXPECT_GE(r["worst_improvement"].get<double>(), 5.0);
  EXPECT_TRUE(r["complete"].get<bool>());
  for (const auto& ch : r["channels"]) {
    EXPECT_GT(ch["uncompensated"]["gap_kPa"].get<double>(), 3.0);
    EXPECT_LT(std::abs(ch["compensated"]["gap_kPa"].get<double>()), 0.3);
  }
  // The controller runs with it: `palprig run` accepts the file for this rig.
  const ProcessResult run = run_process(palprig_cmd() + " run --scene " + source_dir() +
                                        "/data/scenes/phantom_abc.json --cal " + cal + " --duration-s 2");
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

// A staircase too short for a fit is said before the sweep runs (the sweep still runs: a short
// check of the link is a use), and what it says is true: the fit refuses that recording.
TEST(CalibrateCli, ASweepTooShortToFitIsSaidBeforeItRunsAndTheFitAgrees) {
  TempDir dir;
  const std::string data = (dir.path() / "short.csv").string();
  const ProcessResult sweep =
      run_process(palprig_cmd() + " calibrate sweep --from-kPa 10 --to-kPa 20 --repeats 1 --out " + data);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_NE(sweep.err.find("palprig: warning: this sweep is too short to fit: the inflation staircase has 2 holds over "
                           "all repeats and a line needs 3"),
            std::string::npos)
      << sweep.err;
  EXPECT_LT(sweep.err.find("warning: this sweep"), sweep.err.find("sweep: staircase repeat 1/1")) << sweep.err;
  const ProcessResult fit =
      run_process(palprig_cmd() + " calibrate fit " + data + " --out " + (dir.path() / "c.json").string());
  EXPECT_EQ(fit.exit_code, 2) << fit.err;
  EXPECT_NE(fit.err.find("at least 3 points for a line, got 2"), std::string::npos) << fit.err;
  // Paper 002's staircase is long enough: nothing said.
  const ProcessResult full =
      run_process(palprig_cmd() + " calibrate sweep --repeats 1 --out " + (dir.path() / "full.csv").string());
  ASSERT_EQ(full.exit_code, 0) << full.err;
  EXPECT_EQ(full.err.find("too short"), std::string::npos) << full.err;
}

TEST(CalibrateCli, CtrlCDuringARealTimeSweepVentsAndKeepsTheRows) {
  TempDir dir;
  const std::string data = (dir.path() / "data.csv").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string bin = palprig_cmd();
    const std::string err = (dir.path() / "stderr").string();
    freopen(err.c_str(), "w", stderr);
    freopen("/dev/null", "w", stdout);
    execl(bin.c_str(), bin.c_str(), "calibrate", "sweep", "--realtime", "--out", data.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1800));  // a few holds in real time
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = read_file(dir.path() / "stderr");
  EXPECT_NE(err.find("palprig: sweep stopped by signal 2 after "), std::string::npos) << err;
  EXPECT_NE(err.find("holds; all channels vented; what was recorded is in " + data), std::string::npos) << err;
  const std::string csv = read_file(data);
  EXPECT_NE(csv.find("# stopped: signal 2; channels vented; the rows above were kept"), std::string::npos) << csv;
  EXPECT_GT(count_lines(csv, "0."), 50u);  // rows of the first holds (t_s < 1 s)
  EXPECT_NE(csv.find(",staircase,1,inflation,10.0000,"), std::string::npos);
}

TEST(CalibrateCli, RefusedInputExitsTwoWithOneLine) {
  TempDir dir;
  auto one_line = [](const ProcessResult& r) { return r.err.find('\n') == r.err.size() - 1; };
  const auto bad = dir.write("bad.csv", "# rig_id: sim-default\nchannel,command_kPa,monitor_kPa\n1,10,8\n1,20,nan\n");
  ProcessResult r =
      run_process(palprig_cmd() + " calibrate fit " + bad.string() + " --out " + (dir.path() / "c.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: " + bad.string() + ": line 4: a finite number in column monitor_kPa, got \"nan\"\n");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "c.json"));

  r = run_process(palprig_cmd() + " calibrate sweep --channels 1,4 --out " + (dir.path() / "d.csv").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: --channels: 1,4: channel numbers 1..3 separated by commas\n");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "d.csv"));  // refused before anything moved

  // A calibration made on another rig.
  const std::string ch = R"({"actuator": {"slope": 0.25, "intercept_kPa": 5},)"
                         R"( "hysteresis": {"linear_weight": 0.5, "thresholds_kPa": [2], "weights": [0.5]}})";
  const auto other =
      dir.write("other.json", R"({"version": 1, "rig_id": "bench-A", "channels": [)" + ch + "," + ch + "," + ch + "]}");
  r = run_process(palprig_cmd() + " calibrate evaluate --cal " + other.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(one_line(r)) << r.err;
  EXPECT_NE(r.err.find(other.string() + ": rig_id: the id of the rig in use (\"sim-default\""), std::string::npos)
      << r.err;

  // A calibration file of a newer version.
  const auto newer = dir.write("newer.json", R"({"version": 2, "rig_id": "sim-default", "channels": []})");
  r = run_process(palprig_cmd() + " calibrate evaluate --cal " + newer.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(one_line(r)) << r.err;
  EXPECT_NE(r.err.find(newer.string() + ": version"), std::string::npos) << r.err;

  // Hardware can't be hurried.
  r = run_process(palprig_cmd() + " calibrate sweep --fast --rig " + source_dir() +
                  "/data/rigs/wago_750_559.json --out " + (dir.path() / "d.csv").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: --fast: modbus: a simulated rig (hardware runs in real time)\n");
}

// The calibration library names option fields (to_kPa, `from_kPa` in prose); the command line
// prints the flags the user typed, in the file, field and text of the refusal alike.
TEST(CalibrateCli, RefusalsNameTheFlagsTheUserTyped) {
  TempDir dir;
  ProcessResult r = run_process(palprig_cmd() + " calibrate sweep --from-kPa 30 --to-kPa 20 --out " +
                                (dir.path() / "d.csv").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: --to-kPa: value: a pressure above --from-kPa\n");
  r = run_process(palprig_cmd() + " calibrate sweep --repeats 0 --out " + (dir.path() / "d.csv").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: --repeats: value: 1 to 100 repeats\n");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "d.csv"));
}

TEST(CalibrateCli, PlotWritesPngFilesOrIsRefusedWithoutTheChartDrawing) {
  TempDir dir;
  const std::string data = (dir.path() / "data.csv").string(), cal = (dir.path() / "cal.json").string();
  ASSERT_EQ(
      run_process(palprig_cmd() + " calibrate sweep --excitation staircase,random --quiet --out " + data).exit_code, 0);
  const std::string plots = (dir.path() / "plots").string();
  const ProcessResult fit =
      run_process(palprig_cmd() + " calibrate fit " + data + " --out " + cal + " --plot " + plots);
  if (fit.exit_code == 2) {
    // A build without Qt: refused before anything is written.
    EXPECT_EQ(fit.err, "palprig: --plot: " + plots +
                           ": a build with the chart drawing (configure with -DPALPRIG_GUI=ON; needs Qt6)\n");
    EXPECT_FALSE(std::filesystem::exists(cal));
    return;
  }
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(fit.err, "");  // Qt's offscreen set-up stays quiet
  for (const char* name : {"channel_1_regulator.png", "channel_2_hysteresis.png", "channel_3_regulator.png"}) {
    const std::string png = read_file(dir.path() / "plots" / name);
    ASSERT_GT(png.size(), 1000u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG") << name;
  }
  const ProcessResult ev =
      run_process(palprig_cmd() + " calibrate evaluate --cal " + cal + " --duration-s 20 --plot " + plots);
  ASSERT_EQ(ev.exit_code, 0) << ev.err;
  EXPECT_EQ(read_file(dir.path() / "plots" / "evaluate_channel_2_loops.png").substr(1, 3), "PNG");
}
