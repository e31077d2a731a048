// comedi conversion and clamping without a device: comedilib's polynomials built by hand, the
// clamping that must happen before comedi_from_physical (which neither clamps nor guards
// against wrap-around), and the device errors a lab sees.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "formats/comedi_config.hpp"
#include "rigs/comedi_conversion.hpp"
#include "rigs/comedi_rig.hpp"
#include "formats/rig_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

RegulatorScale regulator(double kPa_per_volt, double volts_at_0 = 0) {
  RegulatorScale r;
  r.kPa_per_volt = kPa_per_volt;
  r.volts_at_0_kPa = volts_at_0;
  return r;
}

// A 16-bit +/-10 V output (NI M-series style) driving a 0-10 V regulator at 10 kPa/V.
ComediConversion bipolar_16bit_output() {
  return make_comedi_conversion(linear_polynomial(-10, 10, 65535, COMEDI_FROM_PHYSICAL),
                                linear_polynomial(-10, 10, 65535, COMEDI_TO_PHYSICAL), 65535, -10, 10, 0, 10,
                                regulator(10));
}

nlohmann::json comedi_rig_doc() {
  std::ifstream in(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/ni_pcie_6259_comedi.json");
  return nlohmann::json::parse(in);
}

}  // namespace

TEST(ComediConversion, NominalLineMatchesHandComputedCounts) {
  const ComediConversion c = bipolar_16bit_output();
  EXPECT_EQ(counts_from_kPa(c, 0), 32768u);    // 0 V: 32767.5, rounded to even
  EXPECT_EQ(counts_from_kPa(c, 25), 40959u);   // 2.5 V: 40959.375
  EXPECT_EQ(counts_from_kPa(c, 60), 52428u);   // 6 V: 52428.0
  EXPECT_EQ(counts_from_kPa(c, 100), 65535u);  // 10 V: the top of the range
  EXPECT_NEAR(kPa_from_counts(c, 40959), 25.0, 10.0 * 20.0 / 65535);
}

TEST(ComediConversion, ALoadCellInputReadsVolts) {
  // A load cell's amplifier on an AI channel: counts -> volts, comedilib's nominal line.
  const ComediConversion c = bipolar_16bit_output();
  comedi_range range{-10.0, 10.0, UNIT_volt};
  // (comedi_to_phys says NaN at 0 and maxdata, its out-of-range marks: interior counts only.)
  for (lsampl_t counts : {1u, 32768u, 36044u, 65534u})
    EXPECT_NEAR(volts_from_counts(c, counts), comedi_to_phys(counts, &range, 65535), 1e-3) << counts;
}

TEST(ComediConversion, AgreesWithComediFromPhysForTheNominalRange) {
  // comedi_from_phys is comedilib's own (clamping) nominal conversion: an independent oracle.
  comedi_range range{-10.0, 10.0, UNIT_volt};
  const ComediConversion c = bipolar_16bit_output();
  for (double v = 0; v <= 10.0; v += 0.0137)
    EXPECT_NEAR(double(counts_from_volts(c, v)), double(comedi_from_phys(v, &range, 65535)), 1.0) << v << " V";
}

TEST(ComediConversion, ClampsToTheRegulatorSpanBeforeConverting) {
  const ComediConversion c = bipolar_16bit_output();
  // The card could go to -10 V, the regulator accepts 0-10 V: never below 0 V.
  EXPECT_EQ(counts_from_volts(c, -3.0), 32768u);
  EXPECT_EQ(counts_from_kPa(c, 150), 65535u);  // 15 V asked: 10 V given
  EXPECT_EQ(counts_from_volts(c, std::nan("")), 32768u);
}

TEST(ComediConversion, ClampsACalibrationThatReachesPastTheCountScale) {
  // A soft calibration whose line puts -10 V at -3 counts and +10 V at 65540 counts. Straight
  // through comedi_from_physical, +10 V would be 65540, which a 16-bit DAC wraps to 4 (about
  // -10 V), and -10 V would be a negative count. After clamping both stay on the scale.
  comedi_polynomial_t to_counts{};
  to_counts.order = 1;
  to_counts.coefficients[0] = 32768.5;
  to_counts.coefficients[1] = (65540.0 + 3.0) / 20.0;
  comedi_polynomial_t to_volts = linear_polynomial(-10, 10, 65535, COMEDI_TO_PHYSICAL);
  EXPECT_GT(comedi_from_physical(10.0, &to_counts), 65535u);  // what clamping prevents
  const ComediConversion c = make_comedi_conversion(to_counts, to_volts, 65535, -10, 10, -10, 10, regulator(10));
  EXPECT_EQ(counts_from_volts(c, 10.0), 65535u);
  EXPECT_EQ(counts_from_volts(c, -10.0), 0u);
  EXPECT_LT(c.safe_hi_V, 10.0);
  EXPECT_GT(c.safe_lo_V, -10.0);
  // Inside the safe span the calibration is applied unchanged.
  EXPECT_EQ(counts_from_volts(c, 1.0), comedi_from_physical(1.0, &to_counts));
}

