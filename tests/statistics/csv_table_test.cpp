// CSV input of the statistics commands: quoting, line numbers in refusals, grouping.
#include <gtest/gtest.h>

#include <functional>

#include "statistics/csv_groups.hpp"
#include "statistics/csv_table.hpp"
#include "core/input_error.hpp"

namespace palprig {
namespace {

std::string where_refused(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.where() + " | " + e.expected();
  }
  return "";
}

TEST(experiments_csv, quoted_fields_crlf_bom_and_blank_lines) {
  const CsvTable t =
      CsvTable::parse("\xEF\xBB\xBFname,\"rt, s\"\r\n\"O'Neil, \"\"A\"\"\", 4.5 \r\n\r\nB,+3e0\n", "x.csv");
  ASSERT_EQ(t.header(), (std::vector<std::string>{"name", "rt, s"}));
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.text(0, 0), "O'Neil, \"A\"");
  EXPECT_EQ(t.numbers("rt, s"), (std::vector<double>{4.5, 3.0}));
  EXPECT_EQ(t.line_of_row(1), 4u);  // the blank line 3 is skipped but counted
}

TEST(experiments_csv, refusals_name_the_line_and_column) {
  const CsvTable t = CsvTable::parse("g,v\na,1\na,NaN\nb,\nb,2x\n", "d.csv");
  EXPECT_EQ(where_refused([&] { t.numbers("v"); }), "line 3, column 'v' | a number, got 'NaN'");
  EXPECT_EQ(where_refused([&] { t.number(2, 1); }), "line 4, column 'v' | a number (the value is missing)");
  EXPECT_EQ(where_refused([&] { t.number(3, 1); }), "line 5, column 'v' | a number, got '2x'");
  EXPECT_NE(where_refused([&] { t.column("w"); }).find("columns: g, v"), std::string::npos);
  EXPECT_EQ(where_refused([] { CsvTable::parse("a,b\n1\n", "s.csv"); }), "line 2 | 2 fields like the header, got 1");
  EXPECT_EQ(where_refused([] { CsvTable::parse("a\n\"open\n", "q.csv"); }), "line 2 | a closing quote");
  EXPECT_EQ(where_refused([] { CsvTable::parse("", "e.csv"); }), "line 1 | a header row naming the columns");
}

TEST(experiments_csv, groups_in_order_of_appearance_and_only_used_rows_checked) {
  const CsvTable t = CsvTable::parse("g,v\nb,1\na,2\nc,oops\nb,3\n", "g.csv");
  // Group c's bad value is not read when only a and b are compared.
  const auto ab = two_groups(t, "v", "g", {"a", "b"});
  EXPECT_EQ(ab[0].label, "a");
  EXPECT_EQ(ab[1].values, (std::vector<double>{1, 3}));
  EXPECT_NE(where_refused([&] { group_numbers(t, "v", "g"); }).find("line 4"), std::string::npos);
  EXPECT_NE(where_refused([&] { two_groups(t, "v", "g", {"a", "z"}); }).find("group 'z'"), std::string::npos);
  const CsvTable missing = CsvTable::parse("g,v\n,1\n", "m.csv");
  EXPECT_EQ(where_refused([&] { group_numbers(missing, "v", "g"); }),
            "line 2, column 'g' | a group label (the value is missing)");
}

}  // namespace
}  // namespace palprig
