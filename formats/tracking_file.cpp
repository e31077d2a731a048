#include "formats/tracking_file.hpp"

#include <cstdio>
#include <set>
#include <sstream>

#include "formats/json_file.hpp"
#include "io/checked_output.hpp"
#include "core/input_error.hpp"

namespace palprig {

const TrackedTool* TrackingConfig::tool_for_finger(int finger) const noexcept {
  for (const auto& t : tools)
    if (t.finger == finger) return &t;
  return nullptr;
}

const TrackedTool* TrackingConfig::tool_named(const std::string& name) const noexcept {
  for (const auto& t : tools)
    if (t.name == name) return &t;
  return nullptr;
}

namespace {

Vec3_mm vec3(const JsonObject& o, const std::string& key, double limit) {
  const std::vector<double> v = o.numbers(key, -limit, limit);
  if (v.size() != 3) o.fail(key, "3 numbers [x, y, z] in mm, got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

Rotation3 rotation(const JsonObject& o, const std::string& key) {
  const nlohmann::json& v = o.raw(key);
  const std::string expected = "a 3 x 3 rotation matrix [[r11, r12, r13], [r21, r22, r23], [r31, r32, r33]]";
  if (!v.is_array() || v.size() != 3) o.fail(key, expected + ", got " + json_excerpt(v));
  Rotation3 r{};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!v[i].is_array() || v[i].size() != 3) o.fail(key, expected + ", got " + json_excerpt(v));
    for (std::size_t j = 0; j < 3; ++j) {
      if (!v[i][j].is_number() || !std::isfinite(v[i][j].get<double>()))
        o.fail(key, expected + ", got " + json_excerpt(v));
      r[i][j] = v[i][j].get<double>();
    }
  }
  if (!is_rotation(r, 1e-3))
    o.fail(key, "a rotation (orthonormal rows, determinant +1, to 0.001), got " + json_excerpt(v) +
                    " (a scale or a mirror is not a rigid registration)");
  return r;
}

std::string tool_name(const JsonObject& o) {
  std::string name = o.string("name");  // not const: returned by move
  if (name.empty() || name.size() > kMaxToolNameChars)
    o.fail("name", "an OpenIGTLink device name of 1 to 20 characters, got '" + name + "' (" +
                       std::to_string(name.size()) + ")");
  for (unsigned char c : name)
    if (c < 0x21 || c > 0x7e) o.fail("name", "printable ASCII without spaces, got '" + name + "'");
  return name;
}

}  // namespace

TrackingConfig parse_tracking(const nlohmann::json& doc, const std::string& file) {
  TrackingConfig t;
  t.source = file;
  JsonObject root(doc, file, "");
  root.require_version(kTrackingFileVersion);
  t.placement = root.choice("placement", {"triangle", "per_finger"}) == "triangle" ? TrackedPlacement::triangle
                                                                                   : TrackedPlacement::per_finger;
  const auto tools = root.objects("tools");
  if (tools.empty() || tools.size() > kFingerCount)
    root.fail("tools", "1 to 3 tools, got " + std::to_string(tools.size()));
  if (t.placement == TrackedPlacement::triangle && tools.size() != 1)
    root.fail("tools", "one tool with placement \"triangle\" (the fingers stand around it), got " +
                           std::to_string(tools.size()));
  std::set<std::string> names;
  std::set<int> fingers;
  for (const JsonObject& o : tools) {
    TrackedTool tool;
    tool.name = tool_name(o);
    if (!names.insert(tool.name).second) o.fail("name", "a name no other tool has, got '" + tool.name + "' twice");
    if (t.placement == TrackedPlacement::per_finger) {
      tool.finger = static_cast<int>(o.integer("finger", 1, kFingerCount)) - 1;
      if (!fingers.insert(tool.finger).second)
        o.fail("finger", "a finger no other tool has, got " + std::to_string(tool.finger + 1) + " twice");
    } else {
      tool.finger = static_cast<int>(o.integer_or("finger", 1, 1, 1)) - 1;
    }
    if (o.has("tip")) {
      const JsonObject tip = o.object("tip");
      tool.tip.offset_mm = vec3(tip, "offset_mm", 1000);
      if (tip.has("method")) tool.tip.method = tip.choice("method", {"pivot", "digitized", "measured"});
      if (tip.has("rms_mm")) tool.tip.rms_mm = tip.number("rms_mm", 0, 1000);
      tip.refuse_unknown();
    }
    o.refuse_unknown();
    t.tools.push_back(tool);
  }
  if (root.has("tracker_to_scene")) {
    const JsonObject r = root.object("tracker_to_scene");
    t.registration.tracker_to_scene.rotation = rotation(r, "rotation");
    t.registration.tracker_to_scene.translation_mm = vec3(r, "translation_mm", 1e5);
    if (r.has("fre_mm")) t.registration.fre_mm = r.number("fre_mm", 0, 1000);
    t.registration.fiducials = static_cast<int>(r.integer_or("fiducials", 0, 0, 1000));
    r.refuse_unknown();
  }
  t.reader_fifo_priority = static_cast<int>(root.integer_or("reader_fifo_priority", t.reader_fifo_priority, 0, 98));
  root.refuse_unknown();
  return t;
}

TrackingConfig load_tracking_file(const std::filesystem::path& path) {
  return parse_tracking(read_json_file(path), path.string());
}

namespace {

// A number as the file shows it: 9 significant digits (a micrometre in a metre), no "-0".
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return std::string(b) == "-0" ? "0" : b;
}

std::string vec(const Vec3_mm& v) { return "[" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + "]"; }

std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }

}  // namespace

