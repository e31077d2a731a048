#include "inputs/pose_recording.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "models/decimal_number.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {
constexpr const char* kHeader = "t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw";
}

std::vector<RecordedPose> load_pose_recording(const std::filesystem::path& path, const PoseRecordingLimits& limits) {
  const std::string file = path.string();
  std::ifstream in = open_regular_file(path, kMaxTraceFileBytes, "a tracker pose recording CSV", std::ios::in);
  std::string line;
  std::size_t line_no = 0;
  bool header = false;
  std::vector<RecordedPose> out;
  std::map<std::string, double> last_t;
  double first_t = 0;
  static const char* names[9] = {"t_s", "tool", "x_mm", "y_mm", "z_mm", "qx", "qy", "qz", "qw"};
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::string where = "line " + std::to_string(line_no);
    if (!header) {
      std::string h = line;
      std::erase(h, ' ');
      if (h != kHeader) throw InputError(file, where, std::string("the header '") + kHeader + "', got '" + line + "'");
      header = true;
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (cells.size() != 9)
      throw InputError(file, where, "9 values (" + std::string(kHeader) + "), got " + std::to_string(cells.size()));
    double v[9] = {};
    for (int i = 0; i < 9; ++i) {
      if (i == 1) continue;
      if (parse_decimal(cells[i], v[i]) != DecimalCell::number)
        throw InputError(file, where + ", " + names[i], "a finite number, got '" + cells[i] + "'");
    }
    RecordedPose p;
    p.tool = cells[1];
    if (p.tool.empty() || p.tool.size() > 20)
      throw InputError(file, where + ", tool",
                       "an OpenIGTLink device name of 1 to 20 characters, got '" + p.tool + "'");
    for (unsigned char c : p.tool)
      if (c < 0x21 || c > 0x7e)
        throw InputError(file, where + ", tool", "printable ASCII without spaces, got '" + p.tool + "'");
    if (out.empty()) first_t = v[0];
    p.t_s = v[0] - first_t;
    if (!out.empty() && p.t_s < out.back().t_s)
      throw InputError(file, where + ", t_s", "a time no earlier than the previous row's, got " + cells[0]);
    if (auto it = last_t.find(p.tool); it != last_t.end() && !(p.t_s > it->second))
      throw InputError(file, where + ", t_s", "a time after tool " + p.tool + "'s previous row, got " + cells[0]);
    if (p.t_s > limits.max_length_s)
      throw InputError(file, where + ", t_s", "a recording at most " + std::to_string(limits.max_length_s) + " s long");
    last_t[p.tool] = p.t_s;
    if (!rotation_from_quaternion(v[5], v[6], v[7], v[8], p.pose.rotation))
      throw InputError(file, where + ", qx..qw", "a non-zero quaternion (x, y, z, w)");
    p.pose.translation_mm = {v[2], v[3], v[4]};
    out.push_back(std::move(p));
  }
  if (!header) throw InputError(file, "line 1", std::string("the header '") + kHeader + "'");
  if (out.empty()) throw InputError(file, "line " + std::to_string(line_no), "at least one pose");
  return out;
}

std::vector<std::string> recorded_tools(const std::vector<RecordedPose>& poses) {
  std::vector<std::string> names;
  for (const auto& p : poses) {
    bool known = false;
    for (const auto& n : names) known = known || n == p.tool;
    if (!known) names.push_back(p.tool);
  }
  return names;
}

}  // namespace palprig
