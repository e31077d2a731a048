// RigStep: the one path from targets to the regulators (tick, write, monitors, faults, vent),
// and what it means for the loop and the other callers: pressure rises from the vented state on
// the first tick and after every re-arm, a disarmed backend is vented and read, a
// backend error vents with the backend's words, a closed backend moves nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "controller/loop_runner.hpp"
#include "controller/rig_step.hpp"
#include "rigs/simulated_rig.hpp"
#include "tests/support/rigs_for_tests.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;

using test_rigs::hard_right_scene;
using test_rigs::quiet_plants;
using test_rigs::RecordingRig;
using test_rigs::RestingPen;

namespace {

class StepRecorder final : public TickObserver {
 public:
  std::vector<TelemetryRecord> records;
  void on_tick(const TelemetryRecord& r) noexcept override { records.push_back(r); }
};

}  // namespace

// A pen already pressed on a tumor when a run started once sent the full target (11.75 kPa)
// in one tick to vented regulators. Now the first tick rises by one slew step (2000 kPa/s over
// 1 ms = 2 kPa) and the setpoint ramps from there.
TEST(RigStep, APenAlreadyPressedWhenTheRunStartsRampsFromVented) {
  const auto scene = hard_right_scene();
  SimulatedRig rig(quiet_plants(), 60);
  rig.open();
  RestingPen pen;
  StepRecorder rec;
  RunOptions opt;
  opt.duration_s = 0.05;
  opt.observer = &rec;
  const RunSummary s = palprig::testing::run_loop_leased(TickConfig{}, scene, pen, rig, opt);
  ASSERT_EQ(s.fault, FaultCode::none);
  ASSERT_EQ(rec.records.size(), 50u);
  EXPECT_NEAR(rec.records[0].target_kPa[1], 11.75, 1e-4);
  EXPECT_NEAR(rec.records[0].setpoint_kPa[1], 2.0, 1e-4);
  EXPECT_TRUE(rec.records[0].flags & kSlewLimited);
  for (std::size_t i = 1; i < rec.records.size(); ++i)
    EXPECT_LE(rec.records[i].setpoint_kPa[1] - rec.records[i - 1].setpoint_kPa[1], 2.0f + 1e-4f) << i;
  EXPECT_NEAR(rec.records[10].setpoint_kPa[1], 11.75, 1e-4);  // reached after 6 ticks
  EXPECT_EQ(rig.state(), BackendState::disarmed);             // the run disarms at its end
}

namespace {
// A rig whose I/O thread (as Modbus's) vented it on its own between two steps, the vent over
// before linked() could show it: only forced_vents() tells.
class SelfVentingRig final : public RecordingRig {
 public:
  std::uint64_t vents_on_its_own = 0;
  std::uint64_t forced_vents() const noexcept override { return vents_on_its_own; }
};
}  // namespace

// A machine stalled the loop past the bus's setpoint timeout; the bus vented and the loop's next
// setpoint ramped up again, all between two steps. That step's result is not linked (a sweep
// redoes its hold), and the slew limiter starts again from 0 kPa as the plant did; the link's own
// outages and alarm rows are what linked() showed (none here).
TEST(RigStep, AVentTheBackendDidOnItsOwnBetweenTwoStepsIsNotALinkedStep) {
  SelfVentingRig rig;
  rig.open();
  rig.vents_on_its_own = 3;  // earlier vents, before this step was made, are not this step's
  TickConfig config;         // 2000 kPa/s: 2 kPa per 1 ms step
  RigStep step(config, rig);
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  double t = 0;
  for (int k = 0; k < 20; ++k, t += 0.001) EXPECT_TRUE(step.step_direct({30, 0, 0}, t).linked);
  EXPECT_NEAR(step.last().tick.setpoint_kPa[0], 30.0, 1e-9);
  EXPECT_EQ(step.vents_between_steps(), 0u);

  rig.vents_on_its_own = 4;
  const StepResult& r = step.step_direct({30, 0, 0}, t);
  t += 0.001;
  EXPECT_FALSE(r.linked);
  EXPECT_EQ(r.tick.record.fault, FaultCode::none);
  EXPECT_FALSE(step.faulted());
  EXPECT_EQ(step.vents_between_steps(), 1u);
  EXPECT_EQ(step.link_outages(), 0u);
  EXPECT_EQ(step.unlinked_steps(), 0u);

  // Linked again at once, rising from 0 kPa under the slew limit.
  const StepResult& next = step.step_direct({30, 0, 0}, t);
  t += 0.001;
  EXPECT_TRUE(next.linked);
  EXPECT_NEAR(next.tick.setpoint_kPa[0], 2.0, 1e-9);
  EXPECT_EQ(step.vents_between_steps(), 1u);

  // A vent while disarmed held no pressure: re-arming starts from it without counting it.
  step.disarm();
  rig.vents_on_its_own = 5;
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  EXPECT_TRUE(step.step_direct({30, 0, 0}, t).linked);
  EXPECT_EQ(step.vents_between_steps(), 1u);
}

