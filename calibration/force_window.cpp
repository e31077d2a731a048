#include "calibration/force_window.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {

struct Stats {
  double sum = 0, sum_sq = 0;
  std::size_t n = 0;
  double mean() const { return sum / double(n); }
  double sd() const { return n > 1 ? std::sqrt(std::max(0.0, (sum_sq - sum * sum / double(n)) / double(n - 1))) : 0.0; }
};

double number(const std::string& c, const std::string& file, const std::string& where, const char* column) {
  std::string t = c;
  t.erase(0, t.find_first_not_of(" \t"));
  t.erase(t.find_last_not_of(" \t\r") + 1);
  double v = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
    throw InputError(file, where, std::string("a finite number in column ") + column + ", got \"" + t + "\"");
  return v;
}

}  // namespace

ForceWindowFit force_window_from_presses(const std::filesystem::path& path, double diastolic_mmHg,
                                         double systolic_mmHg) {
  const std::string file = path.string();
  std::ifstream in = open_regular_file(path, kMaxTableFileBytes, "a presses CSV", std::ios::in);
  std::string line;
  std::size_t line_no = 0;
  bool header = false;
  Stats low, high;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const std::string where = "line " + std::to_string(line_no);
    std::vector<std::string> cells;
    std::string c;
    std::istringstream s(line);
    while (std::getline(s, c, ',')) cells.push_back(c);
    if (!header) {
      if (cells.size() != 2 || cells[0].find("reference_mmHg") == std::string::npos ||
          cells[1].find("force_N") == std::string::npos)
        throw InputError(file, where, "the header reference_mmHg,force_N");
      header = true;
      continue;
    }
    if (cells.size() != 2) throw InputError(file, where, "two cells: reference_mmHg,force_N");
    const double ref = number(cells[0], file, where, "reference_mmHg");
    const double f = number(cells[1], file, where, "force_N");
    if (f < 0) throw InputError(file, where, "a pressing force >= 0 N");
    Stats* slot = ref == diastolic_mmHg ? &low : ref == systolic_mmHg ? &high : nullptr;
    if (!slot) {
      std::ostringstream m;
      m << "a reference press at " << diastolic_mmHg << " (diastolic) or " << systolic_mmHg << " mmHg (systolic), got "
        << ref;
      throw InputError(file, where, m.str());
    }
    slot->sum += f;
    slot->sum_sq += f * f;
    ++slot->n;
  }
  if (!header) throw InputError(file, "header", "the header reference_mmHg,force_N");
  if (low.n == 0) throw InputError(file, "presses", "at least one press at the diastolic reference");
  if (high.n == 0) throw InputError(file, "presses", "at least one press at the systolic reference");
  ForceWindowFit fit;
  fit.window.f_min_N = low.mean();
  fit.window.f_max_N = high.mean();
  fit.window.diastolic_mmHg = diastolic_mmHg;
  fit.window.systolic_mmHg = systolic_mmHg;
  fit.f_min_sd_N = low.sd();
  fit.f_max_sd_N = high.sd();
  fit.presses_min = low.n;
  fit.presses_max = high.n;
  if (!(fit.window.f_max_N > fit.window.f_min_N)) {
    std::ostringstream m;
    m << "a systolic press force above the diastolic one (got F_min " << fit.window.f_min_N << " N, F_max "
      << fit.window.f_max_N << " N)";
    throw InputError(file, "presses", m.str());
  }
  return fit;
}

}  // namespace palprig