TEST(ComediConversion, MonitorWithAnOffsetReadsBackInKilopascals) {
  // SMC ITV monitor 1-5 V for 0-100 kPa on a 12-bit 0-10 V input.
  const ComediConversion c = make_comedi_conversion(linear_polynomial(0, 10, 4095, COMEDI_FROM_PHYSICAL),
                                                    linear_polynomial(0, 10, 4095, COMEDI_TO_PHYSICAL), 4095, 0, 10, 0,
                                                    10, regulator(25, 1.0));
  EXPECT_NEAR(kPa_from_counts(c, 2048), (2048.0 / 4095 * 10 - 1) * 25, 1e-9);
  EXPECT_NEAR(kPa_from_counts(c, 410), 0.0, 0.1);  // about 1 V
}

TEST(ComediConversion, RefusesAFallingPolynomialOrASpanOutsideTheRange) {
  EXPECT_THROW(make_comedi_conversion(linear_polynomial(10, -10, 65535, COMEDI_FROM_PHYSICAL),
                                      linear_polynomial(-10, 10, 65535, COMEDI_TO_PHYSICAL), 65535, -10, 10, 0, 10,
                                      regulator(10)),
               palprig::BadInput);
  EXPECT_THROW(
      make_comedi_conversion(linear_polynomial(0, 5, 4095, COMEDI_FROM_PHYSICAL),
                             linear_polynomial(0, 5, 4095, COMEDI_TO_PHYSICAL), 4095, 0, 5, 6, 10, regulator(10)),
      palprig::BadInput);
}

TEST(ComediRigFile, ExampleLoadsAndBadSectionsAreRefused) {
  TempDir dir;
  auto load = [&](const nlohmann::json& doc) {
    try {
      load_rig_file(dir.write("rig.json", doc.dump()));
      return std::string();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(load(comedi_rig_doc()), "");
  const ComediRigConfig cfg =
      load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/ni_pcie_6259_comedi.json").comedi.value();
  EXPECT_EQ(cfg.device, "/dev/comedi0");
  EXPECT_DOUBLE_EQ(cfg.monitors[1].regulator.volts_at_0_kPa, 1.0);
  auto doc = comedi_rig_doc();
  doc["channels"][2]["output"]["channel"] = 0;
  EXPECT_NE(load(doc).find("channels[2].output.channel"), std::string::npos);
  doc = comedi_rig_doc();
  doc["channels"][0]["output"]["volts_span"] = {0, 5};  // 60 kPa needs 6 V
  EXPECT_NE(load(doc).find("channels[0].output.volts_span"), std::string::npos);
  doc = comedi_rig_doc();
  doc["comedi"]["calibration"] = "magic";
  EXPECT_NE(load(doc).find("comedi.calibration"), std::string::npos);
  doc = comedi_rig_doc();
  doc["comedi"]["calibration"] = "hard";
  doc["comedi"]["calibration_file"] = "/tmp/x.cal";
  EXPECT_NE(load(doc).find("comedi.calibration_file"), std::string::npos);
}

TEST(ComediDevice, AMissingDeviceIsOneClearLineAndExitTwo) {
  TempDir dir;
  auto doc = comedi_rig_doc();
  doc["comedi"]["device"] = (dir.path() / "comedi_absent").string();
  const auto rig = dir.write("rig.json", doc.dump());
  const auto r = palprig::test_support::run_process(palprig::test_support::palprig_bin() + " run --rig " +
                                                    rig.string() + " --scene " + PALPRIG_SOURCE_DIR +
                                                    "/data/scenes/phantom_abc.json --duration-s 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find((dir.path() / "comedi_absent").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No such file or directory"), std::string::npos) << r.err;  // comedi's own words
}

TEST(ComediDevice, AFileThatIsNotAComediDeviceIsRefused) {
  TempDir dir;
  auto doc = comedi_rig_doc();
  doc["comedi"]["device"] = "/dev/null";
  const RigConfig rig = load_rig_file(dir.write("rig.json", doc.dump()));
  ComediRig backend(rig.comedi.value());
  try {
    backend.open();
    FAIL() << "/dev/null accepted as a comedi device";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/null"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("comedi_open"), std::string::npos) << e.what();
  }
}

TEST(ComediDevice, DrivesARealBoardWhenOneIsPresent) {
  std::string device;
  for (int i = 0; i < 16 && device.empty(); ++i)
    if (std::filesystem::exists("/dev/comedi" + std::to_string(i))) device = "/dev/comedi" + std::to_string(i);
  if (device.empty())
    GTEST_SKIP() << "no /dev/comedi* device on this machine (load a board's driver, or comedi_test with "
                    "comedi_config /dev/comedi0 comedi_test, to run this test)";
  TempDir dir;
  auto doc = comedi_rig_doc();
  doc["comedi"]["device"] = device;
  doc["comedi"]["calibration"] = "hard";  // no soft-calibration file needed for a smoke test
  for (auto& ch : doc["channels"]) ch["monitor"]["volts_span"] = {0, 5};
  ComediRig rig(load_rig_file(dir.write("rig.json", doc.dump())).comedi.value());
  rig.open();
  ASSERT_EQ(rig.arm(), BackendStatus::ok) << rig.last_error();
  ChannelPressures monitors{};
  EXPECT_EQ(rig.write({0, 0, 0}, 0), BackendStatus::ok) << rig.last_error();
  EXPECT_EQ(rig.read_monitors(monitors, 0), BackendStatus::ok) << rig.last_error();
  for (double m : monitors) EXPECT_TRUE(std::isfinite(m));
  EXPECT_EQ(rig.write({61, 0, 0}, 0), BackendStatus::error);  // above p_max: refused and vented
  rig.close();
}
