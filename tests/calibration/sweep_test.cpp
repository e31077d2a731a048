// Over 400 lines: the schedule, the runner and the data file are one sweep's three sides and
// share its fixtures.
// Calibration sweeps: the schedule (paper 002's staircase, p_max clamp, identification
// excitations), the runner on the simulated rig (settling, stop, backend faults, a sensor
// channel) and the data file (round trip, hand-typed tables, malformed rows).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <vector>

#include "calibration/sweep_csv.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_runner.hpp"
#include "formats/rig_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "core/input_error.hpp"
#include "tests/support/refusal.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;
using palprig::test_support::refusal;
using palprig::test_support::TempDir;

namespace {

std::array<PlantParams, kFingerCount> default_plants() {
  RigConfig rig = load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated.json");
  return rig.plants;
}

// A rig with a deformation sensor under each actuator (like paper 002's caliper): the
// simulated rig's pressure, through the membrane's own backlash of 1.5 kPa, at 0.012 mm/kPa.
// Optionally fails its monitor read after a number of calls (a cable pulled mid-sweep).
class CaliperRig final : public RigBackend {
 public:
  explicit CaliperRig(double p_max_kPa, long fail_after_reads = -1)
      : RigBackend(p_max_kPa), inner_(default_plants(), p_max_kPa), fail_after_(fail_after_reads) {}
  std::string describe() const override { return "caliper test rig"; }
  BackendCapabilities capabilities() const override {
    BackendCapabilities c;
    c.has_sensor = true;
    c.sensor_name = "deformation_mm";
    c.sensor_unit = "mm";
    c.link_kind = "in-process";
    return c;
  }
  int vents = 0;
  double highest_write_kPa = 0;
  double largest_rise_kPa = 0;  // between consecutive writes, any channel
  ChannelPressures last_write_kPa{};

 protected:
  void do_open() override {
    inner_.open();
    inner_.arm();  // the inner rig is this rig's plant: it follows whatever this one is sent
    play_.fill(0);
  }
  void do_close() noexcept override { inner_.close(); }
  BackendStatus do_read_sensors(std::array<double, kFingerCount>& value, double) noexcept override {
    for (std::size_t c = 0; c < kFingerCount; ++c) {
      const double p = inner_.plant_output_kPa(c);
      play_[c] = std::clamp(play_[c], p - 1.5, p + 1.5);
      value[c] = 0.012 * play_[c];
    }
    return BackendStatus::ok;
  }
  BackendStatus do_write(const ChannelPressures& s, double t) noexcept override {
    for (double p : s) highest_write_kPa = std::max(highest_write_kPa, p);
    for (std::size_t c = 0; c < kFingerCount; ++c)
      largest_rise_kPa = std::max(largest_rise_kPa, s[c] - last_write_kPa[c]);
    last_write_kPa = s;
    return inner_.write(s, t);
  }
  BackendStatus do_read(ChannelPressures& m, double t) noexcept override {
    if (fail_after_ >= 0 && reads_++ >= fail_after_) {
      set_error("monitor read failed: cable unplugged");
      return BackendStatus::error;
    }
    return inner_.read_monitors(m, t);
  }
  BackendStatus do_vent() noexcept override {
    ++vents;
    return inner_.vent();
  }

 private:
  SimulatedRig inner_;
  std::array<double, kFingerCount> play_{};
  long fail_after_;
  long reads_ = 0;
};

// Collects what the runner hands over.
struct MemorySink final : SweepSink {
  struct Hold {
    SweepHold hold;
    std::vector<SweepSample> samples;
    HoldOutcome outcome;
  };
  std::vector<Hold> holds;
  void on_hold(std::size_t, const SweepHold& h, std::span<const SweepSample> s, const HoldOutcome& o) override {
    holds.push_back({h, {s.begin(), s.end()}, o});
  }
};

double settled_mean(const MemorySink::Hold& h, std::size_t channel) {
  double sum = 0;
  int n = 0;
  for (const auto& s : h.samples)
    if (s.settled) {
      sum += s.monitor_kPa[channel];
      ++n;
    }
  return n ? sum / n : std::nan("");
}

SweepRunOptions fast_options() {
  SweepRunOptions o;
  o.realtime = false;
  return o;
}

}  // namespace