TEST(RigStep, ADisarmedRigIsVentedAndReadAndRampsAgainAfterReArming) {
  RecordingRig rig;
  rig.open();
  TickConfig config;  // 2000 kPa/s: 2 kPa per 1 ms step
  RigStep step(config, rig);
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  double t = 0;
  for (int k = 0; k < 20; ++k, t += 0.001) step.step_direct({30, 0, 0}, t);
  EXPECT_NEAR(step.last().tick.setpoint_kPa[0], 30.0, 1e-9);

  step.disarm();  // as the loop does while the operator holds VENT
  const std::size_t writes_before = rig.writes.size();
  for (int k = 0; k < 5; ++k, t += 0.001) {
    const StepResult& r = step.step_direct({30, 0, 0}, t);
    EXPECT_FALSE(r.armed);
    EXPECT_EQ(r.tick.setpoint_kPa[0], 0.0);
    EXPECT_TRUE(r.tick.record.flags & kDisarmed);
    EXPECT_TRUE(r.tick.record.flags & kVented);
    EXPECT_EQ(r.tick.record.fault, FaultCode::none);  // disarmed is not a fault
  }
  EXPECT_EQ(rig.writes.size(), writes_before);  // nothing written while disarmed: vented instead
  EXPECT_EQ(rig.state(), BackendState::disarmed);
  EXPECT_FALSE(step.faulted());

  ASSERT_EQ(step.arm(), BackendStatus::ok);
  const StepResult& first = step.step_direct({30, 0, 0}, t);
  EXPECT_TRUE(first.armed);
  EXPECT_NEAR(first.tick.setpoint_kPa[0], 2.0, 1e-9);  // from 0 kPa again, one slew step
  t += 0.001;
  EXPECT_NEAR(step.step_direct({30, 0, 0}, t).tick.setpoint_kPa[0], 4.0, 1e-9);
  for (const auto& w : rig.writes) EXPECT_LE(w[0], 60.0);
}

TEST(RigStep, ABackendErrorVentsDisarmsAndKeepsTheBackendsWords) {
  RecordingRig rig;
  rig.fail_at_write = 5;
  rig.open();
  RigStep step(TickConfig{}, rig);
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  double t = 0;
  for (int k = 0; k < 4; ++k, t += 0.001)
    EXPECT_EQ(step.step_direct({10, 10, 10}, t).tick.record.fault, FaultCode::none);
  const int vents_before = rig.vents;
  const StepResult& r = step.step_direct({10, 10, 10}, t);
  EXPECT_EQ(r.tick.record.fault, FaultCode::backend_error);
  EXPECT_TRUE(r.tick.record.flags & kVented);
  EXPECT_EQ(step.fault(), FaultCode::backend_error);
  EXPECT_EQ(step.fault().detail(), "valve driver overheated on channel 3");
  EXPECT_GT(rig.vents, vents_before);
  EXPECT_EQ(rig.state(), BackendState::disarmed);
  // Latched: a faulted step never moves air again, even when asked to arm.
  EXPECT_EQ(step.arm(), BackendStatus::error);
  const std::size_t writes = rig.writes.size();
  step.step_direct({10, 10, 10}, t + 0.001);
  EXPECT_EQ(rig.writes.size(), writes);
}

TEST(RigStep, ARunOnAClosedBackendMovesNothingAndSaysWhy) {
  RecordingRig rig;  // never opened
  RestingPen pen;
  RunOptions opt;
  opt.duration_s = 0.1;
  const RunSummary s = palprig::testing::run_loop_leased(TickConfig{}, hard_right_scene(), pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::backend_error);
  EXPECT_NE(s.fault.detail().find("closed"), std::string::npos) << s.fault.detail();
  EXPECT_EQ(s.ticks, 0u);
  EXPECT_TRUE(rig.writes.empty());
}

TEST(RigStep, FaultsFromOutsideTheStepVentOnTheNextStep) {
  RecordingRig rig;
  rig.open();
  RigStep step(TickConfig{}, rig);
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  double t = 0;
  for (int k = 0; k < 10; ++k, t += 0.001) step.step_direct({10, 10, 10}, t);
  step.enter_fault(FaultCode::signal);
  const StepResult& r = step.step_direct({10, 10, 10}, t);
  EXPECT_EQ(r.tick.setpoint_kPa, (ChannelPressures{0, 0, 0}));
  EXPECT_EQ(r.tick.record.fault, FaultCode::signal);
  EXPECT_EQ(rig.writes.back(), (ChannelPressures{0, 0, 0}));
  EXPECT_EQ(rig.state(), BackendState::disarmed);
}
