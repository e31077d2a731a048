#pragma once
// CsvTable: a CSV file with a header row, for the statistics commands. Values stay text until
// a command asks for a column as numbers; then a missing or non-numeric value in a row that is
// used is refused with its line number (InputError), never skipped or read as 0.
//
// Format: RFC 4180 (comma separated, fields may be double-quoted with "" for a quote), CRLF or
// LF line ends, a UTF-8 byte-order mark is ignored, blank lines are skipped. Files ending in
// .tsv are tab separated.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace palprig {

class CsvTable {
 public:
  // Throws InputError when the file cannot be read, has no header, or a row has a different
  // number of fields than the header.
  static CsvTable read(const std::filesystem::path& file);
  static CsvTable parse(std::string_view text, std::string source_name, char delimiter = ',');

  const std::string& source() const noexcept { return source_; }
  const std::vector<std::string>& header() const noexcept { return header_; }
  std::size_t rows() const noexcept { return cells_.size(); }
  std::size_t line_of_row(std::size_t row) const { return lines_.at(row); }

  // Index of a column; throws InputError naming the columns that exist.
  std::size_t column(std::string_view name) const;

  const std::string& text(std::size_t row, std::size_t column) const { return cells_.at(row).at(column); }
  // The value as a finite number; throws InputError("line N, column 'C'", "a number, got ...").
  double number(std::size_t row, std::size_t column) const;
  // Every row of a column as numbers.
  std::vector<double> numbers(std::string_view column_name) const;
  // A non-empty label (group column); throws InputError on an empty cell.
  const std::string& label(std::size_t row, std::size_t column) const;

 private:
  std::string source_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> cells_;
  std::vector<std::size_t> lines_;  // 1-based line of each data row in the file
};

// Parse a whole string as a finite double (leading/trailing spaces allowed). False otherwise.
bool parse_finite_number(std::string_view text, double& out) noexcept;

}  // namespace palprig
