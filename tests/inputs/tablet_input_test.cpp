// The tablet reader thread, fed by a shipped evemu recording replayed in real time: the loop
// sees the stroke, a silent pen is not stale, an input that stops is, and `palprig run` takes
// the recording through the same path as a live tablet.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include <nlohmann/json.hpp>

#include "controller/loop_runner.hpp"
#include "formats/rig_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "inputs/tablet_input.hpp"
#include "runtime/worker_fault.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/leased_run.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig;
using namespace std::chrono_literals;

namespace {

MapScene uniform_scene(float stiffness) {
  return MapScene(StiffnessMap(11, 11, 200, 200, std::vector<float>(121, stiffness)), MapSampling::nearest);
}

}  // namespace

TEST(TabletInput, TheLoopSeesTheRecordedStrokeAndASilentPenStaysFresh) {
  TabletInput input(std::make_unique<EvemuPenSource>(palprig::testing::evemu_fixture("pen_stroke.evemu")),
                    TabletConfig{});
  EXPECT_NEAR(input.duration_s(), 0.95, 1e-9);
  EXPECT_NE(input.describe().find("pen_stroke.evemu"), std::string::npos);
  double max_force = 0, max_age = 0;
  bool lifted_after_press = false, pressed_again = false, pressed = false;
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (t > 1.0) break;
    const TouchSample s = input.latest(t);
    max_force = std::max(max_force, s.force_N);
    max_age = std::max(max_age, t - s.t_s);
    if (s.in_contact) {
      pressed = true;
      EXPECT_GE(s.x_mm, 50.0);
      EXPECT_LE(s.x_mm, 90.0);
      EXPECT_DOUBLE_EQ(s.y_mm, 90.0);
      if (lifted_after_press) pressed_again = true;
    } else if (pressed) {
      lifted_after_press = true;
    }
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_TRUE(pressed);
  EXPECT_TRUE(lifted_after_press);
  EXPECT_FALSE(pressed_again);
  EXPECT_NEAR(max_force, 3072.0 / 4095.0 * 4.0, 1e-9);
  // The device is silent from 0.75 s to 0.95 s (out of proximity), yet the reader's heartbeat
  // keeps the sample younger than the loop's 0.1 s limit.
  EXPECT_LT(max_age, 0.1);
  EXPECT_GT(input.frames(), 100u);
}

TEST(TabletInput, AnInputThatStopsIsStaleAndTheLoopVents) {
  clear_worker_faults();
  TabletInput input(std::make_unique<EvemuPenSource>(palprig::testing::evemu_fixture("pen_stroke.evemu")),
                    TabletConfig{});
  const RigConfig rig = default_rig();
  SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
  backend.open();
  TickConfig config;
  config.safety.max_input_age_s = 0.1;
  config.safety.max_consecutive_overruns = 1000000;  // a busy test machine must not end it first
  config.safety.max_lost_time_s = 10;
  const MapScene scene = uniform_scene(1.0f);
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.want_fifo = false;
  opt.rate_hz = 500;
  opt.duration_s = 1.6;  // the recording ends at 0.95 s
  const RunSummary s = palprig::testing::run_loop_leased(config, scene, input, backend, opt);
  EXPECT_EQ(s.fault, FaultCode::input_stale);
  EXPECT_GE(s.fault.t_s, 0.95 + 0.1 - 0.02);
  EXPECT_LE(s.fault.t_s, 0.95 + 0.1 + 0.3);
  EXPECT_GT(s.setpoint_kPa[0].max, 0.0);  // the stroke pressed a hard map
}

TEST(TabletInput, RunReplaysARecordingThroughTheLiveReader) {
  using palprig::test_support::run_process;
  // The default simulated rig, tolerant of a busy test machine's missed deadlines.
  palprig::test_support::TempDir dir;
  auto rig = nlohmann::json::parse(
      palprig::test_support::read_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated.json"));
  rig["safety"]["max_consecutive_overruns"] = 1000000;
  rig["safety"]["max_lost_time_s"] = 10;
  const auto rig_path = dir.write("rig.json", rig.dump(2));
  const auto r = run_process(palprig::test_support::palprig_bin() + " run --no-fifo --rig " + rig_path.string() +
                             " --scene " + PALPRIG_SOURCE_DIR + "/data/scenes/phantom_abc.json --input tablet:" +
                             palprig::testing::evemu_fixture("pen_stroke.evemu") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mode"], "realtime");  // live input always runs on the wall clock
  EXPECT_NE(j["input"].get<std::string>().find("pen recording"), std::string::npos);
  EXPECT_NEAR(j["sim_time_s"].get<double>(), 0.95, 0.01);
  EXPECT_GT(j["target_kPa"][0]["max"].get<double>(), 5.0);  // the stroke crosses tumor C at 3 N
  EXPECT_TRUE(j["fault"].is_null());
}

TEST(TabletInput, MissingDevicesAreOneLineAndExitTwo) {
  using palprig::test_support::run_process;
  const std::string base = palprig::test_support::palprig_bin() + " run --scene " + PALPRIG_SOURCE_DIR +
                           "/data/scenes/phantom_abc.json --duration-s 1 --input ";
  const auto a = run_process(base + "tablet:/dev/input/event_palprig_absent");
  EXPECT_EQ(a.exit_code, 2);
  EXPECT_NE(a.err.find("/dev/input/event_palprig_absent"), std::string::npos) << a.err;
  EXPECT_EQ(std::count(a.err.begin(), a.err.end(), '\n'), 1) << a.err;
  const auto b = run_process(base + "tablet:/dev/null");
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_NE(b.err.find("a pen tablet"), std::string::npos) << b.err;
  if (!std::filesystem::exists("/dev/input")) {  // this machine has no input devices at all
    const auto c = run_process(base + "tablet");
    EXPECT_EQ(c.exit_code, 2);
    EXPECT_NE(c.err.find("a pen tablet under /dev/input"), std::string::npos) << c.err;
  }
}
