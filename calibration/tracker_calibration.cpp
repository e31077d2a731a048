#include "calibration/tracker_calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "models/decimal_number.hpp"
#include "core/input_error.hpp"
#include "models/pose_hold.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {

std::string number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

std::string seconds_text(double s) { return number_text(s) + " s"; }

std::string mm3(const Vec3_mm& p) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(1);
  o << "(" << p[0] << ", " << p[1] << ", " << p[2] << ") mm";
  return o.str();
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Names of the devices seen so far, for a refusal that says what the tracker did send.
struct SeenNames {
  std::vector<std::string> names;
  void add(const char* n) {
    for (const auto& s : names)
      if (s == n) return;
    if (names.size() < 8) names.emplace_back(n);
  }
  std::string text() const {
    if (names.empty()) return "no poses at all";
    std::string t;
    for (const auto& n : names) t += (t.empty() ? "" : ", ") + n;
    return "poses of " + t;
  }
};

// Polls the tracker once (at most 20 ms); throws when the connection ends.
void poll_or_throw(IgtlPoseReader& tracker, std::vector<DecodedPose>& poses) {
  poses.clear();
  const IgtlPoseReader::Status s = tracker.poll(poses, 20);
  if (s != IgtlPoseReader::Status::ok) throw Error(std::string("tracker: ") + tracker.why());
}

double angle_deg(const Rotation3& a, const Rotation3& b) {
  double trace = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) trace += a[r][c] * b[r][c];
  return std::acos(std::clamp((trace - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

std::vector<Fiducial> load_fiducials(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in = open_regular_file(path, kMaxTableFileBytes, "a fiducials CSV", std::ios::in);
  std::string line;
  std::size_t line_no = 0;
  int columns = 0;
  std::vector<Fiducial> out;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::string where = "line " + std::to_string(line_no);
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      std::erase(cell, ' ');
      cells.push_back(cell);
    }
    if (columns == 0) {
      if (cells == std::vector<std::string>{"name", "x_mm", "y_mm", "z_mm"})
        columns = 4;
      else if (cells ==
               std::vector<std::string>{"name", "x_mm", "y_mm", "z_mm", "tracker_x_mm", "tracker_y_mm", "tracker_z_mm"})
        columns = 7;
      else
        throw InputError(
            file, where,
            "the header name,x_mm,y_mm,z_mm (and optionally ,tracker_x_mm,tracker_y_mm,tracker_z_mm), got '" + line +
                "'");
      continue;
    }
    if (static_cast<int>(cells.size()) != columns)
      throw InputError(file, where, std::to_string(columns) + " values, got " + std::to_string(cells.size()));
    Fiducial f;
    f.name = cells[0];
    if (f.name.empty()) throw InputError(file, where + ", name", "a fiducial name");
    double v[6] = {};
    static const char* names[6] = {"x_mm", "y_mm", "z_mm", "tracker_x_mm", "tracker_y_mm", "tracker_z_mm"};
    for (int i = 0; i + 1 < columns; ++i)
      if (parse_decimal(cells[i + 1], v[i]) != DecimalCell::number)
        throw InputError(file, where + ", " + names[i], "a finite number, got '" + cells[i + 1] + "'");
    f.scene_mm = {v[0], v[1], v[2]};
    if (columns == 7) f.touched_mm = Vec3_mm{v[3], v[4], v[5]};
    for (const auto& g : out)
      if (g.name == f.name)
        throw InputError(file, where + ", name", "a name no other fiducial has, got '" + f.name + "' twice");
    out.push_back(f);
  }
  if (columns == 0) throw InputError(file, "line 1", "the header name,x_mm,y_mm,z_mm");
  if (out.size() < 3)
    throw InputError(file, "line " + std::to_string(line_no),
                     "at least 3 fiducials, got " + std::to_string(out.size()));
  return out;
}

std::vector<Vec3_mm> touch_fiducials(IgtlPoseReader& tracker, const TrackedTool& tool,
                                     const std::vector<Fiducial>& fiducials, const TouchRules& rules, const Say& say) {
  std::vector<Vec3_mm> touched;
  std::vector<DecodedPose> poses;
  poses.reserve(64);
  SeenNames seen;
  std::optional<Vec3_mm> last;
  for (std::size_t k = 0; k < fiducials.size(); ++k) {
    const Fiducial& f = fiducials[k];
    say("touch fiducial " + f.name + " " + mm3(f.scene_mm) + " on the scene with " + tool.name +
        "'s tip and hold still for " + seconds_text(rules.hold_s));
    PointHold hold(rules.radius_mm, rules.hold_s);
    bool left = !last.has_value();
    const auto t0 = std::chrono::steady_clock::now();
    HoldTime hold_time;  // the tracker's stamps while they behave like a clock (models/pose_hold.hpp)
    auto seen_tool_at = t0;
    bool done = false;
    while (!done) {
      poll_or_throw(tracker, poses);
      for (const DecodedPose& p : poses) {
        seen.add(p.device);
        if (tool.name != p.device || !p.is_rotation) continue;
        seen_tool_at = std::chrono::steady_clock::now();
        const Vec3_mm tip = p.pose.apply(tool.tip.offset_mm);
        if (!left) {
          // The previous touch must be left first, so one rest is not taken twice.
          left = distance_mm(tip, *last) > rules.leave_mm;
          continue;
        }
        if (hold.add(hold_time.at(p.stamp_s, seconds_since(t0)), tip)) {
          done = true;
          break;
        }
      }
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - seen_tool_at).count() > rules.timeout_s)
        throw Error("tool " + tool.name + " not seen for " + std::to_string(int(rules.timeout_s)) +
                    " s (the tracker sent " + seen.text() + ")");
      if (!done && seconds_since(t0) > rules.timeout_s)
        throw Error("fiducial " + f.name + ": no rest of " + tool.name + "'s tip within " +
                    std::to_string(int(rules.timeout_s)) + " s");
    }
    last = hold.mean();
    touched.push_back(*last);
    say("  " + f.name + " taken at " + mm3(*last) + " (tracker), mean of " + std::to_string(hold.samples()) + " poses");
  }
  return touched;
}

