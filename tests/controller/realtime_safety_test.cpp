// The loop's safety around hardware: a link that drops and returns (alarm, vent, ramp from 0),
// an exception or a lost device on another thread (vent and stop with the reason), and the
// wait-free exchange the loop and the worker threads use.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "runtime/latest_value.hpp"
#include "controller/loop_runner.hpp"
#include "rigs/simulated_rig.hpp"
#include "inputs/tablet_input.hpp"
#include "runtime/worker_fault.hpp"
#include "formats/rig_file.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;

namespace {

MapScene uniform_scene(float stiffness) {
  return MapScene(StiffnessMap(11, 11, 200, 200, std::vector<float>(121, stiffness)), MapSampling::nearest);
}

class PressingPen final : public InputSource {
 public:
  TouchSample latest(double t) noexcept override { return {t, 100, 100, 2.0, true}; }
  double duration_s() const noexcept override { return 0; }
  std::string describe() const override { return "pressing pen"; }
};

// A backend whose link is down for writes [down_from, down_to).
class FlakyLinkRig final : public RigBackend {
 public:
  FlakyLinkRig(int down_from, int down_to) : RigBackend(60), from_(down_from), to_(down_to) {}
  std::string describe() const override { return "flaky link"; }
  BackendCapabilities capabilities() const override {
    BackendCapabilities c;
    c.link_kind = "in-process";
    return c;
  }
  bool linked() const noexcept override { return writes_ < from_ || writes_ >= to_; }

 protected:
  void do_open() override {}
  void do_close() noexcept override {}
  BackendStatus do_write(const ChannelPressures&, double) noexcept override {
    linked_at_write_ = linked();
    ++writes_;
    return BackendStatus::ok;
  }
  BackendStatus do_read(ChannelPressures& m, double) noexcept override {
    m.fill(linked_at_write_ ? 1.0 : std::nan(""));  // no reading while the link is down
    return BackendStatus::ok;
  }
  BackendStatus do_vent() noexcept override { return BackendStatus::ok; }

 private:
  int from_, to_, writes_ = 0;
  bool linked_at_write_ = true;
};

class SafetyRecorder final : public TickObserver {
 public:
  std::vector<TelemetryRecord> records;
  void on_tick(const TelemetryRecord& r) noexcept override { records.push_back(r); }
};

// A pen source whose reader hits trouble after a few calls.
class FailingPenSource final : public PenEventSource {
 public:
  explicit FailingPenSource(bool throws) : throws_(throws) { axes_ = {0, 1000, 10, 0, 1000, 10, 0, 255, true}; }
  const TabletAxes& axes() const noexcept override { return axes_; }
  std::string describe() const override { return "failing pen"; }
  Status next(std::vector<input_event>&, int, PenState&) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (++calls_ < 20) return Status::idle;
    if (throws_) throw std::runtime_error("USB bus reset");
    return Status::ended;
  }
  std::string why() const override { return "/dev/input/event7 is gone (unplugged?)"; }

 private:
  TabletAxes axes_;
  bool throws_;
  int calls_ = 0;
};

}  // namespace

