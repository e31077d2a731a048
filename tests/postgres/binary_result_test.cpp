// Binary-format results (PgConnection::exec_binary, used by the `stats trials` scans) read back
// the same integers and doubles as the text form, bit for bit, from a real server.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "store/pg_connection.hpp"
#include "store/pg_target.hpp"
#include "tests/postgres/pg_test_support.hpp"

namespace palprig {
namespace {

TEST(PostgresBinaryResult, IntegersAndDoublesReadTheSameAsTheirText) {
  PALPRIG_REQUIRE_PG_SERVER();
  PgConnection db(parse_pg_target(testing::pg_uri("postgres")));
  const std::string sql =
      "SELECT v.i2, v.i4, v.i8, v.f8, v.f4, v.t FROM (VALUES "
      "(-2::int2, -70000::int4, -9007199254740993::int8, 0.1::float8, 0.1::float4, 'cond A'::text), "
      "(32767::int2, 2147483647::int4, 9223372036854775807::int8, 4.6e-310::float8, -1.5::float4, ''::text), "
      "(0::int2, 0::int4, 0::int8, 'Infinity'::float8, 'NaN'::float4, 'ü'::text), "
      "(1::int2, 1::int4, 1::int8, -0.0::float8, 3.4e38::float4, 'x'::text)) AS v(i2, i4, i8, f8, f4, t)";
  const PgResult text = db.exec(sql);
  const PgResult binary = db.exec_binary(sql);
  ASSERT_EQ(binary.rows(), 4);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(binary.integer(r, c), text.integer(r, c)) << "row " << r << " column " << c;
    for (int c = 3; c < 5; ++c) {
      const double b = binary.real(r, c), t = text.real(r, c);
      if (std::isnan(t)) {
        EXPECT_TRUE(std::isnan(b)) << "row " << r;
      } else if (c == 4) {  // float4: the text is the float's shortest form, read here as a double
        EXPECT_EQ(static_cast<float>(b), static_cast<float>(t)) << "row " << r;
      } else {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(b), std::bit_cast<std::uint64_t>(t)) << "row " << r << " column " << c;
      }
    }
    EXPECT_EQ(binary.text(r, 5), text.text(r, 5));
  }
  EXPECT_EQ(binary.integer(0, 2), -9007199254740993);
  // A text column read as a number is refused, not misread.
  EXPECT_THROW(binary.integer(0, 5), PgError);
  EXPECT_THROW(binary.real(0, 0), PgError);
}

}  // namespace
}  // namespace palprig
