// Hysteresis compensation on the default simulated plant, end to end in process: sweep,
// fit, then the controller's tick with and without the fitted inverse. The bar: the
// compensated tracking error at least 5x lower.
#include <gtest/gtest.h>

#include <atomic>
#include <functional>

#include "controller/backend_factory.hpp"
#include "calibration/calibration_fit.hpp"
#include "calibration/calibration_writer.hpp"
#include "calibration/compensation_evaluation.hpp"
#include "calibration/sweep_csv.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_runner.hpp"
#include "formats/rig_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

RigConfig default_rig_file() { return load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated.json"); }

// Sweep (staircase + random + sine) and fit on a rig, as `calibrate sweep` and `fit` do.
CalibrationModels calibrate(const RigConfig& rig, const TempDir& dir) {
  auto backend = make_backend(rig);
  backend->open();
  SweepPlanOptions po;
  po.random = po.sine = true;
  const SweepSchedule plan = plan_calibration_sweep(po, rig.safety.p_max_kPa);
  SweepFileInfo info;
  info.rig_id = rig.id;
  const auto data = dir.path() / "data.csv";
  {
    SweepCsvWriter writer(data, info, {true, true, true});
    SweepRunOptions ro;
    ro.realtime = false;
    palprig::testing::LeasedRig leased1(*backend);
    writer.finish(run_calibration_sweep(leased1.lease, plan, ro, writer));
  }
  CalibrationFitOptions fo;
  fo.date = "test";
  const CalibrationResult r = fit_calibration(read_sweep_csv(data), fo);
  return write_calibration_file(dir.path() / "cal.json", calibration_json(r));
}

EvaluationOptions fast(double duration_s = 60) {
  EvaluationOptions o;
  o.realtime = false;
  o.duration_s = duration_s;
  return o;
}

}  // namespace

TEST(CompensationEvaluation, FittedInverseCutsTrackingErrorAtLeastFiveTimes) {
  TempDir dir;
  const RigConfig rig = default_rig_file();
  const CalibrationModels cal = calibrate(rig, dir);
  auto backend = make_backend(rig);
  backend->open();
  palprig::testing::LeasedRig leased2(*backend);
  const EvaluationResult r = evaluate_compensation(leased2.lease, rig, cal, fast());
  ASSERT_TRUE(r.complete());
  EXPECT_GE(r.reversals, 3u);
  EXPECT_DOUBLE_EQ(r.to_kPa, 48.0);  // 80 % of the rig's 60 kPa
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    const TrackingMetrics &off = r.uncompensated.channels[c], &on = r.compensated.channels[c];
    EXPECT_GT(off.samples, 50000u);
    // The plant's 2 kPa play: about 2 kPa of error and a 4 kPa gap between the branches.
    EXPECT_NEAR(off.rms_error_kPa, 2.0, 0.2);
    EXPECT_GT(off.gap_kPa, 3.0);
    EXPECT_LT(std::abs(on.gap_kPa), 0.3);
    EXPECT_GE(r.improvement[c], 5.0) << "channel " << c + 1;
    EXPECT_GT(on.r_squared, 0.999);
    EXPECT_LT(off.r_squared, on.r_squared);
  }
  EXPECT_GE(r.worst_improvement, 5.0);
}

TEST(CompensationEvaluation, AModelOfTheWrongPlantDoesNotPass) {
  // Calibrate a rig whose regulators have a 0.5 kPa play, then drive the 2 kPa default with
  // it: the evaluation must show that it falls short (the measure can fail).
  TempDir dir;
  RigConfig narrow = default_rig_file();
  for (auto& p : narrow.plants) p.hysteresis_kPa = 0.5;
  const CalibrationModels wrong = calibrate(narrow, dir);
  const RigConfig rig = default_rig_file();
  auto backend = make_backend(rig);
  backend->open();
  palprig::testing::LeasedRig leased3(*backend);
  const EvaluationResult r = evaluate_compensation(leased3.lease, rig, wrong, fast(30));
  EXPECT_LT(r.worst_improvement, 2.0);
}

TEST(CompensationEvaluation, StopSignalVentsAndReportsAnIncompleteRun) {
  TempDir dir;
  const RigConfig rig = default_rig_file();
  const CalibrationModels cal = calibrate(rig, dir);
  auto backend = make_backend(rig);
  backend->open();
  RunControl stop;
  stop.signal_stop(15);
  EvaluationOptions o = fast();
  o.control = &stop;
  palprig::testing::LeasedRig leased4(*backend);
  const EvaluationResult r = evaluate_compensation(leased4.lease, rig, cal, o);
  EXPECT_FALSE(r.complete());
  EXPECT_TRUE(r.uncompensated.stopped);
}

TEST(CompensationEvaluation, RefusesWhatCannotBeEvaluated) {
  const RigConfig rig = default_rig_file();
  auto backend = make_backend(rig);
  backend->open();
  auto refusal = [&](const CalibrationModels& cal, const EvaluationOptions& o) -> std::string {
    try {
      palprig::testing::LeasedRig leased5(*backend);
      evaluate_compensation(leased5.lease, rig, cal, o);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  const std::string paper_file = std::string(PALPRIG_SOURCE_DIR) + "/data/calibration/paper002.json";
  const CalibrationModels paper = load_calibration_file(paper_file);
  EXPECT_EQ(refusal(paper, fast()), paper_file +
                                        ": channels[0].hysteresis: a hysteresis model for channel 1 to evaluate "
                                        "(run palprig calibrate fit first)");
  CalibrationModels cal;
  cal.hysteresis[0].linear_weight = 0.5;  // any non-identity model passes this check
  cal.hysteresis[1] = cal.hysteresis[2] = cal.hysteresis[0];
  EvaluationOptions o = fast();
  o.to_kPa = 59;
  EXPECT_EQ(refusal(cal, o), "to_kPa: value: at most the rig's p_max (60 kPa) minus room for the compensation");
  o = fast();
  o.ramp_kPa_per_s = 0;
  EXPECT_EQ(refusal(cal, o), "ramp_kPa_per_s: value: a ramp rate in (0, 1000] kPa/s");
}
