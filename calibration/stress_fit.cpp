#include "calibration/stress_fit.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "models/finger_layout.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> out;
  std::string c;
  std::istringstream in(line);
  while (std::getline(in, c, ',')) {
    const auto b = c.find_first_not_of(" \t\r"), e = c.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : c.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

double parse_number(const std::string& c, const std::string& file, const std::string& where, const char* column) {
  double v = 0;
  const auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), v);
  if (c.empty() || ec != std::errc() || end != c.data() + c.size() || !std::isfinite(v))
    throw InputError(file, where, std::string("a finite number in column ") + column + ", got \"" + c + "\"");
  return v;
}

}  // namespace

std::vector<StressPair> read_stress_pairs_csv(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in = open_regular_file(path, kMaxTableFileBytes, "a stress pairs CSV", std::ios::in);
  std::string line;
  std::size_t line_no = 0;
  int col_p = -1, col_s = -1, col_c = -1;
  std::size_t columns = 0;
  std::vector<StressPair> pairs;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const auto cells = cells_of(line);
    const std::string where = "line " + std::to_string(line_no);
    if (columns == 0) {
      columns = cells.size();
      for (std::size_t i = 0; i < cells.size(); ++i) {
        if (cells[i] == "pressure_kPa")
          col_p = int(i);
        else if (cells[i] == "stress_kPa")
          col_s = int(i);
        else if (cells[i] == "channel")
          col_c = int(i);
        else
          throw InputError(file, where,
                           "columns pressure_kPa, stress_kPa and optionally channel, got \"" + cells[i] + "\"");
      }
      if (col_p < 0 || col_s < 0) throw InputError(file, where, "a header with pressure_kPa and stress_kPa");
      continue;
    }
    if (cells.size() != columns)
      throw InputError(file, where,
                       std::to_string(columns) + " cells like the header, got " + std::to_string(cells.size()));
    StressPair p;
    p.pressure_kPa = parse_number(cells[std::size_t(col_p)], file, where, "pressure_kPa");
    p.stress_kPa = parse_number(cells[std::size_t(col_s)], file, where, "stress_kPa");
    if (col_c >= 0 && !cells[std::size_t(col_c)].empty()) {
      const double c = parse_number(cells[std::size_t(col_c)], file, where, "channel");
      if (c != std::floor(c) || c < 1 || c > double(kFingerCount))
        throw InputError(file, where, "a channel 1.." + std::to_string(kFingerCount) + " (or empty for all)");
      p.channel = int(c);
    }
    pairs.push_back(p);
  }
  if (columns == 0) throw InputError(file, "header", "a header line pressure_kPa,stress_kPa[,channel]");
  return pairs;
}

ActuatorFit fit_actuator_stress(const std::vector<StressPair>& pairs, int channel, const std::string& file) {
  std::vector<double> p, s;
  for (const auto& q : pairs)
    if (q.channel == 0 || q.channel == channel) {
      p.push_back(q.pressure_kPa);
      s.push_back(q.stress_kPa);
    }
  const std::string what = "stress line of channel " + std::to_string(channel);
  ActuatorFit f;
  f.line = fit_line(p, s, file, what);
  if (!(f.line.slope > 1e-9)) {
    std::ostringstream m;
    m << "a fingertip stress that rises with air pressure (the fitted slope is " << f.line.slope << " kPa/kPa)";
    throw InputError(file, what, m.str());
  }
  f.model.slope = f.line.slope;
  f.model.intercept_kPa = f.line.intercept;
  return f;
}

}  // namespace palprig