TEST(SweepPlan, PaperStaircaseWithRepeatsFromVented) {
  const SweepSchedule plan = plan_calibration_sweep({}, 100.0);
  EXPECT_TRUE(plan.notes.empty());
  // 5 repeats x (vent + 10 up + 10 down) + the final vent.
  ASSERT_EQ(plan.holds.size(), 5u * 21u + 1u);
  EXPECT_EQ(plan.holds[0].segment, SweepSegment::vent);
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(plan.holds[1 + k].branch, SweepBranch::inflation);
    EXPECT_DOUBLE_EQ(plan.holds[1 + k].level_kPa, 10.0 * (k + 1));
    EXPECT_EQ(plan.holds[11 + k].branch, SweepBranch::deflation);
    EXPECT_DOUBLE_EQ(plan.holds[11 + k].level_kPa, 100.0 - 10.0 * k);
  }
  EXPECT_EQ(plan.holds[21].segment, SweepSegment::vent);
  EXPECT_EQ(plan.holds[22].repeat, 2);
  EXPECT_EQ(plan.holds.back().segment, SweepSegment::vent);
}

TEST(SweepPlan, LevelsAbovePMaxAreClampedAndSaidSo) {
  const SweepSchedule plan = plan_calibration_sweep({}, 60.0);
  ASSERT_EQ(plan.notes.size(), 1u);
  EXPECT_EQ(plan.notes[0],
            "the rig's p_max is 60 kPa: sweep levels above it are clamped to 60 kPa (asked up to 100 kPa)");
  double top = 0;
  for (const auto& h : plan.holds) top = std::max(top, h.level_kPa);
  EXPECT_DOUBLE_EQ(top, 60.0);
  // 10..60: six levels each way, no level repeated within a branch.
  EXPECT_EQ(plan.holds.size(), 5u * 13u + 1u);
  SweepPlanOptions o;
  o.from_kPa = 5;
  o.to_kPa = 33;
  o.step_kPa = 10;
  const SweepSchedule odd = plan_calibration_sweep(o, 60.0);
  EXPECT_DOUBLE_EQ(odd.holds[4].level_kPa, 33.0);  // 5, 15, 25, then `to` itself
}

TEST(SweepPlan, IdentificationExcitationsStayInRangeAndReverse) {
  SweepPlanOptions o;
  o.staircase = false;
  o.random = true;
  o.sine = true;
  o.to_kPa = 50;
  const SweepSchedule plan = plan_calibration_sweep(o, 60.0);
  int reversals = 0, direction = 0;
  std::size_t random = 0, sine = 0;
  for (std::size_t k = 0; k < plan.holds.size(); ++k) {
    const SweepHold& h = plan.holds[k];
    if (h.segment == SweepSegment::vent) {
      direction = 0;
      continue;
    }
    random += h.segment == SweepSegment::random;
    sine += h.segment == SweepSegment::sine;
    EXPECT_GE(h.level_kPa, 10.0 - 1e-9);
    EXPECT_LE(h.level_kPa, 50.0 + 1e-9);
    if (k && plan.holds[k - 1].segment == h.segment) {
      const int d = h.level_kPa > plan.holds[k - 1].level_kPa ? 1 : -1;
      reversals += direction != 0 && d != direction;
      direction = d;
    }
  }
  EXPECT_EQ(random, 60u);
  EXPECT_EQ(sine, 4u * 16u + 1u);
  EXPECT_GT(reversals, 40);
}

