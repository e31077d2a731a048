#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <sstream>

#include "core/input_error.hpp"
#include "models/stiffness_map.hpp"

using namespace palprig;

namespace {
// 3 x 2 vertices over 20 x 10 mm: x = 0, 10, 20 mm; y = 0, 10 mm.
StiffnessMap small_map(OutsidePolicy outside = {}) {
  return StiffnessMap(3, 2, 20.0, 10.0, {0.0f, 0.5f, 1.0f, 0.2f, 0.4f, 0.6f}, outside);
}

std::string error_of(const std::string& text, double scale = 0.0) {
  std::istringstream in(text);
  try {
    parse_stiffness_csv(in, "map.csv", 20, 10, scale);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}
}  // namespace

TEST(StiffnessMap, NearestPicksTheClosestVertex) {
  const auto m = small_map();
  EXPECT_DOUBLE_EQ(m.sample_nearest(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(m.sample_nearest(4.9, 0), 0.0);
  EXPECT_DOUBLE_EQ(m.sample_nearest(5.1, 0), 0.5);
  EXPECT_FLOAT_EQ(m.sample_nearest(19, 9), 0.6f);
  EXPECT_FLOAT_EQ(m.sample_nearest(10, 6), 0.4f);
}

// The nearest vertex as std::lround picks it (half-way goes away from zero), the tick's rounding
// done without the library call: exact halves and random points over a large map agree.
TEST(StiffnessMap, NearestRoundsHalfWayUpAsLroundDoes) {
  const auto m = small_map();
  EXPECT_DOUBLE_EQ(m.sample_nearest(5.0, 0), 0.5);  // x exactly half-way between 0 and 10 mm
  EXPECT_DOUBLE_EQ(m.sample_nearest(15.0, 0), 1.0);
  EXPECT_FLOAT_EQ(m.sample_nearest(0, 5.0), 0.2f);  // y half-way between the rows
  const std::size_t cols = 257, rows = 129;
  std::vector<float> v(cols * rows);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = float(k % 1000) / 1000.0f;
  const StiffnessMap big(cols, rows, 400.0, 200.0, v);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0, 400), uy(0, 200);
  for (int k = 0; k < 100000; ++k) {
    const double x = ux(rng), y = uy(rng);
    const auto c = static_cast<std::size_t>(std::lround(x / 400.0 * double(cols - 1)));
    const auto r = static_cast<std::size_t>(std::lround(y / 200.0 * double(rows - 1)));
    ASSERT_EQ(big.sample_nearest(x, y), big.at(c, r)) << x << " " << y;
  }
}

// A map of 2 MiB or more lies on 2 MiB boundaries and asks the kernel for huge pages (the
// tick's samples of a pen jumping over a 4096 x 4096 map then miss the TLB far less); a small one
// is an ordinary allocation. Where the kernel gives huge pages on advice only, the map's memory
// is eligible for them (smaps' THPeligible), which memory that did not ask is not.
TEST(StiffnessMap, LargeMapsLieOnHugePageBoundaries) {
  const std::size_t side = 1024;  // 4 MiB of floats
  const StiffnessMap big(side, side, 100.0, 100.0, std::vector<float>(side * side, 0.25f));
  const auto address = reinterpret_cast<std::uintptr_t>(big.values().data());
  EXPECT_EQ(address % kHugePageBytes, 0u);
  EXPECT_FLOAT_EQ(big.at(side - 1, side - 1), 0.25f);
  StiffnessMap copy = big;  // copies allocate the same way
  copy.set_outside({OutsidePolicy::Kind::background, 0.5});
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(copy.values().data()) % kHugePageBytes, 0u);
  EXPECT_EQ(copy.values(), big.values());
  EXPECT_FLOAT_EQ(small_map().at(2, 1), 0.6f);

  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string policy((std::istreambuf_iterator<char>(thp)), std::istreambuf_iterator<char>());
  // Only where the kernel's policy is "madvise" does the map's eligibility show the advice (under
  // "always" every large mapping is eligible, under "never" none), and only if this process has
  // not had huge pages switched off (prctl PR_SET_THP_DISABLE, which some containers set).
  if (policy.find("[madvise]") == std::string::npos) return;
  std::ifstream status("/proc/self/status");
  for (std::string field; std::getline(status, field);)
    if (field.rfind("THP_enabled:", 0) == 0 && field.find('0') != std::string::npos) return;
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool in_map = false;
  int eligible = -1;  // the map's THPeligible, -1 where the kernel does not say
  while (std::getline(smaps, line)) {
    unsigned long lo = 0, hi = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2) {  // a mapping's first line
      in_map = address >= lo && address < hi;
      continue;
    }
    if (in_map && line.rfind("THPeligible:", 0) == 0) eligible = std::stoi(line.substr(12));
  }
  if (eligible >= 0) {
    EXPECT_EQ(eligible, 1) << "the map's memory is not eligible for huge pages (" << policy << ")";
  }
}

