#include "statistics/csv_table.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

}  // namespace

bool parse_finite_number(std::string_view text, double& out) noexcept {
  std::string_view s = trim(text);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars refuses a leading '+'
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size() && std::isfinite(out);
}

CsvTable CsvTable::read(const std::filesystem::path& file) {
  const std::string text = read_regular_file(file, kMaxTableFileBytes, "a CSV table");
  const char delimiter = file.extension() == ".tsv" ? '\t' : ',';
  return parse(text, file.string(), delimiter);
}

CsvTable CsvTable::parse(std::string_view text, std::string source_name, char delimiter) {
  CsvTable table;
  table.source_ = std::move(source_name);
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);

  std::size_t line = 1;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t record_line = line;
    std::vector<std::string> fields(1);
    bool quoted = false;
    bool any_char = false;
    for (; pos < text.size(); ++pos) {
      const char c = text[pos];
      if (quoted) {
        if (c == '"') {
          if (pos + 1 < text.size() && text[pos + 1] == '"') {
            fields.back() += '"';
            ++pos;
          } else {
            quoted = false;
          }
        } else {
          if (c == '\n') ++line;
          fields.back() += c;
        }
        continue;
      }
      if (c == '"') {
        quoted = true;
        any_char = true;
      } else if (c == delimiter) {
        fields.emplace_back();
        any_char = true;
      } else if (c == '\n') {
        ++pos;
        ++line;
        break;
      } else if (c != '\r') {
        fields.back() += c;
        any_char = true;
      }
    }
    if (quoted) throw InputError(table.source_, "line " + std::to_string(record_line), "a closing quote");
    if (!any_char) continue;  // blank line
    for (auto& f : fields) f = std::string(trim(f));
    if (table.header_.empty()) {
      table.header_ = std::move(fields);
      continue;
    }
    if (fields.size() != table.header_.size()) {
      throw InputError(
          table.source_, "line " + std::to_string(record_line),
          std::to_string(table.header_.size()) + " fields like the header, got " + std::to_string(fields.size()));
    }
    table.cells_.push_back(std::move(fields));
    table.lines_.push_back(record_line);
  }
  if (table.header_.empty()) throw InputError(table.source_, "line 1", "a header row naming the columns");
  return table;
}

std::size_t CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return i;
  }
  std::string names;
  for (const auto& h : header_) names += (names.empty() ? "" : ", ") + h;
  throw InputError(source_, "header", "a column named '" + std::string(name) + "' (columns: " + names + ")");
}

double CsvTable::number(std::size_t row, std::size_t column) const {
  const std::string& cell = text(row, column);
  double value = 0;
  if (!parse_finite_number(cell, value)) {
    const std::string where = "line " + std::to_string(lines_[row]) + ", column '" + header_[column] + "'";
    throw InputError(source_, where,
                     cell.empty() ? std::string("a number (the value is missing)") : "a number, got '" + cell + "'");
  }
  return value;
}

std::vector<double> CsvTable::numbers(std::string_view column_name) const {
  const std::size_t c = column(column_name);
  std::vector<double> out(rows());
  for (std::size_t r = 0; r < rows(); ++r) out[r] = number(r, c);
  return out;
}

const std::string& CsvTable::label(std::size_t row, std::size_t column) const {
  const std::string& cell = text(row, column);
  if (cell.empty()) {
    throw InputError(source_, "line " + std::to_string(lines_[row]) + ", column '" + header_[column] + "'",
                     "a group label (the value is missing)");
  }
  return cell;
}

}  // namespace palprig