TEST(SweepPlan, RefusesArgumentsThatMakeNoSweep) {
  SweepPlanOptions o;
  o.to_kPa = 5;
  EXPECT_EQ(refusal([&] { plan_calibration_sweep(o, 60); }), "to_kPa: value: a pressure above `from_kPa`");
  o = {};
  o.step_kPa = 0;
  EXPECT_EQ(refusal([&] { plan_calibration_sweep(o, 60); }), "step_kPa: value: a step > 0 kPa");
  o = {};
  o.from_kPa = 70;
  EXPECT_EQ(refusal([&] { plan_calibration_sweep(o, 60); }),
            "from_kPa: value: a level below the rig's p_max (60 kPa), got 70 kPa");
  o = {};
  o.staircase = false;
  EXPECT_EQ(refusal([&] { plan_calibration_sweep(o, 60); }),
            "excitation: value: at least one of staircase, random, sine, step, chirp");
  o = {};
  o.chirp = true;
  o.chirp_from_hz = 5;
  o.chirp_to_hz = 2;
  EXPECT_EQ(refusal([&] { plan_calibration_sweep(o, 60); }),
            "chirp_to_hz: value: a chirp from a frequency > 0 to a higher one, at most 100 Hz");
  o = {};
  o.step = true;
  o.step_hold_s = 0.01;
  EXPECT_EQ(refusal([&] { plan_calibration_sweep(o, 60); }), "step_hold_s: value: a step hold of 0.05 to 60 s");
}

TEST(SweepPlan, AStaircaseTooShortToFitIsNamedBeforeItRuns) {
  SweepPlanOptions o;
  EXPECT_EQ(sweep_fit_shortfall(plan_calibration_sweep(o, 60)), "");  // paper 002's
  o.to_kPa = 20;
  o.repeats = 1;
  EXPECT_EQ(sweep_fit_shortfall(plan_calibration_sweep(o, 60)),
            "too short to fit: the inflation staircase has 2 holds over all repeats and a line needs 3 (lower Step, "
            "widen From/To or add repeats)");
  o.repeats = 2;  // two levels, twice: a line through 4 points
  EXPECT_EQ(sweep_fit_shortfall(plan_calibration_sweep(o, 60)), "");
  o.staircase = false;
  o.random = true;  // no staircase: no branch lines to judge
  EXPECT_EQ(sweep_fit_shortfall(plan_calibration_sweep(o, 60)), "");
}

TEST(SweepRunner, HoldsSettleOnTheSimulatedRigAndShowItsHysteresis) {
  CaliperRig rig(60.0);
  rig.open();
  SweepPlanOptions po;
  po.repeats = 1;
  const SweepSchedule plan = plan_calibration_sweep(po, 60.0);
  MemorySink sink;
  palprig::testing::LeasedRig leased1(rig);
  const SweepOutcome out = run_calibration_sweep(leased1.lease, plan, fast_options(), sink);
  EXPECT_FALSE(out.stopped);
  EXPECT_FALSE(out.faulted);
  EXPECT_EQ(out.holds_done, plan.holds.size());
  EXPECT_EQ(out.holds_unsettled, 0u);
  EXPECT_LE(rig.highest_write_kPa, 60.0);  // nothing above p_max was ever sent
  ASSERT_EQ(sink.holds.size(), plan.holds.size());
  // The simulated regulator's play of 2 kPa: inflation lands 2 below, deflation 2 above.
  for (const auto& h : sink.holds) {
    EXPECT_TRUE(h.outcome.settled);
    EXPECT_GE(h.outcome.hold_s, 0.5);  // settle test, then 0.3 s of averaging
    EXPECT_LT(h.outcome.hold_s, 2.0);
    if (h.hold.segment != SweepSegment::staircase || h.hold.level_kPa == 60.0) continue;
    const double expected = h.hold.level_kPa + (h.hold.branch == SweepBranch::inflation ? -2.0 : 2.0);
    // Noise 0.1 kPa over 30 samples: the mean is within 0.06 kPa (3 SD); a reading taken while
    // the lag's tail was still in it would be off by ~0.1 kPa towards the previous level.
    for (std::size_t c = 0; c < kFingerCount; ++c) EXPECT_NEAR(settled_mean(h, c), expected, 0.06) << h.hold.level_kPa;
    // The sensor follows: 0.012 mm/kPa through its own 1.5 kPa backlash.
    const auto& last = h.samples.back();
    const double sensor_expected =
        0.012 * (last.monitor_kPa[0] + (h.hold.branch == SweepBranch::inflation ? -1.5 : 1.5));
    EXPECT_NEAR(last.sensor[0], sensor_expected, 0.012 * 0.5);
  }
  EXPECT_GE(rig.vents, 1);  // the sweep ends vented
}