std::string tracking_text(const TrackingConfig& t) {
  // Written by hand rather than by json::dump, so that a person reads it as the docs show it:
  // the version first, one tool per line, the rotation row by row.
  std::ostringstream o;
  o << "{\n  \"version\": " << kTrackingFileVersion << ",\n  \"placement\": \""
    << (t.placement == TrackedPlacement::triangle ? "triangle" : "per_finger") << "\",\n  \"tools\": [\n";
  for (std::size_t i = 0; i < t.tools.size(); ++i) {
    const TrackedTool& tool = t.tools[i];
    o << "    {\"name\": " << quoted(tool.name);
    if (t.placement == TrackedPlacement::per_finger) o << ", \"finger\": " << tool.finger + 1;
    o << ", \"tip\": {\"offset_mm\": " << vec(tool.tip.offset_mm);
    if (!tool.tip.method.empty()) o << ", \"method\": " << quoted(tool.tip.method);
    if (std::isfinite(tool.tip.rms_mm)) o << ", \"rms_mm\": " << num(tool.tip.rms_mm);
    o << "}}" << (i + 1 < t.tools.size() ? "," : "") << "\n";
  }
  const RigidTransform& r = t.registration.tracker_to_scene;
  o << "  ],\n  \"tracker_to_scene\": {\n    \"rotation\": [" << vec(r.rotation[0]) << ", " << vec(r.rotation[1])
    << ", " << vec(r.rotation[2]) << "],\n    \"translation_mm\": " << vec(r.translation_mm);
  if (std::isfinite(t.registration.fre_mm)) o << ",\n    \"fre_mm\": " << num(t.registration.fre_mm);
  if (t.registration.fiducials > 0) o << ",\n    \"fiducials\": " << t.registration.fiducials;
  o << "\n  },\n  \"reader_fifo_priority\": " << t.reader_fifo_priority << "\n}\n";
  return o.str();
}

void write_tracking_file(const std::filesystem::path& path, const TrackingConfig& config) {
  CheckedOutputFile out(path);
  out.stream() << tracking_text(config);
  out.commit([](const std::filesystem::path& written) { (void)load_tracking_file(written); });
}

}  // namespace palprig
