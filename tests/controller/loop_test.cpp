#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <thread>

#include "controller/loop_runner.hpp"
#include "rigs/simulated_rig.hpp"
#include "controller/telemetry_writer.hpp"
#include "core/input_error.hpp"
#include "tests/support/rigs_for_tests.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

using test_rigs::hard_right_scene;
using test_rigs::quiet_plants;
using test_rigs::RestingPen;

// A backend that fails on the n-th write, to see the loop vent and stop.
struct FailingRig : test_rigs::RecordingRig {
  explicit FailingRig(int fail_at) : RecordingRig(fail_at, "bus timeout on channel 2") {}
};

TEST(LoopRunner, ReplayDrivesThePlantToTheTarget) {
  const auto scene = hard_right_scene();
  TickConfig cfg;
  SimulatedRig rig(quiet_plants(), 60);
  rig.open();
  RestingPen pen(50, 20);  // finger 1 over hard tissue
  RunOptions opt;
  opt.duration_s = 1.0;
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.ticks, 1000u);
  EXPECT_EQ(s.fault, FaultCode::none);
  EXPECT_NEAR(s.target_kPa[1].max, 11.75, 1e-4);
  EXPECT_NEAR(s.monitor_kPa[1].max, 11.75, 0.05);  // settled after 1 s with a 50 ms lag
  EXPECT_NEAR(s.monitor_kPa[0].max, 0.0, 1e-9);
  EXPECT_EQ(rig.plant_output_kPa(1), rig.plant_output_kPa(1));
}

TEST(LoopRunner, BackendErrorVentsAndStopsWithTheReason) {
  const auto scene = hard_right_scene();
  TickConfig cfg;
  FailingRig rig(100);
  rig.open();
  RestingPen pen(50, 20);
  RunOptions opt;
  opt.duration_s = 1.0;
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::backend_error);
  EXPECT_EQ(s.fault.detail(), "bus timeout on channel 2");
  EXPECT_EQ(s.ticks, 100u);
  EXPECT_GE(rig.vents, 1);
  EXPECT_EQ(rig.last, (ChannelPressures{0, 0, 0}));
}

TEST(LoopRunner, StopSignalVents) {
  const auto scene = hard_right_scene();
  TickConfig cfg;
  SimulatedRig rig(quiet_plants(), 60);
  rig.open();
  RestingPen pen(50, 20);
  RunControl stop;
  stop.signal_stop(15);
  RunOptions opt;
  opt.duration_s = 1.0;
  opt.control = &stop;
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::signal);
  EXPECT_EQ(s.ticks, 1u);
  EXPECT_EQ(s.setpoint_kPa[1].max, 0.0);  // vented from the first tick on
}

TEST(LoopRunner, RealtimeModeRunsOnTheClock) {
  // Timing is not asserted (benchmarks measure it); this checks the mode works and reports.
  const auto scene = hard_right_scene();
  TickConfig cfg;
  cfg.safety.max_consecutive_overruns = 1000000;  // a loaded CI machine must not fault this
  cfg.safety.max_lost_time_s = 10;
  SimulatedRig rig(quiet_plants(), 60);
  rig.open();
  RestingPen pen(50, 20);
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.rate_hz = 500;
  opt.duration_s = 0.2;
  opt.want_fifo = false;
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::none);
  EXPECT_EQ(s.ticks + s.missed_periods, 100u);  // every period either ran or was skipped
  EXPECT_NEAR(s.sim_time_s, 0.2, 1e-9);
  EXPECT_GT(s.wake_latency.count, 0u);
  EXPECT_GE(s.wall_time_s, 0.19);
}

TEST(LoopRunner, BinaryTelemetryRoundTripsThroughCsv) {
  TempDir dir;
  const auto scene = hard_right_scene();
  TickConfig cfg;
  SimulatedRig rig(quiet_plants(), 60);
  rig.open();
  RestingPen pen(50, 20);
  RunOptions opt;
  opt.duration_s = 0.5;
  opt.telemetry_path = dir.path() / "t.bin";
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.telemetry_dropped, 0u);
  EXPECT_EQ(std::filesystem::file_size(opt.telemetry_path), 16 + 500 * sizeof(TelemetryRecord));
  EXPECT_EQ(convert_telemetry_to_csv(opt.telemetry_path, dir.path() / "t.csv"), 500u);
  std::ifstream csv(dir.path() / "t.csv");
  std::string header, first, line, last;
  std::getline(csv, header);
  std::getline(csv, first);
  while (std::getline(csv, line)) last = line;
  EXPECT_EQ(header.rfind("tick,t_s,x_mm,y_mm,force_N,stiffness_1", 0), 0u);
  EXPECT_EQ(first.rfind("0,0.000000,50.000,20.000,2.0000", 0), 0u);
  EXPECT_EQ(last.rfind("499,0.499000", 0), 0u);
  EXPECT_THROW(convert_telemetry_to_csv(dir.path() / "t.csv", dir.path() / "x.csv"), InputError);
}