// The sweep once wrote its levels straight to the backend, past the tick's safety stage.
// Now every setpoint goes through it: with the rig's slew limit at 500 kPa/s and 100 steps a
// second, no write rises by more than 5 kPa, though the staircase steps by 10 kPa and each
// repeat starts from vented; the levels are still reached and recorded.
TEST(SweepRunner, EverySetpointPassesTheSafetyStage) {
  CaliperRig rig(60.0);
  rig.open();
  SweepPlanOptions po;
  po.repeats = 1;
  po.to_kPa = 40;
  SweepRunOptions ro = fast_options();
  ro.slew_kPa_per_s = 500;
  MemorySink sink;
  palprig::testing::LeasedRig leased2(rig);
  const SweepOutcome out = run_calibration_sweep(leased2.lease, plan_calibration_sweep(po, 60.0), ro, sink);
  EXPECT_FALSE(out.faulted) << out.fault;
  EXPECT_EQ(out.holds_unsettled, 0u);
  EXPECT_GT(rig.largest_rise_kPa, 4.9);
  EXPECT_LE(rig.largest_rise_kPa, 5.0 + 1e-9);
  for (const auto& h : sink.holds) {
    if (h.hold.segment == SweepSegment::staircase && h.hold.branch == SweepBranch::inflation) {
      EXPECT_NEAR(settled_mean(h, 0), h.hold.level_kPa - 2.0, 0.06) << h.hold.level_kPa;
    }
  }
  EXPECT_EQ(rig.state(), BackendState::disarmed);  // vented and disarmed at the end
}

TEST(SweepRunner, OnlySelectedChannelsAreDriven) {
  CaliperRig rig(60.0);
  rig.open();
  SweepPlanOptions po;
  po.repeats = 1;
  SweepRunOptions ro = fast_options();
  ro.channels = {false, true, false};
  MemorySink sink;
  palprig::testing::LeasedRig leased3(rig);
  run_calibration_sweep(leased3.lease, plan_calibration_sweep(po, 60.0), ro, sink);
  double most_1 = 0, most_2 = 0;
  for (const auto& h : sink.holds)
    for (const auto& s : h.samples) {
      most_1 = std::max(most_1, s.monitor_kPa[0]);
      most_2 = std::max(most_2, s.monitor_kPa[1]);
    }
  EXPECT_LT(most_1, 1.0);
  EXPECT_GT(most_2, 55.0);
}

namespace {
// The simulated rig behind a bus whose I/O thread vents on its own when the loop falls silent
// (Modbus's setpoint timeout): on the fifth write of the first deflation hold the machine
// "stalls" for 0.3 s, the plant empties at 0 kPa, and the write then ramps it up again from 0,
// all between two steps; only forced_vents() tells.
class StallingBusRig final : public RigBackend {
 public:
  explicit StallingBusRig(double p_max_kPa) : RigBackend(p_max_kPa), inner_(default_plants(), p_max_kPa) {}
  std::string describe() const override { return "stalling bus test rig"; }
  BackendCapabilities capabilities() const override {
    BackendCapabilities c;
    c.link_kind = "in-process";
    return c;
  }
  std::uint64_t forced_vents() const noexcept override { return stalls; }
  std::uint64_t stalls = 0;

