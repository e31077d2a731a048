// A calibration sweep over a real fieldbus that loses its link mid-hold.
// `palprig sim-rig` serves the WAGO map on loopback; the sweep runs in this process on the
// Modbus backend in real time; the simulator is SIGSTOPped mid-sweep and continued 0.1 s after
// the link is reported lost. The interrupted hold is redone from the right hysteresis branch,
// nothing recorded during the outage reaches the file, and `calibrate fit` takes the file.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <thread>

#include "calibration/sweep_csv.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_recording.hpp"
#include "formats/rig_file.hpp"
#include "rigs/modbus_rig.hpp"
#include "tests/support/modbus_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;
using namespace palprig::test_support;
using namespace std::chrono_literals;

namespace {

template <class Ready>
bool poll_until(Ready ready, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (ready()) return true;
    std::this_thread::sleep_for(2ms);
  }
  return ready();
}

}  // namespace

TEST(SweepOverAFailingLink, AHoldThatSpansAnOutageIsRedoneAndTheFileFits) {
  TempDir dir;
  const std::string rig_src = source_dir() + "/data/rigs/wago_750_559.json";
  std::unique_ptr<WatchedProcess> sim;
  const int port = start_sim_rig(sim, palprig_bin(), rig_src, 0, (dir.path() / "writes.csv").string(),
                                 (dir.path() / "sim.err").string());
  auto rig_json = rig_on_port(read_json(rig_src), port);
  rig_json["modbus"]["io_thread_fifo_priority"] = 0;
  const auto rig_file = dir.path() / "rig.json";
  std::ofstream(rig_file) << rig_json.dump(2);
  const RigConfig rig = load_rig_file(rig_file);
  ModbusRig backend(*rig.modbus);
  backend.set_log_sink(nullptr);
  backend.open();

  SweepPlanOptions plan;
  plan.step_kPa = 10;  // 10..60 kPa up and down: enough holds for the fit's hysteresis stage
  plan.repeats = 1;
  const SweepSchedule schedule = plan_calibration_sweep(plan, rig.safety.p_max_kPa);
  SweepRunOptions run;
  run.realtime = true;
  run.slew_kPa_per_s = rig.safety.slew_kPa_per_s;
  const auto data = dir.path() / "data.csv";
  std::atomic<std::size_t> done{0};
  SweepRecording recording;
  palprig::testing::LeasedRig leased(backend);
  std::thread sweep([&] {
    recording =
        record_calibration_sweep(leased.lease, rig, schedule, run, data,
                                 [&](std::size_t d, std::size_t, const SweepHold&, const HoldOutcome&) { done = d; });
  });
  // Into the falling branch: the next hold (40 kPa coming down from 60) is the one cut.
  const std::size_t cut_after = 9;  // holds: vent, 10..60 up (1-6), 60..10 down (7-12), vent
  ASSERT_LT(cut_after, schedule.holds.size());
  const bool reached = poll_until([&] { return done.load() >= cut_after; }, 60.0);
  if (reached) {
    sim->signal(SIGSTOP);
    EXPECT_TRUE(poll_until([&] { return !backend.linked(); }, 5.0)) << "the outage was never noticed";
    std::this_thread::sleep_for(100ms);  // the outage itself: the link comes back 0.1 s later
    sim->signal(SIGCONT);
  }
  sweep.join();
  backend.close();
  sim->signal(SIGTERM);
  sim->wait();
  ASSERT_TRUE(reached) << "the sweep never got to hold " << cut_after;

  const SweepOutcome& o = recording.outcome;
  EXPECT_FALSE(o.faulted) << o.fault;
  EXPECT_EQ(o.holds_done, o.holds_planned);
  EXPECT_EQ(o.holds_unsettled, 0u);
  EXPECT_GE(o.holds_redone, 1u);

  // No "nan", and every settled row read the plant at its level (not vented): the served
  // plant's 2 kPa play on the right branch, also for the redone hold.
  std::ifstream in(data);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_NE(text.find("# redone: "), std::string::npos);
  const SweepData d = read_sweep_csv(data);
  std::size_t checked = 0;
  for (const HoldPoint& p : d.points) {
    if (p.segment != SweepSegment::staircase || p.command_kPa == 60) continue;
    const double expected = p.command_kPa + (p.branch == SweepBranch::inflation ? -2.0 : 2.0);
    EXPECT_NEAR(p.monitor_kPa, expected, 0.3)
        << "channel " << p.channel << " hold " << p.hold << " " << to_string(p.branch) << " " << p.command_kPa;
    ++checked;
  }
  EXPECT_EQ(checked, 3u * 10u);
  EXPECT_EQ(d.unsettled_holds, 0u);

  // The sweep's own file is fittable.
  const auto r =
      run_process(palprig_bin() + " calibrate fit " + data.string() + " --out " + (dir.path() / "cal.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
}

TEST(SweepCsv, AMonitorWithoutAReadingIsAnEmptyUnsettledCell) {
  TempDir dir;
  const auto path = dir.path() / "d.csv";
  {
    SweepFileInfo info;
    info.rig_id = "r";
    info.rate_hz = 100;
    info.p_max_kPa = 60;
    SweepCsvWriter w(path, info, {true, true, true});
    SweepHold hold{SweepSegment::staircase, 1, SweepBranch::inflation, 10};
    std::vector<SweepSample> samples(3);
    for (auto& s : samples) {
      s.command_kPa = 10;
      s.monitor_kPa = {8, 8, 8};
      s.sensor.fill(std::nan(""));
      s.settled = true;
    }
    samples[1].monitor_kPa[1] = std::nan("");
    w.on_hold(1, hold, samples, HoldOutcome{true, 1});
    w.finish(SweepOutcome{});
  }
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  const SweepData d = read_sweep_csv(path);  // read back without refusal
  EXPECT_EQ(d.points.size(), 3u);
}
