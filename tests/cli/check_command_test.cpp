// palprig check: every shipped file goes through its reader and is named by kind; a refused file
// is the reader's one line and exit 2, with nothing printed for it on stdout.
#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig::test_support;

namespace {}  // namespace

TEST(CheckCommand, EveryShippedFileIsReadAndNamedByItsKind) {
  const ProcessResult r =
      run_process(palprig_bin() + " check " + palprig::testing::shipped_data("rigs/wago_750_559.json") + " " +
                  palprig::testing::shipped_data("rigs/ni_pcie_6259_comedi.json") + " " +
                  palprig::testing::shipped_data("scenes/phantom_abc.json") + " " +
                  palprig::testing::shipped_data("scenes/brachial_pulse.json") + " " +
                  palprig::testing::shipped_data("protocols/discrimination_002.json") + " " +
                  palprig::testing::shipped_data("protocols/threshold_quest.json") + " " +
                  palprig::testing::shipped_data("protocols/pulse_generated.json") + " " +
                  palprig::testing::shipped_data("calibration/sim-default.json") + " " +
                  palprig::testing::shipped_data("traces/phantom_abc_pass.csv") + " " +
                  palprig::testing::shipped_data("waveforms/brachial_pressure.csv") + " " +
                  palprig::testing::shipped_data("scenes/phantom_abc.pgm"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* said :
       {"rig 'wago-750-559', backend modbus", "rig 'ni-pcie-6259-comedi', backend comedi",
        "map scene 'phantom_abc', 3 tumors", "function scene 'brachial_pulse', 0 tumors, arteries",
        "discrimination protocol", "threshold protocol", "pulse protocol", "calibration for rig 'sim-default'",
        "pen trace, 1330 rows", "waveform table", "stiffness map, 161 x 121 vertices"})
    EXPECT_NE(r.out.find(said), std::string::npos) << said << "\n" << r.out;
}

TEST(CheckCommand, ARefusedFileIsOneLineAndExitTwo) {
  TempDir dir;
  const auto scene = dir.path() / "scene.json";
  std::ofstream(scene) << R"({"version": 1, "kind": "function", "body": {"centre_mm": [0, 0], "half_size_mm": [50, 50]},
    "layers": [{"name": "skin", "thickness_mm": 2, "stiffness_kPa": 10}], "felt_range_kPa": {"soft": 10, "hard": 40},
    "inclusions": [{"name": "A", "stiffness_kPa": 30, "shape": {"type": "difference",
      "shape": {"type": "sphere", "centre_mm": [0, 0, 5], "radius_mm": 4},
      "minus": {"type": "sphere", "centre_mm": [0, 0, 5], "radius_mm": 2}}}]})";
  const ProcessResult r = run_process(palprig_bin() + " check " + scene.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");  // nothing about the refused file on stdout
  EXPECT_NE(r.err.find("inclusions[0].shape.from: a value (field is missing)"), std::string::npos) << r.err;
}

TEST(CheckCommand, KindCanBeGivenAndIsThenEnforced) {
  const ProcessResult r =
      run_process(palprig_bin() + " check --kind rig " + palprig::testing::shipped_data("scenes/phantom_abc.json"));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  const ProcessResult bad =
      run_process(palprig_bin() + " check --kind nonsense " + palprig::testing::shipped_data("rigs/simulated.json"));
  EXPECT_NE(bad.exit_code, 0);
}
