// palprig fe as a user runs it: the stress model derived from the shipped files goes through
// calibrate fit (which says it used it, and whose calibration holds its numbers) and runs the
// demo; fe indent writes its tables and figures; refused inputs exit 2 with one line.
//
// Coarse settings (2-3 mm elements where the paper's are 1 mm; the stress model's round trip pressed
// 4 mm rather than 7, the actuator 0.25 mm rather than the shipped model's 0.5 mm, at two air
// pressures: 11 s of CPU where the shipped settings take 35 s, and under the sanitizers, where
// GetFEM's many small allocations are slow, about a third of the 324 s it took; since the laws are
// GetFEM operators computed in C++, 6.4 s and 33 s under the sanitizers): CI runs every
// suite twice, and these check the commands' plumbing, not the paper's figures
// (bench/bench_fe_paper002 and docs/finite-element.md measure those).
#include <gtest/gtest.h>

#include <fstream>

#include "formats/calibration_file.hpp"
#include "formats/fe_result_files.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

using test_support::palprig_bin;
using test_support::run_process;
using test_support::source_dir;
using test_support::TempDir;

const std::string kFe = source_dir() + "/data/fe/";

TEST(FeCommand, StressModelRoundTripsThroughCalibrateFitAndRunsTheDemo) {
  TempDir dir;
  const std::string model = (dir.path() / "model.json").string();
  auto r =
      run_process(palprig_bin() + " fe stress-model --fingertip " + kFe + "fingertip_002.json --tissue " + kFe +
                  "soft_tissue_002_nodule.json --actuator " + kFe +
                  "actuator_002.json --element-mm 3 --depth-mm 4 --press-mm 0.25 --pressures 0,100 --out " + model);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("palprig fe stress-model (soft tissue): step 4 of 4"), std::string::npos) << r.err;
  const FeStressModelFile m = load_stress_model_file(model);
  EXPECT_GT(m.hard_stress_kPa, m.soft_stress_kPa);
  EXPECT_GT(m.actuator.slope, 0);
  EXPECT_EQ(m.pressures_kPa, (std::vector<double>{0, 100}));
  EXPECT_EQ(m.loading, "press-first");  // the default; `--loading together` is measured in docs/finite-element.md
  EXPECT_NE(r.out.find("wrote " + model), std::string::npos);

  const std::string sweep = (dir.path() / "sweep.csv").string(), cal = (dir.path() / "cal.json").string();
  r = run_process(palprig_bin() + " calibrate sweep --channels 1,2,3 --repeats 1 --out " + sweep);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  r = run_process(palprig_bin() + " calibrate fit " + sweep + " --stress-model " + model + " --out " + cal);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("actuator stress lines kept from the finite-element stress model " + model), std::string::npos)
      << r.out;
  const CalibrationModels c = load_calibration_file(cal);
  EXPECT_NEAR(c.stress.soft_stress_kPa, m.soft_stress_kPa, 1e-9);
  EXPECT_NEAR(c.stress.hard_stress_kPa, m.hard_stress_kPa, 1e-9);
  for (const ActuatorModel& a : c.actuators) {
    EXPECT_NEAR(a.slope, m.actuator.slope, 1e-9);
    EXPECT_NEAR(a.intercept_kPa, m.actuator.intercept_kPa, 1e-9);
  }
  r = run_process(palprig_bin() + " demo --cal " + cal + " --out " + (dir.path() / "demo").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Every tumor got higher pressure than soft tissue."), std::string::npos) << r.out;
}