TEST(StiffnessMap, BilinearInterpolatesBetweenVertices) {
  const auto m = small_map();
  EXPECT_DOUBLE_EQ(m.sample_bilinear(0, 0), 0.0);
  EXPECT_NEAR(m.sample_bilinear(5, 0), 0.25, 1e-7);
  EXPECT_NEAR(m.sample_bilinear(0, 5), 0.1, 1e-7);
  // Centre of the left cell: mean of 0, 0.5, 0.2, 0.4.
  EXPECT_NEAR(m.sample_bilinear(5, 5), 0.275, 1e-7);
  EXPECT_NEAR(m.sample_bilinear(20, 10), 0.6, 1e-7);  // far corner, last cell
}

TEST(StiffnessMap, ClampPolicyUsesTheNearestEdge) {
  const auto m = small_map();
  EXPECT_NEAR(m.sample_bilinear(-50, 0), 0.0, 1e-7);
  EXPECT_NEAR(m.sample_bilinear(500, 0), 1.0, 1e-7);
  EXPECT_NEAR(m.sample_nearest(500, 500), 0.6, 1e-7);
}

TEST(StiffnessMap, BackgroundPolicyOutsideTheMap) {
  const auto m = small_map({OutsidePolicy::Kind::background, 0.3});
  EXPECT_DOUBLE_EQ(m.sample_bilinear(-0.01, 5), 0.3);
  EXPECT_DOUBLE_EQ(m.sample_nearest(20.01, 5), 0.3);
  EXPECT_DOUBLE_EQ(m.sample_nearest(10, 10.5), 0.3);
  EXPECT_FLOAT_EQ(m.sample_nearest(20, 10), 0.6f);  // the edge itself is inside
  EXPECT_DOUBLE_EQ(m.sample_nearest(NAN, 5), 0.3);
}

TEST(StiffnessMap, CsvRoundTrip) {
  std::istringstream in("# comment\n0,0.5,1\n0.2, 0.4 ,0.6\n");
  const auto m = parse_stiffness_csv(in, "map.csv", 20, 10);
  ASSERT_EQ(m.cols(), 3u);
  ASSERT_EQ(m.rows(), 2u);
  EXPECT_FLOAT_EQ(m.at(1, 1), 0.4f);
  std::stringstream out;
  write_stiffness_csv(out, m);
  const auto back = parse_stiffness_csv(out, "again.csv", 20, 10);
  EXPECT_EQ(back.values(), m.values());
}

TEST(StiffnessMap, CsvWithScaleNormalises) {
  std::istringstream in("0,32767.5\n65535,0\n");
  const auto m = parse_stiffness_csv(in, "raw.csv", 1, 1, 65535);
  EXPECT_NEAR(m.at(1, 0), 0.5, 1e-6);
  EXPECT_NEAR(m.at(0, 1), 1.0, 1e-6);
}

