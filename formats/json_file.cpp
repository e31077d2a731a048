#include "formats/json_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace palprig {

nlohmann::json read_json_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "file", "a readable JSON file (cannot open it)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line L, column C: ..."
    std::string msg = e.what();
    const auto pos = msg.find("at line");
    throw InputError(path.string(), pos == std::string::npos ? "syntax" : msg.substr(pos, msg.find(':', pos) - pos),
                     "valid JSON (" + msg.substr(msg.rfind(": ") + 2) + ")");
  }
}

JsonObject::JsonObject(const nlohmann::json& value, std::string file, std::string where)
    : value_(&value), file_(std::move(file)), where_(std::move(where)) {
  if (!value.is_object()) throw InputError(file_, where_.empty() ? "top level" : where_, "a JSON object");
}

void JsonObject::fail(const std::string& key, const std::string& expected) const {
  throw InputError(file_, path(key), expected);
}

bool JsonObject::has(const std::string& key) const {
  read_.insert(key);
  return value_->contains(key);
}

const nlohmann::json& JsonObject::get(const std::string& key) const {
  read_.insert(key);
  auto it = value_->find(key);
  if (it == value_->end()) fail(key, "a value (field is missing)");
  return *it;
}

const nlohmann::json& JsonObject::raw(const std::string& key) const { return get(key); }

static std::string range_text(double lo, double hi) {
  std::ostringstream s;
  s << "a number in " << lo << ".." << hi;
  return s.str();
}

double JsonObject::number(const std::string& key, double lo, double hi) const {
  const auto& v = get(key);
  if (!v.is_number()) fail(key, range_text(lo, hi) + ", got " + v.dump());
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < lo || d > hi) fail(key, range_text(lo, hi) + ", got " + v.dump());
  return d;
}

double JsonObject::number_or(const std::string& key, double fallback, double lo, double hi) const {
  return has(key) ? number(key, lo, hi) : fallback;
}

std::int64_t JsonObject::integer(const std::string& key, std::int64_t lo, std::int64_t hi) const {
  const auto& v = get(key);
  if (!v.is_number_integer() || v.get<std::int64_t>() < lo || v.get<std::int64_t>() > hi)
    fail(key, "an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + v.dump());
  return v.get<std::int64_t>();
}

std::int64_t JsonObject::integer_or(const std::string& key, std::int64_t fallback, std::int64_t lo,
                                    std::int64_t hi) const {
  return has(key) ? integer(key, lo, hi) : fallback;
}

std::string JsonObject::string(const std::string& key) const {
  const auto& v = get(key);
  if (!v.is_string()) fail(key, "a string, got " + v.dump());
  return v.get<std::string>();
}

std::string JsonObject::string_or(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

std::string JsonObject::choice(const std::string& key, const std::vector<std::string>& allowed) const {
  const std::string s = string(key);
  for (const auto& a : allowed)
    if (a == s) return s;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
  fail(key, "one of " + list + ", got \"" + s + "\"");
}

std::string JsonObject::choice_or(const std::string& key, const std::string& fallback,
                                  const std::vector<std::string>& allowed) const {
  return has(key) ? choice(key, allowed) : fallback;
}

bool JsonObject::boolean_or(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const auto& v = get(key);
  if (!v.is_boolean()) fail(key, "true or false, got " + v.dump());
  return v.get<bool>();
}

JsonObject JsonObject::object(const std::string& key) const {
  const auto& v = get(key);
  if (!v.is_object()) fail(key, "an object, got " + v.dump());
  return JsonObject(v, file_, path(key));
}

std::vector<JsonObject> JsonObject::objects(const std::string& key) const {
  const auto& v = get(key);
  if (!v.is_array()) fail(key, "an array of objects, got " + v.dump());
  std::vector<JsonObject> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string p = path(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_object()) throw InputError(file_, p, "an object, got " + v[i].dump());
    out.emplace_back(v[i], file_, p);
  }
  return out;
}

std::vector<double> JsonObject::numbers(const std::string& key, double lo, double hi) const {
  const auto& v = get(key);
  if (!v.is_array()) fail(key, "an array of numbers, got " + v.dump());
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string p = path(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_number() || v[i].get<double>() < lo || v[i].get<double>() > hi)
      throw InputError(file_, p, range_text(lo, hi) + ", got " + v[i].dump());
    out.push_back(v[i].get<double>());
  }
  return out;
}

void JsonObject::require_version(int supported) const {
  const auto& v = get("version");
  if (!v.is_number_integer() || v.get<std::int64_t>() < 1)
    fail("version", "a positive integer file version, got " + v.dump());
  if (v.get<std::int64_t>() > supported)
    fail("version", "version " + std::to_string(supported) + " or older (this palprig is older than the file), got " +
                        v.dump());
}

void JsonObject::refuse_unknown() const {
  for (auto it = value_->begin(); it != value_->end(); ++it)
    if (!read_.count(it.key())) fail(it.key(), "no such field here (unknown field; check its spelling)");
}

}  // namespace palprig
