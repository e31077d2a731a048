#include "inputs/input_source.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "models/decimal_number.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

TraceInput::TraceInput(std::vector<TouchSample> samples, std::string name, double contact_force_N)
    : samples_(std::move(samples)), name_(std::move(name)) {
  for (auto& s : samples_) s.in_contact = s.force_N >= contact_force_N;
}

TouchSample TraceInput::latest(double t_s) noexcept {
  TouchSample out;
  out.t_s = t_s;
  if (samples_.empty() || t_s < samples_.front().t_s) return out;  // not yet touching
  if (t_s >= samples_.back().t_s) {
    out = samples_.back();
    out.t_s = t_s;
    out.force_N = 0;  // the trace is over: the pen lifts
    out.in_contact = false;
    return out;
  }
  if (cursor_ >= samples_.size() - 1 || samples_[cursor_].t_s > t_s) cursor_ = 0;
  while (cursor_ + 1 < samples_.size() - 1 && samples_[cursor_ + 1].t_s <= t_s) ++cursor_;
  const TouchSample& a = samples_[cursor_];
  const TouchSample& b = samples_[cursor_ + 1];
  const double f = (t_s - a.t_s) / (b.t_s - a.t_s);
  out.x_mm = a.x_mm + f * (b.x_mm - a.x_mm);
  out.y_mm = a.y_mm + f * (b.y_mm - a.y_mm);
  out.force_N = a.force_N + f * (b.force_N - a.force_N);
  // Contact follows the nearer recorded row, so a lift-off in the trace is a lift-off here.
  out.in_contact = (f < 0.5 ? a : b).in_contact;
  return out;
}

TraceLimits TraceLimits::unbounded() {
  const double inf = std::numeric_limits<double>::infinity();
  return {inf, inf};
}

namespace {
std::string seconds_text(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}
}  // namespace

std::vector<TouchSample> load_trace_csv(const std::filesystem::path& path, double contact_force_N,
                                        const TraceLimits& limits) {
  const std::string file = path.string();
  std::ifstream in = open_regular_file(path, kMaxTraceFileBytes, "a pen trace CSV", std::ios::in);
  std::string line;
  std::size_t line_no = 0;
  std::vector<TouchSample> out;
  bool header = false;
  double first_t_s = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("t_s,x_mm,y_mm,force_N", 0) != 0)
        throw InputError(file, "line " + std::to_string(line_no),
                         "the header 't_s,x_mm,y_mm,force_N', got '" + line + "'");
      header = true;
      continue;
    }
    std::stringstream ss(line);
    std::string cell;
    double v[4];
    int n = 0;
    static const char* names[4] = {"t_s", "x_mm", "y_mm", "force_N"};
    while (std::getline(ss, cell, ',')) {
      if (n >= 4)
        throw InputError(file, "line " + std::to_string(line_no), "4 values (t_s,x_mm,y_mm,force_N), got more");
      if (parse_decimal(cell, v[n]) != DecimalCell::number)
        throw InputError(file, "line " + std::to_string(line_no) + ", " + names[n],
                         "a finite number, got '" + cell + "'");
      ++n;
    }
    if (n != 4)
      throw InputError(file, "line " + std::to_string(line_no),
                       "4 values (t_s,x_mm,y_mm,force_N), got " + std::to_string(n));
    if (v[3] < 0)
      throw InputError(file, "line " + std::to_string(line_no) + ", force_N",
                       "a force >= 0 N, got " + std::to_string(v[3]));
    if (out.empty()) first_t_s = v[0];
    const double t_s = v[0] - first_t_s;  // relative to the first row
    const std::string where_t = "line " + std::to_string(line_no) + ", t_s";
    if (!out.empty() && !(t_s > out.back().t_s))
      throw InputError(file, where_t,
                       "a time after the previous row's " + std::to_string(out.back().t_s + first_t_s) + " s");
    if (!out.empty() && t_s - out.back().t_s > limits.max_gap_s)
      throw TraceBoundError(file, where_t,
                            "rows at most " + seconds_text(limits.max_gap_s) +
                                " apart (the stale-input limit), got a gap of " + seconds_text(t_s - out.back().t_s));
    if (t_s > limits.max_length_s)
      throw TraceBoundError(file, where_t,
                            "a trace at most " + seconds_text(limits.max_length_s) +
                                " long (times count from the first row, " + seconds_text(first_t_s) + "), got " +
                                seconds_text(t_s));
    out.push_back({t_s, v[1], v[2], v[3], v[3] >= contact_force_N});
  }
  if (!header) throw InputError(file, "line 1", "the header 't_s,x_mm,y_mm,force_N'");
  if (out.size() < 2) throw InputError(file, "line " + std::to_string(line_no), "at least 2 samples");
  return out;
}

void write_trace_csv(const std::filesystem::path& path, const std::vector<TouchSample>& samples) {
  std::ofstream out(path);
  out << "t_s,x_mm,y_mm,force_N\n";
  out.precision(9);
  for (const auto& s : samples) out << s.t_s << ',' << s.x_mm << ',' << s.y_mm << ',' << s.force_N << '\n';
}

RasterInput::RasterInput(const SceneBounds& b, const RasterPlan& plan) : area_(b), plan_(plan) {
  area_.x0_mm += plan.margin_mm;
  area_.y0_mm += plan.margin_mm;
  area_.x1_mm -= plan.margin_mm;
  area_.y1_mm -= plan.margin_mm;
  if (area_.x1_mm <= area_.x0_mm || area_.y1_mm < area_.y0_mm) area_ = b;
  row_length_mm_ = area_.x1_mm - area_.x0_mm;
  rows_ = 1 + static_cast<int>(std::floor((area_.y1_mm - area_.y0_mm) / plan.row_step_mm));
  // Each row, then a step down to the next one.
  duration_s_ = (rows_ * row_length_mm_ + (rows_ - 1) * plan.row_step_mm) / plan.speed_mm_per_s;
}

TouchSample RasterInput::latest(double t_s) noexcept {
  TouchSample s;
  s.t_s = t_s;
  if (t_s < 0 || t_s > duration_s_) return s;
  double d = t_s * plan_.speed_mm_per_s;
  const double leg = row_length_mm_ + plan_.row_step_mm;
  const int row = std::min(static_cast<int>(d / leg), rows_ - 1);
  d -= row * leg;
  const bool forward = row % 2 == 0;
  const double along = std::min(d, row_length_mm_);
  const double down = std::max(0.0, d - row_length_mm_);
  s.x_mm = forward ? area_.x0_mm + along : area_.x1_mm - along;
  s.y_mm = area_.y0_mm + row * plan_.row_step_mm + down;
  s.force_N = plan_.force_N;
  s.in_contact = true;
  return s;
}

}  // namespace palprig