 protected:
  void do_open() override {
    inner_.open();
    inner_.arm();
  }
  void do_close() noexcept override { inner_.close(); }
  BackendStatus do_write(const ChannelPressures& s, double t) noexcept override {
    if (s[0] < last_kPa_ - 1e-9 && s[0] > 0) ++deflation_writes_;
    last_kPa_ = s[0];
    if (deflation_writes_ == 5 && stalls == 0) {
      inner_.write({0, 0, 0}, t + offset_s_);
      offset_s_ += 0.3;
      ++stalls;
    }
    return inner_.write(s, t + offset_s_);
  }
  BackendStatus do_read(ChannelPressures& m, double t) noexcept override {
    return inner_.read_monitors(m, t + offset_s_);
  }
  BackendStatus do_vent() noexcept override { return inner_.vent(); }

 private:
  SimulatedRig inner_;
  double offset_s_ = 0, last_kPa_ = 0;
  int deflation_writes_ = 0;
};
}  // namespace

// A deflation hold whose plant the bus vented behind the sweep's back once read 2 kPa below its
// level (the rising branch) and went into the file as deflation. Now the step after the vent is
// an outage's, the hold is redone from the right branch, and every hold reads its branch.
TEST(SweepRunner, AHoldTheBusVentedBetweenTwoStepsIsRedoneFromItsBranch) {
  StallingBusRig rig(60.0);
  rig.open();
  SweepPlanOptions po;
  po.repeats = 1;
  MemorySink sink;
  palprig::testing::LeasedRig leased(rig);
  const SweepOutcome out = run_calibration_sweep(leased.lease, plan_calibration_sweep(po, 60.0), fast_options(), sink);
  EXPECT_FALSE(out.faulted) << out.fault;
  EXPECT_EQ(rig.stalls, 1u);
  EXPECT_EQ(out.holds_redone, 1u);
  EXPECT_EQ(out.holds_unsettled, 0u);
  std::size_t deflations = 0;
  for (const auto& h : sink.holds) {
    if (h.hold.segment != SweepSegment::staircase || h.hold.level_kPa == 60.0) continue;
    const double expected = h.hold.level_kPa + (h.hold.branch == SweepBranch::inflation ? -2.0 : 2.0);
    for (std::size_t c = 0; c < kFingerCount; ++c)
      EXPECT_NEAR(settled_mean(h, c), expected, 0.06) << to_string(h.hold.branch) << " " << h.hold.level_kPa;
    deflations += h.hold.branch == SweepBranch::deflation;
  }
  EXPECT_GE(deflations, 4u);
}

TEST(SweepRunner, StopSignalVentsAndKeepsWhatWasRecorded) {
  CaliperRig rig(60.0);
  rig.open();
  RunControl stop;
  SweepRunOptions ro = fast_options();
  ro.control = &stop;
  MemorySink sink;
  std::size_t seen = 0;
  const SweepSchedule plan = plan_calibration_sweep({}, 60.0);
  auto progress = [&](std::size_t done, std::size_t, const SweepHold&, const HoldOutcome&) {
    seen = done;
    if (done == 7) stop.signal_stop(2);  // SIGINT arrives during hold 8
  };
  palprig::testing::LeasedRig leased4(rig);
  const SweepOutcome out = run_calibration_sweep(leased4.lease, plan, ro, sink, progress);
  EXPECT_TRUE(out.stopped);
  EXPECT_EQ(out.stop_signal, 2);
  EXPECT_EQ(seen, 7u);
  EXPECT_EQ(out.holds_done, 7u);  // the interrupted hold had no sample yet
  EXPECT_EQ(sink.holds.size(), 7u);
  EXPECT_GE(rig.vents, 1);
}