TEST(RealtimeSafety, ALinkOutageIsAnAlarmThatVentsAndRampsBackFromZero) {
  FlakyLinkRig rig(300, 400);
  rig.open();
  PressingPen pen;
  const MapScene scene = uniform_scene(1.0f);
  TickConfig config;  // slew 2000 kPa/s: 2 kPa per 1 ms tick
  SafetyRecorder rec;
  RunOptions opt;
  opt.mode = LoopMode::replay;
  opt.duration_s = 0.6;
  opt.observer = &rec;
  const RunSummary s = palprig::testing::run_loop_leased(config, scene, pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::none);  // not latched: the run went on
  EXPECT_EQ(s.link_outages, 1u);
  EXPECT_EQ(s.unlinked_ticks, 100u);
  ASSERT_EQ(rec.records.size(), 600u);
  const float steady = rec.records[299].setpoint_kPa[0];
  EXPECT_GT(steady, 10.0f);
  for (std::size_t i = 300; i < 400; ++i) {
    const auto& r = rec.records[i];
    EXPECT_EQ(r.fault, FaultCode::backend_error) << i;  // the alarm in telemetry
    EXPECT_TRUE(r.flags & kVented) << i;
    for (float p : r.setpoint_kPa) EXPECT_EQ(p, 0.0f) << i;
    EXPECT_TRUE(std::isnan(r.monitor_kPa[0])) << i;
  }
  // Back: the first linked tick may rise by one slew step only, then the ramp continues.
  EXPECT_EQ(rec.records[400].fault, FaultCode::none);
  EXPECT_NEAR(rec.records[400].setpoint_kPa[0], 2.0f, 1e-4);
  for (std::size_t i = 401; i < 600; ++i)
    EXPECT_LE(rec.records[i].setpoint_kPa[0] - rec.records[i - 1].setpoint_kPa[0], 2.0f + 1e-4) << i;
  EXPECT_FLOAT_EQ(rec.records[599].setpoint_kPa[0], steady);
  // Monitors without a reading are left out of the statistics instead of poisoning them.
  EXPECT_DOUBLE_EQ(s.monitor_kPa[0].mean(), 1.0);
}

TEST(RealtimeSafety, AnExceptionOnTheReaderThreadVentsAndStopsTheLoop) {
  clear_worker_faults();
  TabletInput input(std::make_unique<FailingPenSource>(true), TabletConfig{});
  const RigConfig rig = default_rig();
  SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
  backend.open();
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.want_fifo = false;
  opt.duration_s = 2.0;
  TickConfig config;
  config.safety.max_consecutive_overruns = 1000000;  // a busy test machine must not end it first
  config.safety.max_lost_time_s = 10;
  const RunSummary s = palprig::testing::run_loop_leased(config, uniform_scene(0.5f), input, backend, opt);
  EXPECT_EQ(s.fault, FaultCode::thread_exception);
  EXPECT_NE(s.fault.detail().find("USB bus reset"), std::string::npos) << s.fault.detail();
  EXPECT_NE(s.fault.detail().find("pen tablet reader"), std::string::npos) << s.fault.detail();
  EXPECT_LT(s.fault.t_s, 1.0);
  clear_worker_faults();
}

TEST(RealtimeSafety, ALiveTabletThatDisappearsIsAWorkerFaultWithTheReason) {
  clear_worker_faults();
  TabletInput input(std::make_unique<FailingPenSource>(false), TabletConfig{});
  const RigConfig rig = default_rig();
  SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
  backend.open();
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.want_fifo = false;
  opt.duration_s = 2.0;
  TickConfig config;
  config.safety.max_consecutive_overruns = 1000000;  // a busy test machine must not end it first
  config.safety.max_lost_time_s = 10;
  const RunSummary s = palprig::testing::run_loop_leased(config, uniform_scene(0.5f), input, backend, opt);
  EXPECT_EQ(s.fault, FaultCode::thread_exception);
  EXPECT_NE(s.fault.detail().find("unplugged"), std::string::npos) << s.fault.detail();
  clear_worker_faults();
}

TEST(RealtimeSafety, LatestValueNeverTearsAndOnlyMovesForward) {
  struct Pair {
    std::uint64_t a, b;  // b == 3 * a in every published value
  };
  LatestValue<Pair> value(Pair{0, 0});
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::uint64_t i = 1; i <= 2'000'000; ++i) value.publish(Pair{i, 3 * i});
    done = true;
  });
  std::uint64_t last = 0, reads = 0;
  bool torn = false, backwards = false;
  while (!done.load() || reads < 10) {
    const Pair p = value.latest();
    torn = torn || p.b != 3 * p.a;
    backwards = backwards || p.a < last;
    last = p.a;
    ++reads;
  }
  writer.join();
  EXPECT_FALSE(torn);
  EXPECT_FALSE(backwards);
  EXPECT_EQ(value.latest().a, 2'000'000u);  // the last value always arrives
  EXPECT_EQ(value.published(), 2'000'000u);
}