PointRegistration register_fiducials(const std::vector<Fiducial>& fiducials, const std::vector<Vec3_mm>& touched,
                                     const std::string& fiducials_file) {
  std::vector<Vec3_mm> scene;
  scene.reserve(fiducials.size());
  for (const auto& f : fiducials) scene.push_back(f.scene_mm);
  try {
    return register_points(touched, scene);
  } catch (const BadInput& e) {
    throw InputError(fiducials_file, "fiducials", e.what());
  }
}

PivotCalibration pivot_from_tracker(IgtlPoseReader& tracker, const std::string& tool, double seconds, double timeout_s,
                                    const Say& say, double min_step_deg) {
  say("pivot " + tool + " about its tip in a divot (a cone of 20-40 degrees) for " + seconds_text(seconds));
  std::vector<RigidTransform> kept;
  std::vector<DecodedPose> poses;
  SeenNames seen;
  const auto t0 = std::chrono::steady_clock::now();
  std::optional<std::chrono::steady_clock::time_point> first;
  while (true) {
    poll_or_throw(tracker, poses);
    for (const DecodedPose& p : poses) {
      seen.add(p.device);
      if (tool != p.device || !p.is_rotation || !p.has_rotation) continue;
      if (!first) first = std::chrono::steady_clock::now();
      if (kept.empty() || angle_deg(kept.back().rotation, p.pose.rotation) >= min_step_deg) kept.push_back(p.pose);
    }
    if (first && std::chrono::duration<double>(std::chrono::steady_clock::now() - *first).count() >= seconds) break;
    if (!first && seconds_since(t0) > timeout_s)
      throw Error("tool " + tool + " not seen within " + std::to_string(int(timeout_s)) + " s (the tracker sent " +
                  seen.text() + ")");
  }
  say("  " + std::to_string(kept.size()) + " poses at least " + number_text(min_step_deg) + " degrees apart");
  try {
    return pivot_calibrate(kept);
  } catch (const BadInput& e) {
    throw Error(std::string("pivot calibration of ") + tool + ": " + e.what());
  }
}

Vec3_mm digitize_from_tracker(IgtlPoseReader& tracker, const std::string& finger_tool,
                              const std::string& digitizer_tool, const Vec3_mm& digitizer_tip_mm,
                              const TouchRules& rules, const Say& say) {
  say("touch " + finger_tool + "'s fingertip with " + digitizer_tool + "'s tip and hold both still for " +
      seconds_text(rules.hold_s));
  std::vector<DecodedPose> poses;
  SeenNames seen;
  std::optional<RigidTransform> finger, digitizer;
  PointHold hold(rules.radius_mm, rules.hold_s);
  const auto t0 = std::chrono::steady_clock::now();
  while (true) {
    poll_or_throw(tracker, poses);
    bool fresh = false;
    for (const DecodedPose& p : poses) {
      seen.add(p.device);
      if (!p.is_rotation) continue;
      if (finger_tool == p.device && p.has_rotation) finger = p.pose, fresh = true;
      if (digitizer_tool == p.device) digitizer = p.pose, fresh = true;
    }
    if (fresh && finger && digitizer) {
      // Paper 003 eq. 2: the digitized point in the finger sensor's frame; held still in that
      // frame (the hand may move as long as the two move together).
      const Vec3_mm local = digitize_tip(*finger, digitizer->apply(digitizer_tip_mm));
      if (hold.add(seconds_since(t0), local)) {
        say("  taken: " + mm3(hold.mean()) + " in " + finger_tool + "'s frame, mean of " +
            std::to_string(hold.samples()) + " pose pairs");
        return hold.mean();
      }
    }
    if (seconds_since(t0) > rules.timeout_s) {
      std::string why = "no rest of ";
      why.append(digitizer_tool).append(" on ").append(finger_tool).append(" within ");
      why.append(std::to_string(int(rules.timeout_s))).append(" s (the tracker sent ").append(seen.text()).append(")");
      throw Error(why);
    }
  }
}

}  // namespace palprig