TEST(SweepRunner, BackendFaultVentsAndReportsTheBackendsReason) {
  CaliperRig rig(60.0, 500);
  rig.open();
  MemorySink sink;
  palprig::testing::LeasedRig leased5(rig);
  const SweepOutcome out = run_calibration_sweep(leased5.lease, plan_calibration_sweep({}, 60.0), fast_options(), sink);
  EXPECT_TRUE(out.faulted);
  EXPECT_EQ(out.fault, "monitor read failed: cable unplugged");
  EXPECT_GT(out.holds_done, 5u);
  std::size_t samples = 0;
  for (const auto& h : sink.holds) samples += h.samples.size();
  EXPECT_EQ(samples, 500u);  // every good sample kept, the partial hold included
  EXPECT_GE(rig.vents, 1);
}

TEST(SweepRunner, ASinkThatThrowsLeavesTheRigVented) {
  CaliperRig rig(60.0);
  rig.open();
  struct FullDisk final : SweepSink {
    int holds = 0;
    void on_hold(std::size_t, const SweepHold&, std::span<const SweepSample>, const HoldOutcome&) override {
      if (++holds == 3) throw std::runtime_error("cannot write data.csv");
    }
  } sink;
  palprig::testing::LeasedRig leased6(rig);
  EXPECT_THROW(run_calibration_sweep(leased6.lease, plan_calibration_sweep({}, 60.0), fast_options(), sink),
               std::runtime_error);
  EXPECT_EQ(rig.vents, 1);
}

TEST(SweepRunner, AHoldThatNeverSettlesIsMarkedAndTheSweepGoesOn) {
  CaliperRig rig(60.0);
  rig.open();
  SweepPlanOptions po;
  po.repeats = 1;
  SweepRunOptions ro = fast_options();
  ro.settle_band_kPa = 1e-9;  // the monitor's noise never gets inside this
  ro.max_hold_s = 0.8;
  MemorySink sink;
  palprig::testing::LeasedRig leased7(rig);
  const SweepOutcome out = run_calibration_sweep(leased7.lease, plan_calibration_sweep(po, 60.0), ro, sink);
  EXPECT_EQ(out.holds_unsettled, out.holds_done);
  EXPECT_FALSE(out.faulted);
  for (const auto& h : sink.holds) {
    EXPECT_FALSE(h.outcome.settled);
    EXPECT_NEAR(h.outcome.hold_s, 0.8, 0.011);
  }
}

TEST(SweepCsv, RoundTripAveragesSettledRowsPerHold) {
  TempDir dir;
  CaliperRig rig(60.0);
  rig.open();
  SweepPlanOptions po;
  po.repeats = 2;
  const SweepSchedule plan = plan_calibration_sweep(po, 60.0);
  SweepFileInfo info;
  info.rig_id = "bench-7";
  info.backend = rig.describe();
  info.date = "2026-11-22T12:00:00Z";
  info.p_max_kPa = 60;
  info.rate_hz = 100;
  info.sensor_name = rig.sensor_name();
  info.notes = plan.notes;
  const auto path = dir.path() / "data.csv";
  MemorySink memory;
  {
    SweepCsvWriter writer(path, info, {true, false, true});
    struct Both final : SweepSink {
      SweepSink &a, &b;
      Both(SweepSink& x, SweepSink& y) : a(x), b(y) {}
      void on_hold(std::size_t i, const SweepHold& h, std::span<const SweepSample> s, const HoldOutcome& o) override {
        a.on_hold(i, h, s, o);
        b.on_hold(i, h, s, o);
      }
    } both(writer, memory);
    SweepRunOptions ro = fast_options();
    ro.channels = {true, false, true};
    palprig::testing::LeasedRig leased8(rig);
    writer.finish(run_calibration_sweep(leased8.lease, plan, ro, both));
  }
  const SweepData data = read_sweep_csv(path);
  EXPECT_EQ(data.info.rig_id, "bench-7");
  EXPECT_EQ(data.info.backend, "caliper test rig");
  EXPECT_EQ(data.info.sensor_name, "deformation_mm");
  EXPECT_EQ(data.info.p_max_kPa, 60);
  ASSERT_EQ(data.info.notes.size(), 1u);
  EXPECT_TRUE(data.has_monitor);
  EXPECT_TRUE(data.has_sensor);
  EXPECT_EQ(data.channels, (std::vector<int>{1, 3}));
  EXPECT_EQ(data.unsettled_holds, 0u);
  const auto ch3 = data.channel_points(3);
  ASSERT_EQ(ch3.size(), memory.holds.size());
  for (std::size_t k = 0; k < ch3.size(); ++k) {
    EXPECT_EQ(ch3[k].segment, memory.holds[k].hold.segment);
    EXPECT_EQ(ch3[k].branch, memory.holds[k].hold.branch);
    EXPECT_EQ(ch3[k].repeat, memory.holds[k].hold.repeat);
    EXPECT_DOUBLE_EQ(ch3[k].command_kPa, memory.holds[k].hold.level_kPa);
    EXPECT_NEAR(ch3[k].monitor_kPa, settled_mean(memory.holds[k], 2), 1e-3);  // 4 decimals in the file
    EXPECT_EQ(ch3[k].samples, 30u);                                           // the 0.3 s settle window at 100 Hz
  }
  EXPECT_TRUE(data.channel_points(2).empty());
}

