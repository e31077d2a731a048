#pragma once
// Strict reading of one number from a text file's cell (CSV maps, traces, waveform tables).
// std::stod takes more than a person writes in a table: hexadecimal floats ("0x1p-2"),
// "infinity", "nan". A cell here is an optional sign, decimal digits, an optional fraction and
// exponent, with spaces around it allowed, and nothing else; infinite and NaN values ("inf",
// "nan", 1e999) are told apart so the refusal can say "a finite ...".
#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>

namespace palprig {

enum class DecimalCell { number, not_a_number, not_finite };

// Reads the cell into `value` when it is one finite decimal number.
inline DecimalCell parse_decimal(std::string_view cell, double& value) {
  const auto first = cell.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return DecimalCell::not_a_number;
  cell = cell.substr(first, cell.find_last_not_of(" \t\r") - first + 1);
  if (cell.front() == '+') {  // from_chars refuses a leading '+'; one is fine, "+-1" is not
    cell.remove_prefix(1);
    if (cell.empty() || cell.front() == '+' || cell.front() == '-') return DecimalCell::not_a_number;
  }
  std::string_view word = cell.front() == '-' ? cell.substr(1) : cell;
  auto is_word = [&](std::string_view w) {
    if (word.size() != w.size()) return false;
    for (std::size_t i = 0; i < w.size(); ++i)
      if ((word[i] | 0x20) != w[i]) return false;
    return true;
  };
  if (is_word("inf") || is_word("infinity") || is_word("nan")) return DecimalCell::not_finite;
  // Only digits, signs, '.' and 'e' may appear: this refuses hex floats outright.
  for (char c : cell)
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '-' || c == '+'))
      return DecimalCell::not_a_number;
  double v = 0;
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v, std::chars_format::general);
  if (end != cell.data() + cell.size()) return DecimalCell::not_a_number;
  if (ec == std::errc::result_out_of_range) {
    // Overflow is not finite; an underflow (1e-400) is a number that rounds to 0.
    const auto e = cell.find_first_of("eE");
    if (e != std::string_view::npos && e + 1 < cell.size() && cell[e + 1] == '-') {
      value = 0;
      return DecimalCell::number;
    }
    return DecimalCell::not_finite;
  }
  if (ec != std::errc() || !std::isfinite(v)) return DecimalCell::not_finite;
  value = v;
  return DecimalCell::number;
}

}  // namespace palprig
