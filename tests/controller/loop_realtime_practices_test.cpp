// run_loop in real time holds the PM QoS request (and the other practices) while it runs,
// and says what was in effect.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <thread>
#include <vector>

#include "controller/loop_runner.hpp"
#include "formats/rig_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;

namespace {

class StillPen final : public InputSource {
 public:
  TouchSample latest(double t) noexcept override { return {t, 50, 50, 2.0, true}; }
  double duration_s() const noexcept override { return 0; }
  std::string describe() const override { return "still pen"; }
};

// Reads the kernel's current CPU latency target on the loop's first tick.
class TargetProbe final : public TickObserver {
 public:
  void on_tick(const TelemetryRecord&) noexcept override {
    if (read_) return;
    read_ = true;
    const int fd = ::open(kCpuDmaLatencyPath, O_RDONLY);
    if (fd < 0) return;
    if (::read(fd, &target_us, sizeof target_us) != sizeof target_us) target_us = -1;
    ::close(fd);
  }
  bool read_ = false;
  std::int32_t target_us = -1;
};

RunSummary run_briefly(RealtimeOptions rt, TickObserver* observer) {
  RunSummary s;
  std::thread t([&] {  // FIFO, slack and pinning stay on this thread
    const RigConfig rig = default_rig();
    const MapScene scene(StiffnessMap(11, 11, 100, 100, std::vector<float>(121, 0.5f)), MapSampling::nearest);
    StillPen pen;
    SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
    backend.open();
    RunOptions opt;
    opt.mode = LoopMode::realtime;
    opt.rate_hz = 1000;
    opt.duration_s = 0.05;
    opt.realtime = rt;
    opt.observer = observer;
    s = palprig::testing::run_loop_leased(TickConfig{}, scene, pen, backend, opt);
  });
  t.join();
  return s;
}

}  // namespace

TEST(LoopRealtimePractices, HoldsThePmQosRequestWhileRunning) {
  if (::access(kCpuDmaLatencyPath, W_OK) != 0) GTEST_SKIP() << kCpuDmaLatencyPath << " not writable here";
  TargetProbe probe;
  const RunSummary s = run_briefly(RealtimeOptions{}, &probe);
  ASSERT_TRUE(probe.read_);
  EXPECT_EQ(probe.target_us, 0);
  EXPECT_NE(s.realtime_practices.find("PM QoS 0 us"), std::string::npos) << s.realtime_practices;
  EXPECT_NE(s.realtime_practices.find("timer slack 1 ns"), std::string::npos);
  EXPECT_NE(s.realtime_practices.find("stack prefaulted"), std::string::npos);
}

TEST(LoopRealtimePractices, NoPmQosMeansNoRequest) {
  RealtimeOptions rt;
  rt.pm_qos = false;
  rt.cpu = 0;
  const RunSummary s = run_briefly(rt, nullptr);
  EXPECT_EQ(s.realtime_practices.find("PM QoS"), std::string::npos) << s.realtime_practices;
  EXPECT_NE(s.realtime_practices.find("CPU 0"), std::string::npos) << s.realtime_practices << " / " << s.realtime_note;
  EXPECT_EQ(s.realtime_note.find("PM QoS"), std::string::npos);  // not asked for, so not complained about
}

TEST(LoopRealtimePractices, ReplayTouchesNoneOfThem) {
  const RigConfig rig = default_rig();
  const MapScene scene(StiffnessMap(11, 11, 100, 100, std::vector<float>(121, 0.5f)), MapSampling::nearest);
  StillPen pen;
  SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
  backend.open();
  RunOptions opt;
  opt.mode = LoopMode::replay;
  opt.duration_s = 0.05;
  const RunSummary s = palprig::testing::run_loop_leased(TickConfig{}, scene, pen, backend, opt);
  EXPECT_TRUE(s.realtime_practices.empty());
}
