// Stiffness maps from outside: a PGM header may not make palprig allocate what the file does not
// hold, map dimensions are bounded, and CSV cells are plain decimals (no hex floats); refusals
// quote at most a few hundred characters of the offending line, with control characters escaped.
#include <gtest/gtest.h>

#include <sstream>

#include "models/decimal_number.hpp"
#include "core/input_error.hpp"
#include "models/stiffness_map.hpp"

using namespace palprig;

namespace {

std::string pgm_refusal(const std::string& bytes) {
  std::istringstream in(bytes);
  try {
    parse_stiffness_pgm(in, "m.pgm", 100, 100);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

std::string csv_refusal(const std::string& text) {
  std::istringstream in(text);
  try {
    parse_stiffness_csv(in, "m.csv", 100, 100);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(MapHardening, PgmHeaderPromisingMoreThanTheFileHoldsIsRefusedBeforeAllocating) {
  // 21 bytes asking for 20000x20000 16-bit pixels (800 MB of pixels, 1.6 GB of floats): refused
  // from the header and the file's size. Before the fix it allocated first.
  EXPECT_EQ(pgm_refusal("P5\n4000 4000\n65535\n\x01\x02"),
            "m.pgm: pixel data: 32000000 bytes for 4000x4000 pixels, the file has 2");
  EXPECT_EQ(pgm_refusal("P2\n3 3\n255\n1 2 3\n"), "m.pgm: pixel data: 17 or more bytes for 3x3 pixels, the file has 6");
}

TEST(MapHardening, MapDimensionsAreBounded) {
  EXPECT_EQ(pgm_refusal("P5\n20000 20000\n65535\n"), "m.pgm: header width: an integer in 2..16384, got '20000'");
  EXPECT_EQ(pgm_refusal("P5\n16384 16384\n255\n"),
            "m.pgm: header width x height: at most 16777216 pixels (a map of 4096x4096), got 16384x16384");
  EXPECT_EQ(pgm_refusal("P5\n65536 65536\n65535\n"), "m.pgm: header width: an integer in 2..16384, got '65536'");
}

TEST(MapHardening, ASmallValidPgmStillLoads) {
  std::istringstream in(std::string("P5\n2 2\n255\n\x00\xff\x80\x40", 15));
  const auto m = parse_stiffness_pgm(in, "m.pgm", 10, 10);
  EXPECT_EQ(m.cols(), 2u);
  EXPECT_NEAR(m.at(1, 0), 1.0, 1e-6);
}

TEST(MapHardening, CsvRefusesHexFloats) {
  EXPECT_EQ(csv_refusal("0,0x1p-2\n0,0\n"), "m.csv: line 1, column 2: a number, got '0x1p-2'");
  EXPECT_EQ(csv_refusal("0,0X.8P0\n0,0\n"), "m.csv: line 1, column 2: a number, got '0X.8P0'");
  EXPECT_EQ(csv_refusal("0,1e999\n0,0\n"), "m.csv: line 1, column 2: a finite stiffness, got '1e999'");
  EXPECT_EQ(csv_refusal("0,-INF\n0,0\n"), "m.csv: line 1, column 2: a finite stiffness, got '-INF'");
  EXPECT_EQ(csv_refusal("+0.5, 0.25 \n0,1e-1\n"), "accepted");
}

TEST(MapHardening, RefusalsQuoteAFewHundredEscapedCharacters) {
  const std::string why = csv_refusal("0,\x1b[31m" + std::string(2'000'000, '7') + "\n0,0\n");
  EXPECT_LT(why.size(), 400u);
  EXPECT_EQ(why.rfind("m.csv: line 1, column 2: a number, got '\\x1b[31m777", 0), 0u) << why.substr(0, 100);
  EXPECT_EQ(why.find('\x1b'), std::string::npos);
}

TEST(DecimalNumber, AcceptsPlainDecimalsOnly) {
  double v = 0;
  EXPECT_EQ(parse_decimal(" -1.5e3 ", v), DecimalCell::number);
  EXPECT_EQ(v, -1500);
  EXPECT_EQ(parse_decimal("1e-400", v), DecimalCell::number);
  EXPECT_EQ(v, 0);
  for (const char* bad : {"", " ", "0x10", "1,5", "1.5.5", "++1", "+-1", "e5", "1e", "--1", "1_000", "0b1"})
    EXPECT_EQ(parse_decimal(bad, v), DecimalCell::not_a_number) << bad;
  for (const char* inf : {"inf", "-Infinity", "NaN", "1e309", "-1e999"})
    EXPECT_EQ(parse_decimal(inf, v), DecimalCell::not_finite) << inf;
}