TEST(LatencyHistogram, Percentiles) {
  LatencyHistogram h;
  for (int i = 0; i < 1000; ++i) h.record(i < 990 ? 10.5 : 500.0);
  const auto s = h.summary();
  EXPECT_EQ(s.count, 1000u);
  EXPECT_NEAR(s.p50_us, 10.6, 1e-9);  // 0.1 us bins below 100 us
  EXPECT_NEAR(s.p99_us, 10.6, 1e-9);
  EXPECT_EQ(s.p999_us, 500.0);
  EXPECT_EQ(s.max_us, 500.0);
}

TEST(LatencyHistogram, TenthsOfAMicrosecondBelow100usAndWholeMicrosecondsAbove) {
  LatencyHistogram fast;
  for (int i = 0; i < 100; ++i) fast.record(0.41 + 0.001 * i);  // a tick of 0.41..0.51 us
  EXPECT_NEAR(fast.percentile_us(0.5), 0.5, 1e-9);
  EXPECT_NEAR(fast.percentile_us(0.99), 0.509, 1e-9);  // its bin edge (0.6) is past the maximum
  LatencyHistogram slow;
  for (int i = 0; i < 100; ++i) slow.record(i < 50 ? 150.3 : 19999.5);
  EXPECT_EQ(slow.percentile_us(0.5), 151.0);
  EXPECT_EQ(slow.percentile_us(0.99), 19999.5);  // the bin's edge (20000) is past the maximum
  slow.record(50000);
  EXPECT_EQ(slow.summary().max_us, 50000.0);
}

namespace {

// Plays the GUI's VENT button and Arm from the loop's own thread at chosen ticks, and keeps
// what each tick sent (the records are checked after the run).
class VentOperator final : public TickObserver {
 public:
  explicit VentOperator(RunControl& control) : control_(control) {}
  void on_tick(const TelemetryRecord& r) noexcept override {
    if (records.size() < records.capacity()) records.push_back(r);
    if (r.tick == 499) control_.hold_vent(true);
    if (r.tick == 799) control_.hold_vent(false);
    if (r.tick == 1199) control_.request_stop();
  }
  std::vector<TelemetryRecord> records;

 private:
  RunControl& control_;
};

}  // namespace

TEST(LoopRunner, VentRequestZeroesEverySetpointFromTheNextTickAndArmingSlewsBackUp) {
  const auto scene = hard_right_scene();
  TickConfig cfg;
  FailingRig rig(1 << 30);  // never fails; keeps the last write
  rig.open();               // connected and vented: run_loop arms it
  RestingPen pen(50, 20);   // finger 2 over hard tissue: 11.75 kPa
  RunControl control;
  VentOperator op(control);
  op.records.reserve(5000);
  RunOptions opt;
  opt.duration_s = 5.0;
  opt.control = &control;
  opt.observer = &op;
  const RunSummary s = palprig::testing::run_loop_leased(cfg, scene, pen, rig, opt);
  EXPECT_EQ(s.fault, FaultCode::none);  // a vent and a stop are operator actions, not faults
  // The stop asked for after tick 1199 ended the run before its 5 s, with one last tick whose
  // record shows every channel vented.
  EXPECT_EQ(s.ticks, 1201u);
  ASSERT_EQ(op.records.size(), 1201u);
  EXPECT_TRUE(op.records[1200].flags & kVented);
  for (int i = 0; i < kFingerCount; ++i) EXPECT_EQ(op.records[1200].setpoint_kPa[i], 0.0f);
  EXPECT_NEAR(op.records[499].setpoint_kPa[1], 11.75, 1e-4);
  for (std::size_t k = 500; k < 800; ++k) {
    for (int i = 0; i < kFingerCount; ++i) ASSERT_EQ(op.records[k].setpoint_kPa[i], 0.0f) << "tick " << k;
    ASSERT_TRUE(op.records[k].flags & kVented);
    EXPECT_NEAR(op.records[k].target_kPa[1], 11.75, 1e-4);  // the models still ask; nothing is sent
  }
  // Armed again: from 0 under the slew limit (2000 kPa/s = 2 kPa per 1 ms tick), not a step.
  EXPECT_FALSE(op.records[800].flags & kVented);
  EXPECT_NEAR(op.records[800].setpoint_kPa[1], 2.0, 1e-4);
  EXPECT_NEAR(op.records[900].setpoint_kPa[1], 11.75, 1e-4);
  EXPECT_EQ(rig.last, (ChannelPressures{0, 0, 0}));  // the run ended vented
}
