// A loop that cannot hold its rate faults and vents within
// safety.max_lost_time_s of lost periods, whether its overruns come in a row or not, in real time
// and in a replay (judged there by the tick's CPU time, so a replay cannot run for hours).
#include <gtest/gtest.h>

#include <time.h>

#include <memory>

#include "controller/loop_runner.hpp"
#include "models/tissue_scene.hpp"
#include "tests/support/rigs_for_tests.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;
using test_rigs::RecordingRig;
using test_rigs::RestingPen;

namespace {

// A function scene built in code (the scene loader refuses it, see
// tests/formats/scene_cost_bound_test.cpp): 64 inclusions, each the intersection of 2000 large
// spheres whose boxes hold the pen's neighbourhood but whose insides do not, so every one of
// the tick's ~360 sampled points visits all 128,000 spheres: a tenth of a second or more per
// tick.
std::unique_ptr<FunctionScene> slow_function_scene() {
  TissueDefinition t;
  t.body = {{100, 60}, 80, 60, 6};
  t.layers = {{"skin", 2, 14.7}, {"fat", 40, 16}};
  t.felt = {14.7, 21.9};
  for (int i = 0; i < 64; ++i) {
    Inclusion inc;
    inc.name = "slow-" + std::to_string(i);
    inc.stiffness_kPa = 21.9;
    std::vector<FrepShape::Node> parts;
    parts.reserve(2000);
    for (int k = 0; k < 2000; ++k) parts.push_back(inc.shape.sphere({100 - 350 + 0.001 * k, 60 - 350, -350}, 400));
    inc.shape.intersect(parts);
    t.inclusions.push_back(std::move(inc));
  }
  return std::make_unique<FunctionScene>(std::move(t), std::vector<ArterySpec>{});
}

std::int64_t cpu_now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

// Costs spin_ms of CPU on every other tick (its three samples), nothing on the others: its
// overruns never come two in a row, so the consecutive-overrun limit alone never fires.
class IntermittentlySlowScene final : public Scene {
 public:
  explicit IntermittentlySlowScene(double spin_ms) : spin_ns_(std::int64_t(spin_ms * 1e6)) {}
  TissueSample sample(const Point2_mm&, double, double t_s) const noexcept override {
    if (++calls_ % 6 == 1) {  // the first finger of every other tick
      (void)t_s;
      const std::int64_t end = cpu_now_ns() + spin_ns_;
      while (cpu_now_ns() < end) {}
    }
    return {0.5, -1};
  }
  SceneBounds bounds() const noexcept override { return {0, 0, 200, 120}; }

 private:
  std::int64_t spin_ns_;
  mutable std::uint64_t calls_ = 0;
};

RunOptions realtime_options(double seconds) {
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.want_fifo = false;
  opt.duration_s = seconds;
  return opt;
}

}  // namespace

TEST(LostTime, ASlowFunctionSceneFaultsAndVentsInRealTime) {
  const auto scene = slow_function_scene();
  TickConfig cfg;  // default limits: 20 consecutive overruns, 50 ms of lost time
  RecordingRig rig;
  rig.open();
  RestingPen pen(100, 60);
  const RunSummary s = palprig::testing::run_loop_leased(cfg, *scene, pen, rig, realtime_options(3.0));
  // Before: every tick overran by 100+ periods, the run reached its end before 20 of them in a
  // row and reported no fault. Now the first tick's lost periods exceed 50 ms, so the run ends
  // there: at most two ticks. (No bound on the wall time: one tick of this scene is 0.3 s of
  // CPU, several times that under a sanitizer on a loaded machine; the tick count is what says
  // the run did not go on.)
  EXPECT_EQ(s.fault, FaultCode::lost_time_limit) << to_string(s.fault);
  EXPECT_NE(s.fault.detail().find("max_lost_time_s"), std::string::npos) << s.fault.detail();
  EXPECT_LE(s.ticks, 2u) << "the run went on after the limit";
  EXPECT_EQ(rig.last, (ChannelPressures{0, 0, 0}));  // vented
  EXPECT_GE(rig.vents, 1);
}

TEST(LostTime, ASlowFunctionSceneFaultsInReplayInsteadOfRunningForHours) {
  const auto scene = slow_function_scene();
  TickConfig cfg;
  RecordingRig rig;
  rig.open();
  RestingPen pen(100, 60);
  RunOptions opt;         // replay, simulated time
  opt.duration_s = 10.0;  // 10,000 ticks of 0.1 s or more each: hours without the bound
  const RunSummary s = palprig::testing::run_loop_leased(cfg, *scene, pen, rig, opt);
  // Two ticks at most, so the run ended within seconds instead of hours (the tick count says it;
  // a wall-clock bound would not hold under a sanitizer on a busy machine).
  EXPECT_EQ(s.fault, FaultCode::lost_time_limit) << to_string(s.fault);
  EXPECT_LE(s.ticks, 2u);
  EXPECT_EQ(rig.last, (ChannelPressures{0, 0, 0}));
}

TEST(LostTime, OverrunsThatNeverComeInARowStillFaultWithinTheBound) {
  // Every other tick costs 5 ms: it loses about 5 periods and the next tick is on time again.
  IntermittentlySlowScene scene(5.0);
  TickConfig cfg;  // default 20 consecutive overruns: never reached, the overruns alternate
  RecordingRig rig;
  rig.open();
  RestingPen pen(100, 60);
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, realtime_options(3.0));
  EXPECT_EQ(s.fault, FaultCode::lost_time_limit) << to_string(s.fault) << " " << s.fault.detail();
  // About 10 slow ticks lose 50 ms: the fault comes within a fraction of a second, not at the
  // end of the 3 s run (and not never, as before).
  EXPECT_LT(s.fault.t_s, 1.0);
  EXPECT_GE(s.missed_periods, 45u);
  EXPECT_EQ(rig.last, (ChannelPressures{0, 0, 0}));
}

TEST(LostTime, ReplayOfTheSameSceneFaultsTooAndTheLimitIsTheRigFilesSetting) {
  IntermittentlySlowScene scene(3.0);  // every other tick 3 ms of CPU
  TickConfig cfg;
  cfg.safety.max_lost_time_s = 0.2;
  RecordingRig rig;
  rig.open();
  RestingPen pen(100, 60);
  RunOptions opt;
  opt.duration_s = 10.0;
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::lost_time_limit);
  // A 3 ms tick loses the 3 periods a real-time loop would skip: 0.2 s after about 67 slow
  // ticks, one tick in two (2 periods, 100 slow ticks, should a preemption between two ticks
  // make the CPU estimate fall short of 3 ms).
  EXPECT_GE(s.ticks, 120u);
  EXPECT_LE(s.ticks, 210u);
}

TEST(LostTime, AFastReplayLosesNothing) {
  IntermittentlySlowScene scene(0.0);
  TickConfig cfg;
  RecordingRig rig;
  rig.open();
  RestingPen pen(100, 60);
  RunOptions opt;
  opt.duration_s = 2.0;
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::none) << s.fault.detail();
  EXPECT_EQ(s.ticks, 2000u);
}
