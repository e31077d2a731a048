#include "formats/json_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/regular_file.hpp"

namespace palprig {

namespace {

// nlohmann's DOM builder, plus what a user-facing file needs: the field path of every value
// (so an overflowing number names its field) and a nesting limit (so a file of 100,000 '['
// is refused here, before any recursive walk over the value - dump(), comparison, the
// validators - can overflow the stack). The parser itself is iterative.
class CheckedSax {
 public:
  using json = nlohmann::json;
  CheckedSax(json& root, std::string file) : dom_(root, true), file_(std::move(file)) {}

  bool null() { return value(), dom_.null(); }
  bool boolean(bool v) { return value(), dom_.boolean(v); }
  bool number_integer(json::number_integer_t v) { return value(), dom_.number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return value(), dom_.number_unsigned(v); }
  bool number_float(json::number_float_t v, const json::string_t& s) { return value(), dom_.number_float(v, s); }
  bool string(json::string_t& v) { return value(), dom_.string(v); }
  bool binary(json::binary_t& v) { return value(), dom_.binary(v); }
  bool start_object(std::size_t n) { return open(false), dom_.start_object(n); }
  bool key(json::string_t& k) {
    frames_.back().key = k;
    return dom_.key(k);
  }
  bool end_object() { return frames_.pop_back(), dom_.end_object(); }
  bool start_array(std::size_t n) { return open(true), dom_.start_array(n); }
  bool end_array() { return frames_.pop_back(), dom_.end_array(); }

  [[noreturn]] bool parse_error(std::size_t, const std::string& token, const nlohmann::detail::exception& ex) {
    if (ex.id == 406)  // a number beyond double's range (1e400): bad input in a known field
      throw InputError(file_, path_or("top level", true),
                       "a number within +-1.8e308, got " + printable_excerpt(token, 40));
    // e.what() reads "[json.exception.parse_error.101] parse error at line L, column C: ..."
    const std::string msg = ex.what();
    const auto pos = msg.find("at line");
    throw InputError(file_, pos == std::string::npos ? "syntax" : msg.substr(pos, msg.find(':', pos) - pos),
                     "valid JSON (" + msg.substr(msg.rfind(": ") + 2) + ")");
  }

 private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;  // next element's index (arrays)
    std::string key;        // last key seen (objects)
  };
  // A value arrives: in an array it is the next element.
  void value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  void open(bool array) {
    value();
    if (frames_.size() >= kMaxJsonDepth)
      throw InputError(file_, path_or("top level", false),
                       "objects and arrays nested at most " + std::to_string(kMaxJsonDepth) + " deep");
    frames_.push_back({array, 0, {}});
  }
  // The path of the value being read. A scalar still pending (being_read) has not been counted
  // in its array yet; an opened container has.
  std::string path_or(const char* fallback, bool being_read) const {
    std::string p;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      const bool pending = being_read && i + 1 == frames_.size();
      if (f.array)
        p += "[" + std::to_string(pending || f.index == 0 ? f.index : f.index - 1) + "]";
      else if (!f.key.empty() || !p.empty())
        p += (p.empty() ? "" : ".") + f.key;
      if (p.size() > kMaxWhereChars) break;  // InputError cuts it anyway
    }
    return p.empty() ? fallback : p;
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::string file_;
  std::vector<Frame> frames_;
};

}  // namespace

nlohmann::json read_json_file(const std::filesystem::path& path) {
  const std::string text = read_regular_file(path, kMaxJsonFileBytes, "a JSON document");
  nlohmann::json doc;
  CheckedSax sax(doc, path.string());
  nlohmann::json::sax_parse(text, &sax);
  return doc;
}