TEST(StiffnessMap, MalformedCsvIsRefusedWithLineAndReason) {
  EXPECT_EQ(error_of("0,0.5,1\n0.2,0.4\n"), "map.csv: line 2: 3 values like the first row, got 2");
  EXPECT_EQ(error_of("0,0.5\n0.2,abc\n"), "map.csv: line 2, column 2: a number, got 'abc'");
  EXPECT_EQ(error_of("0,0.5\n0.2,nan\n"), "map.csv: line 2, column 2: a finite stiffness, got 'nan'");
  EXPECT_EQ(error_of("0,1.5\n0.2,0.1\n"),
            "map.csv: line 1, column 2: a stiffness in 0..1 (or give a value scale), got '1.5'");
  EXPECT_EQ(error_of("0,-0.1\n0.2,0.1\n"),
            "map.csv: line 1, column 2: a stiffness in 0..1 (or give a value scale), got '-0.1'");
  EXPECT_EQ(error_of("0,0.5\n"), "map.csv: line 1: a grid of at least 2x2 values, got 2x1");
  EXPECT_EQ(error_of(""), "map.csv: line 0: a grid of at least 2x2 values, got 0x0");
  EXPECT_EQ(error_of("0,0.5,\n0,0,\n"), "map.csv: line 1: no trailing comma (empty last value)");
  EXPECT_EQ(error_of("0,,0.5\n0,0,0\n"), "map.csv: line 1, column 2: a number, got ''");
  EXPECT_NE(error_of("0,70000\n0,0\n", 65535).find("line 1, column 2: a value in 0..65535"), std::string::npos);
}

TEST(StiffnessMap, BadPhysicalSizeIsRefused) {
  std::istringstream in("0,1\n1,0\n");
  try {
    parse_stiffness_csv(in, "m.csv", 0, 10);
    FAIL() << "accepted a zero width";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "width_mm");
  }
}

TEST(StiffnessMap, Pgm16RoundTripKeepsValues) {
  const auto m = small_map();
  std::stringstream buf;
  write_stiffness_pgm16(buf, m);
  const auto back = parse_stiffness_pgm(buf, "m.pgm", 20, 10);
  ASSERT_EQ(back.cols(), 3u);
  ASSERT_EQ(back.rows(), 2u);
  for (std::size_t i = 0; i < m.values().size(); ++i) EXPECT_NEAR(back.values()[i], m.values()[i], 1.0 / 65535);
}

TEST(StiffnessMap, AsciiPgmWithCommentsLoads) {
  std::istringstream in("P2\n# made by hand\n2 2\n# maxval next\n100\n0 50\n100 25\n");
  const auto m = parse_stiffness_pgm(in, "m.pgm", 10, 10);
  EXPECT_NEAR(m.at(1, 0), 0.5, 1e-6);
  EXPECT_NEAR(m.at(1, 1), 0.25, 1e-6);
}

TEST(StiffnessMap, MalformedPgmIsRefused) {
  auto err = [](const std::string& bytes) {
    std::istringstream in(bytes);
    try {
      parse_stiffness_pgm(in, "m.pgm", 10, 10);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(err("P6\n2 2\n255\n"), "m.pgm: header magic: 'P5' (binary) or 'P2' (ASCII) PGM, got 'P6'");
  EXPECT_EQ(err("P5\n2 x\n255\n"), "m.pgm: header height: an integer in 2..16384, got 'x'");
  EXPECT_EQ(err("P5\n2 2\n70000\n"), "m.pgm: header maxval: an integer in 1..65535, got '70000'");
  EXPECT_EQ(err(std::string("P5\n2 2\n65535\n") + std::string(5, '\0')),
            "m.pgm: pixel data: 8 bytes for 2x2 pixels, the file has 5");
  EXPECT_EQ(err("P2\n2 2\n10\n1 2 11 3\n"), "m.pgm: pixel 2: an integer in 0..10, got '11'");
  EXPECT_EQ(err("P2\n2 2\n10\n1 2 3\n"), "m.pgm: pixel data: 7 or more bytes for 2x2 pixels, the file has 6");
  EXPECT_EQ(err("P2\n2 2\n10\n1 2 3    \n"), "m.pgm: pixel 3: an integer in 0..10, got ''");
}