TEST(SweepCsv, HandTypedTableWithoutHoldsOrMonitor) {
  TempDir dir;
  const auto p = dir.write("caliper.csv",
                           "# rig_id: bench-2\n"
                           "channel,branch,repeat,command_kPa,sensor\n"
                           "1,inflation,1,10,0.11\n1,inflation,1,20,0.23\n1,deflation,1,20,0.27\n");
  const SweepData d = read_sweep_csv(p);
  EXPECT_EQ(d.info.rig_id, "bench-2");
  EXPECT_FALSE(d.has_monitor);
  EXPECT_TRUE(d.has_sensor);
  ASSERT_EQ(d.points.size(), 3u);  // every row its own point
  EXPECT_EQ(d.points[2].branch, SweepBranch::deflation);
  EXPECT_DOUBLE_EQ(d.points[2].sensor, 0.27);
  EXPECT_TRUE(std::isnan(d.points[2].monitor_kPa));
  EXPECT_EQ(d.points[2].line, 5u);
}

TEST(SweepCsv, MalformedFilesAreRefusedWithTheLine) {
  TempDir dir;
  auto read = [&](const std::string& text) {
    const auto p = dir.write("d.csv", text);
    return refusal([&] { read_sweep_csv(p); });
  };
  const std::string f = (dir.path() / "d.csv").string();
  EXPECT_EQ(
      read("channel,command_kPa,pressure\n"),
      f + ": line 1: known columns (t_s, channel, hold, segment, repeat, branch, command_kPa, monitor_kPa, sensor, "
          "settled), got \"pressure\"");
  EXPECT_EQ(read("channel,command_kPa\n"), f + ": line 1: a monitor_kPa or a sensor column (the response to fit)");
  EXPECT_EQ(read("channel,command_kPa,monitor_kPa\n4,10,9\n"),
            f + ": line 2: an integer 1..3 in column channel, got \"4\"");
  EXPECT_EQ(read("channel,command_kPa,monitor_kPa\n1,10,NaN\n"),
            f + ": line 2: a finite number in column monitor_kPa, got \"NaN\"");
  EXPECT_EQ(read("channel,command_kPa,monitor_kPa\n1,10\n"), f + ": line 2: 3 cells like the header, got 2");
  EXPECT_EQ(read("channel,branch,command_kPa,monitor_kPa\n1,up,10,9\n"),
            f + ": line 2: branch inflation, deflation or none, got \"up\"");
  EXPECT_EQ(read("channel,hold,command_kPa,monitor_kPa\n1,3,10,9\n1,3,20,19\n"),
            f + ": line 3: one command, segment and branch per hold (hold 3 of channel 1 changes here)");
  EXPECT_EQ(read("# only comments\n"), f + ": header: a header line (t_s,channel,hold,...)");
  EXPECT_EQ(read("channel,command_kPa,monitor_kPa\n"), f + ": rows: at least one data row");
}
