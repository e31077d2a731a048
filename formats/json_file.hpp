#pragma once
// Validated reading of palprig's JSON files (rig, scene, calibration, protocol). nlohmann-json
// parses; this adds what it lacks for user-facing files: every error names the file, the field
// path and what was expected (InputError), and fields nobody reads are refused, so a typo such
// as "p_max_kpa" is caught instead of silently ignored.
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"

namespace palprig {

// Objects and arrays nested deeper than this are refused while parsing (no palprig file
// needs more than 6 levels; the bound keeps every recursive walk over a value far from the
// stack's end).
inline constexpr std::size_t kMaxJsonDepth = 64;

// Parse a whole file; syntax errors report the line and column, a number beyond double's range
// (1e400) and too deep a nesting report the field path.
nlohmann::json read_json_file(const std::filesystem::path& path);

// A value as JSON text for a refusal: at most max_chars characters (then "..."), control
// characters escaped; costs max_chars however large the value is.
std::string json_excerpt(const nlohmann::json& value, std::size_t max_chars = 80);

class JsonObject {
 public:
  // `where` is the field path of this object within the file ("" for the root).
  JsonObject(const nlohmann::json& value, std::string file, std::string where);

  bool has(const std::string& key) const;
  double number(const std::string& key, double lo, double hi) const;
  double number_or(const std::string& key, double fallback, double lo, double hi) const;
  std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi) const;
  std::int64_t integer_or(const std::string& key, std::int64_t fallback, std::int64_t lo, std::int64_t hi) const;
  std::string string(const std::string& key) const;
  std::string string_or(const std::string& key, const std::string& fallback) const;
  // One of the listed words.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string choice_or(const std::string& key, const std::string& fallback,
                        const std::vector<std::string>& allowed) const;
  bool boolean_or(const std::string& key, bool fallback) const;
  JsonObject object(const std::string& key) const;
  std::vector<JsonObject> objects(const std::string& key) const;  // array of objects
  std::vector<double> numbers(const std::string& key, double lo, double hi) const;
  const nlohmann::json& raw(const std::string& key) const;

  // The file's "version" must be present and no newer than supported.
  void require_version(int supported) const;
  // Refuse any field that was not read (call after reading everything).
  void refuse_unknown() const;

  std::string path(const std::string& key) const { return where_.empty() ? key : where_ + "." + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;
  const std::string& file() const { return file_; }

 private:
  const nlohmann::json& get(const std::string& key) const;
  const nlohmann::json* value_;
  std::string file_, where_;
  mutable std::set<std::string> read_;
};

}  // namespace palprig
