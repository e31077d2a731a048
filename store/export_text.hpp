#pragma once
// How every export writes a value: numbers with fixed decimals or "n/a", CSV and TSV fields,
// and the BIDS sidecar entry of a column. Shared by the trial, threshold and pulse exports.
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace palprig::export_text {

inline std::string number(const std::optional<double>& x, int decimals = 4) {
  if (!x || !std::isfinite(*x)) return "n/a";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, *x);
  return buf;
}

// A number with fixed decimals, or `not_available` when it is not finite (a table says "n/a"; a
// CSV for R or pandas says "NA").
inline std::string fixed(double x, int decimals, const char* not_available = "n/a") {
  if (!std::isfinite(x)) return not_available;
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

// A JSON number, or null when it is not finite (JSON has no NaN).
inline nlohmann::ordered_json number_or_null(double x) {
  if (std::isfinite(x)) return x;
  return nullptr;
}

inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

inline std::string tsv_field(const std::string& s) {
  std::string out;
  for (char c : s) out += (c == '\t' || c == '\n' || c == '\r') ? ' ' : c;
  return out.empty() ? "n/a" : out;
}

// The BIDS sidecar entry of one column.
inline nlohmann::ordered_json column(const std::string& description, const std::string& units = "",
                                     const nlohmann::ordered_json& levels = nullptr) {
  nlohmann::ordered_json c;
  c["Description"] = description;
  if (!levels.is_null()) c["Levels"] = levels;
  if (!units.empty()) c["Units"] = units;
  return c;
}

}  // namespace palprig::export_text
