// The command line of tracked fingers, as a user runs it: `palprig igtl-replay` as a
// real server process and `palprig run --input igtl:...` against it with the per-region table;
// the tracking commands; the load-cell commands; and the refusals, each one line, exit 2.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <thread>

#include <nlohmann/json.hpp>

#include "calibration/force_window.hpp"
#include "formats/tracking_file.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;
using palprig::testing::ChildProcess;
using palprig::testing::run_palprig;

namespace {

const std::string kData = std::string(PALPRIG_SOURCE_DIR) + "/data";

// A replay server process on a free port; its port once it listens.
int start_replay(ChildProcess& server) {
  std::smatch m;
  const std::regex listening("listening on port ([0-9]+)");
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < end) {
    server.pump(20);
    const std::string out = server.out();
    if (std::regex_search(out, m, listening)) return std::stoi(m[1]);
  }
  return 0;
}

// The first `seconds` of the shipped three-finger pass (tumor B is pressed from 1.0 to 2.6 s).
std::string head_of_pass(const TempDir& dir, double seconds) {
  std::ifstream in(kData + "/tracking/phantom_three_fingers_pass.csv");
  std::string line, text;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#' && line[0] != 't' && std::stod(line) > seconds) break;
    text += line + "\n";
  }
  return dir.write("head.csv", text).string();
}

}  // namespace

// The shipped rig with load cells, patient with a shared machine: lost periods, overruns and a
// tracker reader that was not scheduled for a while are not what this test is about (a busy CI
// machine loses 50 ms now and then, and a virtual machine's CPU can stall 100 ms: the reader's
// heartbeat then goes stale and the loop vents, "pen input stale"). The pass's first 3 s have no
// tool out of view, so a second's input age changes nothing else.
std::string patient_rig(const TempDir& dir) {
  auto rig = nlohmann::json::parse(test_support::read_file(kData + "/rigs/simulated_load_cells.json"));
  rig["safety"]["max_consecutive_overruns"] = 100000;
  rig["safety"]["max_lost_time_s"] = 10;
  rig["safety"]["max_input_age_s"] = 1.0;
  return dir.write("rig.json", rig.dump(2)).string();
}

