#include "calibration/sweep_csv.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/checked_output.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {

// The sweep file is streamed, hold by hold, so that a stopped sweep keeps every finished hold;
// each flush and the close are checked, and a failure is io/checked_output's one line. A
// file that failed cannot be left looking like a whole sweep: without holds it is removed; with
// some it is renamed NAME.partial (a rename needs no room on the disk), which the line names.
// Only a regular file is removed or renamed: never a device (/dev/full) or a FIFO given as --out.
[[noreturn]] void fail_writing(std::ofstream& out, const std::filesystem::path& path, bool has_holds) {
  const int error = errno;
  out.close();
  std::string reason = error != 0 ? std::strerror(error) : "the write failed";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(path, ec))) {
    // Nothing to tidy.
  } else if (!has_holds) {
    std::filesystem::remove(path, ec);
  } else {
    std::filesystem::path partial = path;
    partial += ".partial";
    std::filesystem::rename(path, partial, ec);
    if (!ec) reason += " (the holds recorded before it are in " + partial.string() + ")";
  }
  throw OutputError(path, reason);
}

}  // namespace

SweepCsvWriter::SweepCsvWriter(const std::filesystem::path& path, const SweepFileInfo& info,
                               const std::array<bool, kFingerCount>& channels)
    : path_(path), out_(path), channels_(channels), has_sensor_(!info.sensor_name.empty()) {
  if (!out_) {
    const int error = errno;
    throw OutputError(path, error != 0 ? std::strerror(error) : "the file cannot be created");
  }
  out_ << "# palprig calibration sweep\n";
  out_ << "# rig_id: " << info.rig_id << "\n";
  out_ << "# backend: " << info.backend << "\n";
  out_ << "# date: " << info.date << "\n";
  out_ << "# p_max_kPa: " << info.p_max_kPa << "\n";
  out_ << "# rate_hz: " << info.rate_hz << "\n";
  out_ << "# sensor: " << (has_sensor_ ? info.sensor_name : "none") << "\n";
  for (const auto& n : info.notes) out_ << "# note: " << n << "\n";
  out_ << "t_s,channel,hold,segment,repeat,branch,command_kPa,monitor_kPa,sensor,settled\n";
  if (!out_.flush()) fail_writing(out_, path_, false);
}

void SweepCsvWriter::on_hold(std::size_t index, const SweepHold& hold, std::span<const SweepSample> samples,
                             const HoldOutcome&) {
  char line[256];
  for (const SweepSample& s : samples) {
    for (std::size_t c = 0; c < kFingerCount; ++c) {
      if (!channels_[c]) continue;
      char sensor[40] = "";
      if (has_sensor_ && std::isfinite(s.sensor[c])) std::snprintf(sensor, sizeof sensor, "%.6g", s.sensor[c]);
      // A monitor without a reading is an empty cell, never "nan", which no reader takes; such a
      // sample is never marked settled (the runner redoes a hold an outage spoils).
      char monitor[40] = "";
      const bool has_monitor = std::isfinite(s.monitor_kPa[c]);
      if (has_monitor) std::snprintf(monitor, sizeof monitor, "%.4f", s.monitor_kPa[c]);
      std::snprintf(line, sizeof line, "%.4f,%zu,%zu,%s,%d,%s,%.4f,%s,%s,%d\n", s.t_s, c + 1, index,
                    to_string(hold.segment), hold.repeat, to_string(hold.branch), s.command_kPa, monitor, sensor,
                    s.settled && has_monitor ? 1 : 0);
      out_ << line;
      ++rows_;
    }
  }
  // A crash or Ctrl-C keeps every finished hold.
  if (!out_.flush()) fail_writing(out_, path_, index > 0);
}

void SweepCsvWriter::finish(const SweepOutcome& o) {
  out_ << "# holds: " << o.holds_done << " of " << o.holds_planned << " (" << o.holds_unsettled << " not settled)\n";
  if (o.holds_redone) out_ << "# redone: " << o.holds_redone << " hold(s) started again after a link outage\n";
  if (o.stopped)
    out_ << "# stopped: "
         << (o.stop_signal ? "signal " + std::to_string(o.stop_signal) : std::string("by the operator"))
         << "; channels vented; the rows above were kept\n";
  if (o.faulted) out_ << "# fault: " << o.fault << "; channels vented\n";
  if (!out_.flush()) fail_writing(out_, path_, rows_ > 0);
  out_.close();
  if (!out_) fail_writing(out_, path_, rows_ > 0);
}

