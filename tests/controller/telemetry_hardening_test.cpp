// Telemetry that a file or a runaway run can make hostile: rows with extreme floats (the CSV
// row writer once summed snprintf results into a fixed buffer and wrote past it), mutated
// binary files through `telemetry to-csv`, and a writer that must stop before the disk fills.
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "core/error.hpp"
#include "controller/telemetry_writer.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream s(row);
  std::string c;
  while (std::getline(s, c, ',')) out.push_back(c);
  return out;
}

std::size_t header_columns() {
  std::ostringstream h;
  write_telemetry_csv_header(h);
  std::string line = h.str();
  line.pop_back();
  return cells(line).size();
}

TelemetryRecord extreme_record(float v) {
  TelemetryRecord r;
  r.tick = std::numeric_limits<std::uint64_t>::max();
  r.t_s = -std::numeric_limits<double>::max();
  r.x_mm = r.y_mm = r.force_N = v;
  for (int i = 0; i < kFingerCount; ++i) r.stiffness[i] = r.target_kPa[i] = r.setpoint_kPa[i] = r.monitor_kPa[i] = v;
  for (int i = 0; i < kFingerCount; ++i) r.drag_x_mm[i] = r.drag_y_mm[i] = v;
  r.wake_latency_us = r.io_us = -v;
  r.fault = static_cast<FaultCode>(255);
  r.flags = 255;
  for (int i = 0; i < kFingerCount; ++i) {
    r.finger_x_mm[i] = r.finger_y_mm[i] = r.finger_force_N[i] = v;
    r.finger_vent[i] = static_cast<FingerVent>(255);
  }
  return r;
}

}  // namespace

TEST(TelemetryHardening, RowsWithExtremeFloatsAreWholeRows) {
  const float max = std::numeric_limits<float>::max();
  struct Case {
    float value;
    const char* text;
  };
  for (const Case c : {Case{1e38f, "99999996802856924650656260769173209088.0000"},
                       Case{-max, "-340282346638528859811704183484516925440.0000"},
                       Case{std::numeric_limits<float>::infinity(), "inf"},
                       Case{std::numeric_limits<float>::quiet_NaN(), "nan"}, Case{-0.0f, "-0.0000"}}) {
    std::ostringstream out;
    write_telemetry_csv_row(out, extreme_record(c.value));
    const std::string row = out.str();
    ASSERT_EQ(row.back(), '\n');
    const auto v = cells(row.substr(0, row.size() - 1));
    ASSERT_EQ(v.size(), header_columns()) << row;
    EXPECT_EQ(v[0], "18446744073709551615");
    EXPECT_EQ(v[1].size(), 317u);  // -1.8e308 with 6 decimals: 309 digits, sign, point, 6
    EXPECT_EQ(v[5], c.text);       // stiffness_1
    EXPECT_EQ(v[19], "255");       // the fault
    EXPECT_EQ(v[20], "255");       // the flags, then the fingers' positions, forces and vents, the drag
    EXPECT_EQ(v[27], c.text);      // finger_force_N_1
    EXPECT_EQ(v[32], "255");       // finger_vent_3
    char drag[512];
    std::snprintf(drag, sizeof drag, "%.3f", double(c.value));
    EXPECT_EQ(v[33], drag);     // drag_x_mm_1, printed whole
    EXPECT_EQ(v.back(), drag);  // drag_y_mm_3
  }
}

TEST(TelemetryHardening, MutatedBinaryFilesConvertOrAreRefused) {
  TempDir dir;
  std::mt19937 rng(20261123);
  for (int file = 0; file < 50; ++file) {
    // A valid header, then records of random bytes: any float, any double, any fault code.
    std::string bytes = "PALPRIGT";
    const std::uint32_t header[2] = {kTelemetryFileVersion, static_cast<std::uint32_t>(sizeof(TelemetryRecord))};
    bytes.append(reinterpret_cast<const char*>(header), sizeof header);
    const std::size_t records = 1 + rng() % 20;
    for (std::size_t i = 0; i < records * sizeof(TelemetryRecord); ++i) bytes.push_back(static_cast<char>(rng()));
    const bool truncated = file % 5 == 0;
    if (truncated) bytes.resize(bytes.size() - 1 - rng() % 10);
    const auto bin = dir.write("m" + std::to_string(file) + ".bin", bytes);
    const auto csv = dir.path() / ("m" + std::to_string(file) + ".csv");
    if (truncated) {
      EXPECT_THROW(convert_telemetry_to_csv(bin, csv), InputError);
      continue;
    }
    ASSERT_EQ(convert_telemetry_to_csv(bin, csv), records);
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    std::size_t rows = 0;
    while (std::getline(in, line)) {
      ++rows;
      EXPECT_EQ(cells(line).size(), header_columns()) << line.substr(0, 200);
    }
    EXPECT_EQ(rows, records);
  }
}

TEST(TelemetryHardening, CommandLineConvertsAFileOfHugeFloats) {
  TempDir dir;
  std::string bytes = "PALPRIGT";
  const std::uint32_t header[2] = {kTelemetryFileVersion, static_cast<std::uint32_t>(sizeof(TelemetryRecord))};
  bytes.append(reinterpret_cast<const char*>(header), sizeof header);
  for (int i = 0; i < 3; ++i) {
    const TelemetryRecord r = extreme_record(3e38f);
    bytes.append(reinterpret_cast<const char*>(&r), sizeof r);
  }
  const auto bin = dir.write("huge.bin", bytes);
  const auto r = test_support::run_process(test_support::palprig_bin() + " telemetry to-csv " + bin.string() + " " +
                                           (dir.path() / "huge.csv").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "huge.csv"));
}

TEST(TelemetryHardening, WriterStopsAtItsByteBudget) {
  TempDir dir;
  TelemetryLimits limits;
  limits.max_bytes = std::uint64_t{64} * 1024;
  TelemetryWriter w(dir.path() / "t.bin", TelemetryFormat::binary, 1024, limits);
  TelemetryRecord r;
  for (int i = 0; i < 10000 && !w.failed(); ++i) w.push_wait(r);
  try {
    w.finish();
    FAIL() << "the writer went past its budget";
  } catch (const palprig::Error& e) {
    EXPECT_NE(std::string(e.what()).find("budget of 64 KiB per file is reached"), std::string::npos) << e.what();
  }
  EXPECT_LE(std::filesystem::file_size(dir.path() / "t.bin"), limits.max_bytes);
}

TEST(TelemetryHardening, WriterStopsBeforeTheDiskFills) {
  TempDir dir;
  TelemetryLimits limits;
  limits.min_free_bytes = std::uint64_t(1) << 62;  // more than any disk has free: it is "full"
  TelemetryWriter w(dir.path() / "t.csv", TelemetryFormat::csv, 1024, limits);
  TelemetryRecord r;
  w.push_wait(r);
  try {
    w.finish();
    FAIL() << "the writer ignored the free space";
  } catch (const palprig::Error& e) {
    EXPECT_NE(std::string(e.what()).find("are kept free"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::filesystem::file_size(dir.path() / "t.csv"), 0u);
}