TEST(TrackingCli, RunOverAReplayedTrackerPrintsThePerRegionTable) {
  TempDir dir;
  ChildProcess server({"igtl-replay", "--poses", head_of_pass(dir, 3.0), "--port", "0", "--duration-s", "60"});
  const int port = start_replay(server);
  ASSERT_GT(port, 0) << server.out() << server.err();
  const auto r = run_palprig({"run", "--input", "igtl:127.0.0.1:" + std::to_string(port), "--tracking",
                              kData + "/tracking/tracking_three_fingers.json", "--rig", patient_rig(dir), "--scene",
                              kData + "/scenes/phantom_abc.json", "--duration-s", "3", "--regions", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["input"], "tracker igtl:127.0.0.1:" + std::to_string(port) +
                            " (Finger1ToTracker, Finger2ToTracker, Finger3ToTracker)");
  EXPECT_EQ(j["mode"], "realtime");
  EXPECT_TRUE(j["fault"].is_null());
  // Finger 2 pressed tumor B: its region's target is paper 002's hard nodule; soft tissue ~0.
  const auto& regions = j["regions"];
  ASSERT_EQ(regions.size(), 4u);
  EXPECT_EQ(regions[1]["region"], "tumor B");
  EXPECT_GT(regions[1]["finger_ticks"].get<int>(), 800);
  EXPECT_GT(regions[1]["target_kPa_mean"].get<double>(), 10.0);
  EXPECT_EQ(regions[0]["finger_ticks"].get<int>(), 0);  // A and C come later in the pass
  EXPECT_TRUE(regions[0]["target_kPa_mean"].is_null()) << "a region not reached has no figure, not a 0";
  // Soft tissue: pressed on by the fingers beside B (a hard nodule's target is not theirs), or
  // not reached in these 3 s.
  if (regions[3]["finger_ticks"].get<int>() > 0)
    EXPECT_LT(regions[3]["target_kPa_mean"].get<double>(), 1.0);
  else
    EXPECT_TRUE(regions[3]["target_kPa_mean"].is_null());
  // 4 mm deep on 0.5 N/mm; the recording's 0.1 mm of tracker noise and the finger's tilt add a little.
  EXPECT_NEAR(j["tracked_fingers"][1]["force_N"]["max"].get<double>(), 2.0, 0.25);
  ::kill(server.pid(), SIGTERM);
  EXPECT_EQ(server.finish().exit_code, 0);
}

TEST(TrackingCli, RefusalsAreOneLineBeforeAnythingMoves) {
  const std::vector<std::string> base = {"run", "--scene", kData + "/scenes/phantom_abc.json", "--duration-s", "1"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return run_palprig(args);
  };
  auto r = with({"--input", "igtl:127.0.0.1:9", "--rig", kData + "/rigs/simulated_load_cells.json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(
      r.err,
      "palprig: tracking: input igtl:127.0.0.1:9: a tracking file (--tracking FILE) that maps the tracker's tools "
      "to fingers (docs/tracking.md)\n");
  r = with({"--input", "igtl:127.0.0.1:9", "--tracking", kData + "/tracking/tracking_three_fingers.json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(
      r.err.find("simulated.json: load_cells: load cells measuring the pressing force, for input igtl:127.0.0.1:9"),
      std::string::npos)
      << r.err;
  r = with({"--input", "igtl:127.0.0.1:9", "--tracking", kData + "/tracking/tracking_three_fingers.json", "--rig",
            kData + "/rigs/simulated_load_cells.json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("input igtl: 127.0.0.1:9: a running OpenIGTLink server"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot connect: Connection refused"), std::string::npos) << r.err;
  EXPECT_EQ(palprig::testing::count_lines(r.err), 1);
  r = with({"--input", "sweep", "--tracking", kData + "/tracking/tracking_three_fingers.json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--input igtl:HOST:PORT with it"), std::string::npos) << r.err;
  r = with({"--input", "igtl:nowhere", "--tracking", kData + "/tracking/tracking_three_fingers.json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("igtl:HOST:PORT"), std::string::npos) << r.err;
}

TEST(TrackingCli, RegisterFromTouchedPointsAndPivotOverAReplayedSession) {
  TempDir dir;
  // Offline: the touched points are in the file (a 90-degree turn and a shift, 0.1 mm off).
  const auto fid =
      dir.write("fid.csv",
                "name,x_mm,y_mm,z_mm,tracker_x_mm,tracker_y_mm,tracker_z_mm\n"
                "F1,10,10,0,-10,10.1,0\nF2,150,10,0,-10,150,0\nF3,150,110,0,-110,150,0.1\nF4,10,110,5,-110,10,5\n");
  const std::string out = (dir.path() / "reg.json").string();
  auto r = run_palprig({"tracking", "register", "--tracking", kData + "/tracking/tracking_stylus.json", "--fiducials",
                        fid.string(), "--out", out});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("FRE 0.0"), std::string::npos) << r.out;
  const TrackingConfig t = load_tracking_file(out);
  EXPECT_EQ(t.registration.fiducials, 4);
  EXPECT_LT(t.registration.fre_mm, 0.1);
  EXPECT_NEAR(t.registration.tracker_to_scene.rotation[0][1], 1, 1e-3);  // tracker y is scene x
  // A bad touch: refused and not written.
  const auto bad =
      dir.write("bad.csv",
                "name,x_mm,y_mm,z_mm,tracker_x_mm,tracker_y_mm,tracker_z_mm\n"
                "F1,10,10,0,-10,10,0\nF2,150,10,0,-10,150,0\nF3,150,110,0,-110,150,0\nF4,10,110,5,-80,30,5\n");
  r = run_palprig({"tracking", "register", "--tracking", kData + "/tracking/tracking_stylus.json", "--fiducials",
                   bad.string(), "--out", (dir.path() / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("is over --max-fre-mm 2.00"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad.json"));

  // Live: the shipped pivot session served by a real replay process.
  ChildProcess server(
      {"igtl-replay", "--poses", kData + "/tracking/pivot_finger1.csv", "--port", "0", "--duration-s", "60"});
  const int port = start_replay(server);
  ASSERT_GT(port, 0);
  const std::string pivoted = (dir.path() / "pivot.json").string();
  r = run_palprig({"tracking", "pivot", "--igtl", "127.0.0.1:" + std::to_string(port), "--tracking",
                   kData + "/tracking/tracking_three_fingers.json", "--tool", "Finger1ToTracker", "--seconds", "2",
                   "--out", pivoted});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const TrackingConfig p = load_tracking_file(pivoted);
  // tools/make_tracking_data.py put the tip 12 mm along the sensor's -z.
  EXPECT_NEAR(p.tools[0].tip.offset_mm[0], 0, 0.5);
  EXPECT_NEAR(p.tools[0].tip.offset_mm[2], -12, 0.5);
  EXPECT_EQ(p.tools[0].tip.method, "pivot");
  EXPECT_LT(p.tools[0].tip.rms_mm, 0.5);
  ::kill(server.pid(), SIGTERM);
  EXPECT_EQ(server.finish().exit_code, 0);
}

TEST(TrackingCli, LoadCellReadAndPressOnTheSimulatedRig) {
  TempDir dir;
  const std::string rig = kData + "/rigs/simulated_load_cells.json";
  auto r = run_palprig({"load-cell", "read", "--rig", rig, "--seconds", "1", "--load-N", "5", "--known-N", "5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("3 cells, 100 readings each"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("5.000 N on it: its N_per_V is 2.00"), std::string::npos) << r.out;
  const std::string presses = (dir.path() / "presses.csv").string();
  ASSERT_EQ(run_palprig({"load-cell", "press", "--rig", rig, "--mmHg", "60", "--load-N", "1.2", "--presses", presses})
                .exit_code,
            0);
  ASSERT_EQ(run_palprig({"load-cell", "press", "--rig", rig, "--mmHg", "120", "--load-N", "2.4", "--presses", presses})
                .exit_code,
            0);
  const std::string text = test_support::read_file(presses);
  EXPECT_TRUE(std::regex_match(text, std::regex("reference_mmHg,force_N\n60,1\\.(2|19)[0-9]*\n120,2\\.(4|39)[0-9]*\n")))
      << text;
  // The presses are what `calibrate fit --force-presses` reads: paper 003's force window.
  const ForceWindowFit window = force_window_from_presses(presses);
  EXPECT_NEAR(window.window.f_min_N, 1.2, 0.01);
  EXPECT_NEAR(window.window.f_max_N, 2.4, 0.01);
  r = run_palprig({"load-cell", "read", "--rig", kData + "/rigs/simulated.json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("simulated.json: load_cells: a \"load_cells\" section"), std::string::npos) << r.err;
}
