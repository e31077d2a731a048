// One owner of the rig: a second taker is refused with the holder's name, a yielding holder (the
// window's live loop) gives way to a taker and its loop ends vented without a fault, and giving a
// lease back vents every channel. Real loops on real threads against the simulated rig.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>

#include "controller/loop_runner.hpp"
#include "controller/rig_lease.hpp"
#include "models/scene.hpp"
#include "rigs/simulated_rig.hpp"
#include "runtime/run_control.hpp"

namespace palprig {
namespace {

class PressingPen final : public InputSource {
 public:
  TouchSample latest(double t_s) noexcept override { return TouchSample{t_s, 50, 50, 4.0, true}; }
  double duration_s() const noexcept override { return 0; }
  std::string describe() const override { return "still pen"; }
};

MapScene stiff_scene() {
  return MapScene(StiffnessMap(11, 11, 100, 100, std::vector<float>(121, 1.0f)), MapSampling::nearest);
}

TEST(RigLease, ASecondTakerIsRefusedWithTheHoldersName) {
  SimulatedRig backend(std::array<PlantParams, kFingerCount>{}, 60.0);
  backend.open();
  Rig rig(backend, "rig test-rig (simulated)");
  RigLease first = rig.lease("the calibration sweep");
  EXPECT_TRUE(rig.leased());
  EXPECT_EQ(rig.holder(), "the calibration sweep");
  try {
    RigLease second = rig.lease("a study session");
    FAIL() << "a second lease was granted while the first was out";
  } catch (const RigBusy& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rig test-rig (simulated) is held by the calibration sweep"), std::string::npos) << what;
    EXPECT_NE(what.find("a study session cannot take it"), std::string::npos) << what;
    EXPECT_EQ(e.exit_code(), 1);
  }
  first.release();
  EXPECT_FALSE(rig.leased());
  RigLease again = rig.lease("a study session");  // free again: granted
  EXPECT_EQ(rig.holder(), "a study session");
}

TEST(RigLease, GivingTheLeaseBackVentsAnArmedRig) {
  SimulatedRig backend(std::array<PlantParams, kFingerCount>{}, 60.0);
  backend.open();
  Rig rig(backend, "rig");
  {
    RigLease lease = rig.lease("a test");
    ASSERT_EQ(lease.backend().arm(), BackendStatus::ok);
    ASSERT_EQ(lease.backend().write({20, 20, 20}, 0.0), BackendStatus::ok);
  }
  EXPECT_NE(backend.state(), BackendState::armed) << "a returned rig is never left armed";
  // Vented: the plant relaxes toward 0 kPa, never toward the last setpoint.
  ChannelPressures monitor{};
  for (int k = 1; k <= 2000; ++k) ASSERT_EQ(backend.read_monitors(monitor, k * 0.001), BackendStatus::ok);
  for (double p : monitor) EXPECT_LT(p, 1.0);
}

TEST(RigLease, AYieldingLoopGivesWayToASecondTakerAndEndsVentedWithoutAFault) {
  SimulatedRig backend(std::array<PlantParams, kFingerCount>{}, 60.0);
  backend.open();
  Rig rig(backend, "rig");
  const MapScene scene = stiff_scene();
  PressingPen pen;
  RunControl control;
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.want_fifo = false;
  opt.duration_s = 60;  // far longer than the test: only the hand-over ends it
  opt.control = &control;
  opt.realtime.fifo = false;
  RunSummary summary;
  std::optional<RigLease> live;
  live.emplace(rig.lease("the window's live loop", LeaseKind::yielding));
  std::thread loop([&] { summary = run_loop(TickConfig{}, scene, pen, *live, opt); });
  // Let the loop press for a while, then take the rig as a session would.
  while (backend.state() != BackendState::armed) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::thread taker([&] {
    RigLease session = rig.lease("a study session", LeaseKind::exclusive, std::chrono::seconds(10));
    EXPECT_EQ(rig.holder(), "a study session");
  });
  loop.join();
  live.reset();  // the loop's owner drops the lease once its loop has ended (LiveRun::join_loop)
  taker.join();
  EXPECT_EQ(summary.fault, FaultCode::none) << "giving way is not a fault";
  EXPECT_GT(summary.ticks, 10u);
  EXPECT_LT(summary.sim_time_s, 30.0);
  EXPECT_FALSE(rig.leased());
}

TEST(RigLease, ANonYieldingHolderIsNotAskedToGiveWay) {
  SimulatedRig backend(std::array<PlantParams, kFingerCount>{}, 60.0);
  backend.open();
  Rig rig(backend, "rig");
  RigLease sweep = rig.lease("the calibration sweep", LeaseKind::exclusive);
  EXPECT_THROW(rig.lease("the window's live loop", LeaseKind::yielding), RigBusy);
  EXPECT_FALSE(sweep.release_requested()) << "an exclusive holder is never asked to give way";
}

// The window restarts its live loop on a timer whenever the rig is free. In the moment between
// the yielding lease going back and the waiting session waking, the loop must not take the rig
// again: nobody would be left to ask it to give way, and the session would time out (CI saw a
// study session refused after 5 s under load).
TEST(RigLease, AWaitingTakerComesBeforeAYieldingLoopRestartingInTheGap) {
  SimulatedRig backend(std::array<PlantParams, kFingerCount>{}, 60.0);
  backend.open();
  Rig rig(backend, "rig");
  std::optional<RigLease> live;
  live.emplace(rig.lease("the window's live loop", LeaseKind::yielding));
  std::atomic<bool> session_got_it{false};
  std::atomic<bool> checked{false};
  std::thread taker([&] {
    RigLease session = rig.lease("a study session", LeaseKind::exclusive, std::chrono::seconds(20));
    session_got_it = true;
    EXPECT_EQ(rig.holder(), "a study session");
    while (!checked) std::this_thread::yield();  // the session runs until the checks below are made
  });
  while (!live->release_requested()) std::this_thread::yield();
  live.reset();  // the loop gave way ...
  // ... and restarts at once, before the session's thread has woken: refused, the rig is promised.
  EXPECT_TRUE(rig.leased()) << "a rig a taker waits for is not free";
  EXPECT_THROW(rig.lease("the window's live loop", LeaseKind::yielding), RigBusy);
  checked = true;
  taker.join();
  EXPECT_TRUE(session_got_it);
  EXPECT_FALSE(rig.leased());
  // Free again: the live loop may have it.
  RigLease again = rig.lease("the window's live loop", LeaseKind::yielding);
  EXPECT_EQ(rig.holder(), "the window's live loop");
}

TEST(RunControl, AStopBySignalIsKeptWhileAnOperatorsStopIsForgottenByRestart) {
  RunControl control;
  control.request_stop();
  EXPECT_TRUE(control.stop_requested());
  EXPECT_TRUE(control.stopped_by_operator());
  control.restart();
  EXPECT_FALSE(control.stop_requested());
  control.signal_stop(15);
  control.restart();
  EXPECT_TRUE(control.stop_requested());
  EXPECT_EQ(control.stop_signal(), 15);
}

}  // namespace
}  // namespace palprig