std::string json_excerpt(const nlohmann::json& v, std::size_t max_chars) {
  // Built piece by piece so a huge value costs max_chars, not its whole size.
  std::string out;
  auto add = [&](const std::string& s) {
    if (out.size() <= max_chars) out += s;
    return out.size() <= max_chars;
  };
  auto walk = [&](auto&& self, const nlohmann::json& x, std::size_t depth) -> bool {
    if (depth > kMaxJsonDepth) return add("...");
    if (x.is_object()) {
      if (!add("{")) return false;
      bool first = true;
      for (auto it = x.begin(); it != x.end(); ++it) {
        if (!add(std::string(first ? "" : ", ") + nlohmann::json(it.key()).dump() + ": ")) return false;
        if (!self(self, it.value(), depth + 1)) return false;
        first = false;
      }
      return add("}");
    }
    if (x.is_array()) {
      if (!add("[")) return false;
      for (std::size_t i = 0; i < x.size(); ++i) {
        if (i && !add(", ")) return false;
        if (!self(self, x[i], depth + 1)) return false;
      }
      return add("]");
    }
    // dump() escapes control characters in strings; a long string is cut below.
    return add(x.is_string() && x.get_ref<const std::string&>().size() > max_chars
                   ? nlohmann::json(x.get_ref<const std::string&>().substr(0, max_chars)).dump()
                   : x.dump());
  };
  walk(walk, v, 0);
  if (out.size() > max_chars) {
    out.resize(max_chars);
    out += "...";
  }
  return out;
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
  if (!v.is_number()) fail(key, range_text(lo, hi) + ", got " + json_excerpt(v));
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < lo || d > hi) fail(key, range_text(lo, hi) + ", got " + json_excerpt(v));
  return d;
}

double JsonObject::number_or(const std::string& key, double fallback, double lo, double hi) const {
  return has(key) ? number(key, lo, hi) : fallback;
}

std::int64_t JsonObject::integer(const std::string& key, std::int64_t lo, std::int64_t hi) const {
  const auto& v = get(key);
  if (!v.is_number_integer() || v.get<std::int64_t>() < lo || v.get<std::int64_t>() > hi)
    fail(key, "an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + json_excerpt(v));
  return v.get<std::int64_t>();
}

std::int64_t JsonObject::integer_or(const std::string& key, std::int64_t fallback, std::int64_t lo,
                                    std::int64_t hi) const {
  return has(key) ? integer(key, lo, hi) : fallback;
}

std::string JsonObject::string(const std::string& key) const {
  const auto& v = get(key);
  if (!v.is_string()) fail(key, "a string, got " + json_excerpt(v));
  return v.get<std::string>();
}

std::string JsonObject::string_or(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

std::string JsonObject::choice(const std::string& key, const std::vector<std::string>& allowed) const {
  std::string s = string(key);  // not const: returned by move
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
  if (!v.is_boolean()) fail(key, "true or false, got " + json_excerpt(v));
  return v.get<bool>();
}

JsonObject JsonObject::object(const std::string& key) const {
  const auto& v = get(key);
  if (!v.is_object()) fail(key, "an object, got " + json_excerpt(v));
  return JsonObject(v, file_, path(key));
}

std::vector<JsonObject> JsonObject::objects(const std::string& key) const {
  const auto& v = get(key);
  if (!v.is_array()) fail(key, "an array of objects, got " + json_excerpt(v));
  std::vector<JsonObject> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string p = path(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_object()) throw InputError(file_, p, "an object, got " + json_excerpt(v[i]));
    out.emplace_back(v[i], file_, p);
  }
  return out;
}

std::vector<double> JsonObject::numbers(const std::string& key, double lo, double hi) const {
  const auto& v = get(key);
  if (!v.is_array()) fail(key, "an array of numbers, got " + json_excerpt(v));
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string p = path(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_number() || v[i].get<double>() < lo || v[i].get<double>() > hi)
      throw InputError(file_, p, range_text(lo, hi) + ", got " + json_excerpt(v[i]));
    out.push_back(v[i].get<double>());
  }
  return out;
}

void JsonObject::require_version(int supported) const {
  const auto& v = get("version");
  if (!v.is_number_integer() || v.get<std::int64_t>() < 1)
    fail("version", "a positive integer file version, got " + json_excerpt(v));
  if (v.get<std::int64_t>() > supported)
    fail("version", "version " + std::to_string(supported) + " or older (this palprig is older than the file), got " +
                        json_excerpt(v));
}

void JsonObject::refuse_unknown() const {
  for (auto it = value_->begin(); it != value_->end(); ++it)
    if (!read_.count(it.key())) fail(it.key(), "no such field here (unknown field; check its spelling)");
}

}  // namespace palprig
