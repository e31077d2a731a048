// The Modbus register map: raw-count encodings checked against hand-computed values for each
// kind of module, and maps a lab could get wrong refused when the rig file is loaded.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "rigs/modbus_link.hpp"
#include "formats/modbus_register_map.hpp"
#include "formats/rig_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

RegisterScale scale(int full_scale, bool is_signed, double lo, double hi, double kPa_per_volt, double volts_at_0 = 0) {
  RegisterScale s;
  s.raw_full_scale = full_scale;
  s.is_signed = is_signed;
  s.volts_lo = lo;
  s.volts_hi = hi;
  s.regulator.kPa_per_volt = kPa_per_volt;
  s.regulator.volts_at_0_kPa = volts_at_0;
  return s;
}

nlohmann::json wago_rig() {
  std::ifstream in(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json");
  return nlohmann::json::parse(in);
}

// Load a rig document through a real file; returns the InputError text ("" when accepted).
std::string load_error(const nlohmann::json& doc) {
  TempDir dir;
  const auto path = dir.write("rig.json", doc.dump(2));
  try {
    load_rig_file(path);
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

}  // namespace

TEST(ModbusRegisterScale, TwelveBitUnsignedZeroToTenVolts) {
  // Moxa E1241 / ADAM AO: 0..4095 over 0..10 V; regulator 10 kPa/V.
  const RegisterScale s = scale(4095, false, 0, 10, 10);
  EXPECT_EQ(s.word_from_kPa(0), 0);
  EXPECT_EQ(s.word_from_kPa(25), 1024);   // 2.5 V -> 1023.75 counts
  EXPECT_EQ(s.word_from_kPa(12.5), 512);  // 1.25 V -> 511.875
  EXPECT_EQ(s.word_from_kPa(60), 2457);   // 6 V -> 2457.0
  EXPECT_EQ(s.word_from_kPa(100), 4095);
  EXPECT_EQ(s.word_from_kPa(150), 4095);  // beyond the span: clamped, never wrapped
  EXPECT_NEAR(s.kPa_from_word(1024), 25.0061, 1e-4);
}

TEST(ModbusRegisterScale, FifteenBitWagoStyle) {
  // WAGO 750-559 style: 0..32767 over 0..10 V.
  const RegisterScale s = scale(32767, false, 0, 10, 10);
  EXPECT_EQ(s.word_from_kPa(25), 8192);     // 8191.75
  EXPECT_EQ(s.word_from_kPa(11.75), 3850);  // 1.175 V -> 3850.1225 (paper 002's hard-nodule pressure)
  EXPECT_NEAR(s.kPa_from_word(3850), 11.7496, 1e-4);
}

TEST(ModbusRegisterScale, SignedTwosComplement) {
  // A +/-10 V module with int16 counts -32767..32767.
  const RegisterScale s = scale(32767, true, -10, 10, 10);
  EXPECT_EQ(s.word_from_kPa(0), 0);
  EXPECT_EQ(s.word_from_kPa(25), 8192);                     // 2.5 V -> 8191.75
  EXPECT_EQ(s.word_from_volts(-2.5), 0xE000);               // -8192 in two's complement
  EXPECT_NEAR(s.volts_from_word(0xE000), -2.500076, 1e-6);  // -8192 / 32767 * 10 V
  EXPECT_EQ(s.word_from_volts(-20), std::uint16_t(-32767));
}

TEST(ModbusRegisterScale, OffsetBinarySixteenBit) {
  // ADAM-6024 AI style: 0..65535 over -10..+10 V.
  const RegisterScale s = scale(65535, false, -10, 10, 10);
  EXPECT_EQ(s.word_from_volts(0), 32768);  // 32767.5 rounds away from zero
  EXPECT_EQ(s.word_from_kPa(25), 40959);   // 40959.375
  EXPECT_NEAR(s.volts_from_word(0), -10.0, 1e-12);
}

TEST(ModbusRegisterScale, MonitorWithOffsetLikeSmcItv) {
  // ITV monitor: 1..5 V for 0..100 kPa = 25 kPa/V with 0 kPa at 1 V, read on a 0..10 V input.
  const RegisterScale s = scale(32767, false, 0, 10, 25, 1.0);
  EXPECT_EQ(s.word_from_kPa(50), 9830);  // 3 V -> 9830.1
  EXPECT_NEAR(s.kPa_from_word(9830), 49.9992, 1e-4);
  EXPECT_NEAR(s.kPa_from_word(3277), 0.0, 0.01);  // 1 V
}

TEST(ModbusRegisterScale, NonFiniteGoesToTheLowEdge) {
  const RegisterScale s = scale(4095, false, 0, 10, 10);
  EXPECT_EQ(s.word_from_volts(std::nan("")), 0);
  EXPECT_EQ(s.word_from_volts(INFINITY), 0);  // not a pressure at all: the safe side, not full scale
}

TEST(ModbusRegisterScale, RoundTripWithinHalfACount) {
  for (const RegisterScale& s :
       {scale(4095, false, 0, 10, 10), scale(32767, true, -10, 10, 10), scale(65535, false, 0, 5, 20)})
    for (double kPa = 0; kPa <= 60; kPa += 0.37)
      EXPECT_NEAR(
          s.kPa_from_word(s.word_from_kPa(kPa)), kPa,
          0.5 * (s.volts_hi - s.volts_lo) / double(s.raw_full_scale - s.raw_lo()) * s.regulator.kPa_per_volt + 1e-9);
}

TEST(ModbusLinkPlan, GroupsConsecutiveRegisters) {
  const auto runs = contiguous_runs({{12, 2}, {10, 0}, {11, 1}, {20, 3}});
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].start, 10);
  EXPECT_EQ(runs[0].channels, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(runs[1].start, 20);
  EXPECT_EQ(runs[1].channels, (std::vector<int>{3}));
}

TEST(ModbusRigFile, ShippedExamplesLoad) {
  for (const char* name : {"wago_750_559.json", "moxa_iologik_e1241.json", "advantech_adam_6024.json"}) {
    const RigConfig rig = load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/" + name);
    ASSERT_EQ(rig.backend, "modbus") << name;
    const ModbusRigConfig map = rig.modbus.value();
    for (std::size_t c = 0; c < kFingerCount; ++c) {
      // Every example must carry 0..p_max on its outputs.
      const auto& out = map.channels[c].output.scale;
      EXPECT_LE(out.volts_lo, out.regulator.volts(0)) << name;
      EXPECT_GE(out.volts_hi, out.regulator.volts(rig.safety.p_max_kPa)) << name;
    }
  }
}

TEST(ModbusRigFile, WagoMapReadsAsWritten) {
  const ModbusRigConfig map =
      load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json").modbus.value();
  ASSERT_EQ(map.links.size(), 1u);
  EXPECT_EQ(map.links[0].endpoint(), "tcp 127.0.0.1:1502");
  EXPECT_EQ(map.channels[2].output.address, 2);
  EXPECT_EQ(map.channels[2].monitor.kind, RegisterKind::input);
  EXPECT_EQ(map.channels[2].output.scale.raw_full_scale, 32767);
  EXPECT_DOUBLE_EQ(map.response_timeout_s, 0.05);
  EXPECT_DOUBLE_EQ(map.reconnect_initial_s, 0.1);
}

TEST(ModbusRigFile, RefusesAnOutputRegisterUsedTwice) {
  auto doc = wago_rig();
  doc["channels"][1]["output"]["register"] = 0;
  const std::string e = load_error(doc);
  EXPECT_NE(e.find("channels[1].output.register"), std::string::npos) << e;
  EXPECT_NE(e.find("also channel 1"), std::string::npos) << e;
}

TEST(ModbusRigFile, RefusesASpanThatCannotCarryPmax) {
  auto doc = wago_rig();
  doc["channels"][0]["output"]["kPa_per_volt"] = 5;  // 60 kPa would need 12 V on a 0-10 V output
  const std::string e = load_error(doc);
  EXPECT_NE(e.find("channels[0].output.volts_span"), std::string::npos) << e;
  EXPECT_NE(e.find("12 V"), std::string::npos) << e;
}

TEST(ModbusRigFile, RefusesASignedFullScaleBeyondInt16) {
  auto doc = wago_rig();
  doc["channels"][2]["output"]["signed"] = true;
  doc["channels"][2]["output"]["raw_full_scale"] = 65535;
  const std::string e = load_error(doc);
  EXPECT_NE(e.find("channels[2].output.raw_full_scale"), std::string::npos) << e;
}

TEST(ModbusRigFile, RefusesAMonitorOnAnotherChannelsOutput) {
  auto doc = wago_rig();
  doc["channels"][0]["monitor"] = {{"register", 1}, {"function", "holding"}};
  const std::string e = load_error(doc);
  EXPECT_NE(e.find("channels[0].monitor.register"), std::string::npos) << e;
  EXPECT_NE(e.find("channel 2's output"), std::string::npos) << e;
}

TEST(ModbusRigFile, AcceptsAMonitorReadingBackItsOwnOutput) {
  auto doc = wago_rig();
  doc["channels"][0]["monitor"] = {{"register", 0}, {"function", "holding"}};
  EXPECT_EQ(load_error(doc), "");
}

TEST(ModbusRigFile, RefusesMisspelledAndMissingFields) {
  auto doc = wago_rig();
  doc["channels"][0]["output"]["regster"] = 4;
  EXPECT_NE(load_error(doc).find("channels[0].output.regster"), std::string::npos);
  doc = wago_rig();
  doc["channels"][1].erase("monitor");
  EXPECT_NE(load_error(doc).find("channels[1].monitor"), std::string::npos);
  doc = wago_rig();
  doc["modbus"]["links"][0].erase("tcp");
  EXPECT_NE(load_error(doc).find("modbus.links[0].tcp"), std::string::npos);
}

TEST(ModbusRigFile, RefusesUnknownAndUnusedLinks) {
  auto doc = wago_rig();
  doc["channels"][0]["output"]["link"] = "wgo";
  EXPECT_NE(load_error(doc).find("channels[0].output.link"), std::string::npos);
  doc = wago_rig();
  doc["modbus"]["links"].push_back({{"name", "spare"}, {"tcp", {{"host", "10.0.0.2"}, {"port", 502}}}});
  for (auto& ch : doc["channels"]) ch["output"]["link"] = "wago", ch["monitor"]["link"] = "wago";
  const std::string e = load_error(doc);
  EXPECT_NE(e.find("modbus.links[1]"), std::string::npos) << e;
  EXPECT_NE(e.find("used by none"), std::string::npos) << e;
}

TEST(ModbusRigFile, RefusesBadTimingsAndSerialSettings) {
  auto doc = wago_rig();
  doc["modbus"]["reconnect_backoff_ms"] = {2000, 100};
  EXPECT_NE(load_error(doc).find("modbus.reconnect_backoff_ms"), std::string::npos);
  doc = wago_rig();
  doc["modbus"]["links"][0].erase("tcp");
  doc["modbus"]["links"][0]["rtu"] = {{"device", "/dev/ttyUSB0"}, {"baud", 9600}, {"parity", "X"}};
  EXPECT_NE(load_error(doc).find("modbus.links[0].rtu.parity"), std::string::npos);
}

TEST(ModbusRigFile, RunRefusesABadMapBeforeAnythingMoves) {
  TempDir dir;
  auto doc = wago_rig();
  doc["channels"][1]["output"]["register"] = 0;
  const auto rig = dir.write("bad.json", doc.dump());
  const auto r = palprig::test_support::run_process(palprig::test_support::palprig_bin() + " run --realtime --rig " +
                                                    rig.string() + " --scene " + PALPRIG_SOURCE_DIR +
                                                    "/data/scenes/phantom_abc.json --duration-s 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("channels[1].output.register"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
  const auto s = palprig::test_support::run_process(palprig::test_support::palprig_bin() +
                                                    " sim-rig --listen 127.0.0.1:0 --rig " + rig.string());
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("channels[1].output.register"), std::string::npos) << s.err;
}