// Paper 002's reading of its actuator (the uninflated actuator stands for healthy tissue): the
// same solves, the line's slope kept and its intercept moved to the soft stress, so the nodule's
// air is (hard - soft) / slope; the file says so and calibrate fit takes the line as written.
TEST(FeCommand, StressModelWithTheUninflatedActuatorAsSoftTissue) {
  TempDir dir;
  const std::string fitted = (dir.path() / "fitted.json").string(), soft = (dir.path() / "soft.json").string();
  const std::string common = palprig_bin() + " fe stress-model --fingertip " + kFe + "fingertip_002.json --tissue " +
                             kFe + "soft_tissue_002_nodule.json --actuator " + kFe +
                             "actuator_002.json --element-mm 3 --depth-mm 4 --press-mm 0.5 --loading together "
                             "--pressures 0,50,100 --out ";
  auto r = run_process(common + fitted);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  r = run_process(common + soft + " --uninflated soft-tissue");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("the uninflated actuator as soft tissue: stress = "), std::string::npos) << r.out;
  const FeStressModelFile f = load_stress_model_file(fitted), s = load_stress_model_file(soft);
  EXPECT_EQ(f.uninflated, "fitted");
  EXPECT_EQ(s.uninflated, "soft-tissue");
  EXPECT_NE(f.inputs.hash, s.inputs.hash);  // a cached result of one is not the other
  EXPECT_DOUBLE_EQ(s.actuator.slope, f.actuator.slope);
  EXPECT_DOUBLE_EQ(s.actuator.intercept_kPa, s.soft_stress_kPa);
  EXPECT_NEAR(s.nodule_pressure_kPa, (s.hard_stress_kPa - s.soft_stress_kPa) / s.actuator.slope, 1e-9);
  EXPECT_LT(s.nodule_pressure_kPa, f.nodule_pressure_kPa);
  r = run_process(palprig_bin() + " check " + soft);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("(the uninflated actuator as soft tissue)"), std::string::npos) << r.out;
  r = run_process(common + soft + " --uninflated inflated");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
}

TEST(FeCommand, IndentWritesTablesAndFigures) {
  TempDir dir;
  const auto out = dir.path() / "indent";
  auto r = run_process(palprig_bin() + " fe indent --fingertip " + kFe + "fingertip_002.json --tissue " + kFe +
                       "soft_tissue_002.json --element-mm 2 --depth-mm 2 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  for (const char* f : {"soft_tissue_002_steps.csv", "soft_tissue_002_profiles.csv", "soft_tissue_002_mesh.png",
                        "soft_tissue_002_mesh.svg", "contact_stress.png", "contact_stress.svg"})
    EXPECT_GT(std::filesystem::file_size(out / f), 100u) << f;
  std::ifstream steps(out / "soft_tissue_002_steps.csv");
  std::string header, first, second;
  std::getline(steps, header);
  std::getline(steps, first);
  std::getline(steps, second);
  EXPECT_EQ(header, "depth_mm,peak_kPa,node_peak_kPa,peak_at_mm,force_N_per_m,contact_length_mm,newton_iterations");
  EXPECT_EQ(first.rfind("1,", 0), 0u) << first;
  EXPECT_EQ(second.rfind("2,", 0), 0u) << second;
}

TEST(FeCommand, RefusedFilesAndArgumentsExitTwoWithOneLine) {
  TempDir dir;
  const auto bad = dir.path() / "tissue.json";
  std::ofstream(bad) << R"({"version": 1, "kind": "tissue", "block": {"width_mm": 30, "height_mm": 100},
    "inclusions": [{"centre_depth_mm": 3, "diameter_mm": 10}]})";
  auto r = run_process(palprig_bin() + " fe indent --fingertip " + kFe + "fingertip_002.json --tissue " + bad.string() +
                       " --out " + (dir.path() / "o").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: " + bad.string() +
                       ": inclusions[0].centre_depth_mm: a centre at least 0.5 mm deeper than the radius (5 mm): the "
                       "inclusion must stay under the surface\n");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "o")) << "nothing is written for a refused file";
  r = run_process(palprig_bin() + " fe stress-model --fingertip " + kFe + "fingertip_002.json --tissue " + kFe +
                  "soft_tissue_002.json --actuator " + kFe + "actuator_002.json --out " +
                  (dir.path() / "m.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: " + kFe +
                       "soft_tissue_002.json: inclusions: a nodule: the stress over it is the model's "
                       "hard stress\n");
  r = run_process(palprig_bin() + " fe actuator --fingertip " + kFe + "fingertip_002.json --actuator " + kFe +
                  "actuator_002.json --loading sideways --out " + (dir.path() / "a").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--loading"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sideways"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "a"));
  r = run_process(palprig_bin() + " fe stress-model --fingertip " + kFe + "fingertip_002.json --tissue " + kFe +
                  "soft_tissue_002_nodule.json --actuator " + kFe + "actuator_002.json --loading sideways --out " +
                  (dir.path() / "m.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--loading"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "m.json"));
  r = run_process(palprig_bin() + " check " + kFe + "fingertip_002.json " + kFe + "actuator_002.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("fingertip_002.json: fingertip, 16 x 12 mm"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace palprig