std::vector<DynamicsSample> SweepData::channel_dynamics(int channel) const {
  std::vector<DynamicsSample> out;
  for (const auto& d : dynamics)
    if (d.channel == channel) out.push_back(d);
  return out;
}

std::vector<HoldPoint> SweepData::channel_points(int channel) const {
  std::vector<HoldPoint> out;
  for (const auto& p : points)
    if (p.channel == channel) out.push_back(p);
  return out;
}

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

struct Accumulator {
  HoldPoint point;
  double monitor_sum = 0, sensor_sum = 0;
  std::size_t monitor_n = 0, sensor_n = 0, settled = 0;
};

}  // namespace

SweepData read_sweep_csv(const std::filesystem::path& path) {
  SweepData data;
  data.file = path.string();
  const std::string& file = data.file;
  std::ifstream in = open_regular_file(path, kMaxTableFileBytes, "a sweep CSV", std::ios::in);

  std::string text;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  std::map<std::string, std::size_t> col;
  std::map<std::pair<int, long>, std::size_t> hold_index;  // (channel, hold) -> accumulator
  std::vector<Accumulator> holds;
  std::set<int> channels;
  std::array<double, kFingerCount> last_dynamics_t;
  last_dynamics_t.fill(-std::numeric_limits<double>::infinity());

  auto where = [&] { return "line " + std::to_string(line_no); };
  while (std::getline(in, text)) {
    ++line_no;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.find_first_not_of(" \t") == std::string::npos) continue;
    if (text[0] == '#') {
      const auto colon = text.find(':');
      if (colon == std::string::npos) continue;
      const auto key_b = text.find_first_not_of("# ");
      const std::string key = text.substr(key_b, colon - key_b);
      std::string value = text.substr(colon + 1);
      value.erase(0, value.find_first_not_of(' '));
      if (key == "rig_id")
        data.info.rig_id = value;
      else if (key == "backend")
        data.info.backend = value;
      else if (key == "date")
        data.info.date = value;
      else if (key == "sensor")
        data.info.sensor_name = value == "none" ? "" : value;
      else if (key == "p_max_kPa")
        data.info.p_max_kPa = std::strtod(value.c_str(), nullptr);
      else if (key == "rate_hz")
        data.info.rate_hz = std::strtod(value.c_str(), nullptr);
      else if (key == "note")
        data.info.notes.push_back(value);
      continue;
    }
    if (header.empty()) {
      header = split_csv(text);
      for (std::size_t i = 0; i < header.size(); ++i) {
        static const std::set<std::string> known{"t_s",    "channel",     "hold",        "segment", "repeat",
                                                 "branch", "command_kPa", "monitor_kPa", "sensor",  "settled"};
        if (!known.count(header[i]))
          throw InputError(file, where(),
                           "known columns (t_s, channel, hold, segment, repeat, branch, command_kPa, "
                           "monitor_kPa, sensor, settled), got \"" +
                               header[i] + "\"");
        if (col.count(header[i])) throw InputError(file, where(), "each column once (\"" + header[i] + "\" repeats)");
        col[header[i]] = i;
      }
      for (const char* required : {"channel", "command_kPa"})
        if (!col.count(required)) throw InputError(file, where(), std::string("a \"") + required + "\" column");
      if (!col.count("monitor_kPa") && !col.count("sensor"))
        throw InputError(file, where(), "a monitor_kPa or a sensor column (the response to fit)");
      continue;
    }
    const auto cells = split_csv(text);
    if (cells.size() != header.size())
      throw InputError(file, where(),
                       std::to_string(header.size()) + " cells like the header, got " + std::to_string(cells.size()));
    ++data.rows;
    auto cell = [&](const char* name) -> const std::string* {
      const auto it = col.find(name);
      return it == col.end() ? nullptr : &cells[it->second];
    };
    auto number = [&](const char* name, bool allow_empty) {
      const std::string* c = cell(name);
      if (!c || c->empty()) {
        if (allow_empty) return std::numeric_limits<double>::quiet_NaN();
        throw InputError(file, where(), std::string("a value in column ") + name);
      }
      double v = 0;
      const auto [end, ec] = std::from_chars(c->data(), c->data() + c->size(), v);
      if (ec != std::errc() || end != c->data() + c->size() || !std::isfinite(v))
        throw InputError(file, where(), std::string("a finite number in column ") + name + ", got \"" + *c + "\"");
      return v;
    };
    auto integer = [&](const char* name, long fallback, long lo, long hi) {
      const std::string* c = cell(name);
      if (!c || c->empty()) return fallback;
      long v = 0;
      const auto [end, ec] = std::from_chars(c->data(), c->data() + c->size(), v);
      if (ec != std::errc() || end != c->data() + c->size() || v < lo || v > hi)
        throw InputError(file, where(),
                         std::string("an integer ") + std::to_string(lo) + ".." + std::to_string(hi) + " in column " +
                             name + ", got \"" + *c + "\"");
      return v;
    };

    HoldPoint p;
    p.channel = static_cast<int>(integer("channel", 0, 1, kFingerCount));
    if (p.channel == 0) throw InputError(file, where(), "a channel number 1.." + std::to_string(kFingerCount));
    p.command_kPa = number("command_kPa", false);
    p.repeat = static_cast<int>(integer("repeat", 0, 0, 1000000));
    p.line = line_no;
    if (const std::string* b = cell("branch"); b && !b->empty() && !parse_branch(*b, p.branch))
      throw InputError(file, where(), "branch inflation, deflation or none, got \"" + *b + "\"");
    if (const std::string* s = cell("segment"); s && !s->empty() && !parse_segment(*s, p.segment))
      throw InputError(file, where(), "segment vent, staircase, random, sine, step or chirp, got \"" + *s + "\"");
    const long settled = integer("settled", 1, 0, 1);
    const double monitor = number("monitor_kPa", true), sensor = number("sensor", true);
    // Without a hold column every row is a point of its own.
    p.hold = col.count("hold") ? integer("hold", 0, 0, 1L << 40) : long(data.rows);
    if (col.count("hold") && cell("hold")->empty()) throw InputError(file, where(), "a value in column hold");
    channels.insert(p.channel);
    if (is_dynamics_segment(p.segment)) {
      // A step or chirp row: one sample of the dynamics fit, with its time.
      DynamicsSample d;
      d.channel = p.channel;
      d.hold = p.hold;
      d.segment = p.segment;
      d.t_s = number("t_s", false);
      d.command_kPa = p.command_kPa;
      d.monitor_kPa = monitor;
      d.line = line_no;
      double& last_t = last_dynamics_t[std::size_t(d.channel - 1)];
      if (d.t_s < last_t)
        throw InputError(file, where(), "times that do not go back within a channel's step and chirp rows");
      last_t = d.t_s;
      if (std::isfinite(monitor)) data.has_monitor = true;
      data.dynamics.push_back(d);
      continue;
    }

    const auto key = std::make_pair(p.channel, p.hold);
    auto it = hold_index.find(key);
    if (it == hold_index.end()) {
      it = hold_index.emplace(key, holds.size()).first;
      holds.push_back(Accumulator{p});
    }
    Accumulator& a = holds[it->second];
    if (a.point.command_kPa != p.command_kPa || a.point.branch != p.branch || a.point.segment != p.segment)
      throw InputError(file, where(),
                       "one command, segment and branch per hold (hold " + std::to_string(p.hold) + " of channel " +
                           std::to_string(p.channel) + " changes here)");
    if (!settled) continue;
    ++a.settled;
    if (std::isfinite(monitor)) {
      a.monitor_sum += monitor;
      ++a.monitor_n;
      data.has_monitor = true;
    }
    if (std::isfinite(sensor)) {
      a.sensor_sum += sensor;
      ++a.sensor_n;
      data.has_sensor = true;
    }
  }
  if (header.empty()) throw InputError(file, "header", "a header line (t_s,channel,hold,...)");
  if (data.rows == 0) throw InputError(file, "rows", "at least one data row");
  for (Accumulator& a : holds) {
    if (a.settled == 0) {
      ++data.unsettled_holds;
      continue;
    }
    a.point.samples = a.settled;
    if (a.monitor_n) a.point.monitor_kPa = a.monitor_sum / double(a.monitor_n);
    if (a.sensor_n) a.point.sensor = a.sensor_sum / double(a.sensor_n);
    data.points.push_back(a.point);
  }
  data.channels.assign(channels.begin(), channels.end());
  // Sensor readings under a "# sensor: none" line, or with no such line: the sensor is named
  // after its column, so reports and chart titles and axes never show an empty name.
  if (data.has_sensor && data.info.sensor_name.empty()) data.info.sensor_name = "sensor";
  return data;
}

}  // namespace palprig
