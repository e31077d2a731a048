#include "calibration/branch_fits.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "core/input_error.hpp"

namespace palprig {

const char* to_string(MeasuredSignal r) noexcept { return r == MeasuredSignal::monitor ? "monitor" : "sensor"; }

double response_of(const HoldPoint& p, MeasuredSignal r) noexcept {
  return r == MeasuredSignal::monitor ? p.monitor_kPa : p.sensor;
}

namespace {

// Levels are commanded values; readings of one level across repeats share a key.
long long level_key(double command_kPa) { return std::llround(command_kPa * 1000.0); }

std::string describe(const HoldPoint& p) {
  std::ostringstream s;
  s << "line " << p.line << " (channel " << p.channel << ", repeat " << p.repeat << " " << to_string(p.branch) << ", "
    << p.command_kPa << " kPa)";
  return s.str();
}

void require_values(std::span<const HoldPoint> pts, MeasuredSignal r, const std::string& file,
                    const std::string& what) {
  for (const auto& p : pts)
    if (!std::isfinite(response_of(p, r)))
      throw InputError(file, describe(p), "a " + std::string(to_string(r)) + " reading for " + what);
}

}  // namespace

BranchFits fit_branches(std::span<const HoldPoint> pts, MeasuredSignal r, const std::string& file,
                        const std::string& what) {
  require_values(pts, r, file, what);
  std::vector<double> xi, yi, xd, yd, xb, yb;
  // level -> (inflation values, deflation values)
  std::map<long long, std::pair<std::vector<double>, std::vector<double>>> by_level;
  std::map<int, int> repeats;
  for (const auto& p : pts) {
    const double v = response_of(p, r);
    auto& slot = by_level[level_key(p.command_kPa)];
    if (p.branch == SweepBranch::inflation) {
      xi.push_back(p.command_kPa);
      yi.push_back(v);
      slot.first.push_back(v);
    } else if (p.branch == SweepBranch::deflation) {
      xd.push_back(p.command_kPa);
      yd.push_back(v);
      slot.second.push_back(v);
    } else
      continue;
    xb.push_back(p.command_kPa);
    yb.push_back(v);
    repeats[p.repeat] = 1;
  }
  BranchFits f;
  f.inflation = fit_line(xi, yi, file, what + " inflation");
  f.deflation = fit_line(xd, yd, file, what + " deflation");
  f.both = fit_line(xb, yb, file, what + " both branches");
  f.repeats = repeats.size();
  f.levels = by_level.size();
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
  };
  double gap_sum = 0, sd_sum = 0;
  std::size_t gap_n = 0, sd_n = 0;
  for (const auto& [level, branches] : by_level) {
    if (!branches.first.empty() && !branches.second.empty()) {
      gap_sum += mean(branches.second) - mean(branches.first);
      ++gap_n;
    }
    for (const auto* values : {&branches.first, &branches.second}) {
      if (values->size() < 2) continue;
      const double m = mean(*values);
      double ss = 0;
      for (double x : *values) ss += (x - m) * (x - m);
      if (std::abs(m) > 1e-9) {
        sd_sum += 100.0 * std::sqrt(ss / double(values->size() - 1)) / std::abs(m);
        ++sd_n;
      }
    }
  }
  f.gap = gap_n ? gap_sum / double(gap_n) : 0.0;
  f.repeat_sd_percent = sd_n ? sd_sum / double(sd_n) : std::numeric_limits<double>::quiet_NaN();
  return f;
}

void check_staircase_monotone(std::span<const HoldPoint> pts, MeasuredSignal r, double tolerance_fraction,
                              const std::string& file, const std::string& what) {
  require_values(pts, r, file, what);
  // Branch runs in file order: (repeat, branch) -> points.
  std::map<std::pair<int, int>, std::vector<const HoldPoint*>> runs;
  for (const auto& p : pts)
    if (p.branch != SweepBranch::none) runs[{p.repeat, int(p.branch)}].push_back(&p);
  for (const auto& [key, run] : runs) {
    if (run.size() < 2) continue;
    const bool up = key.second == int(SweepBranch::inflation);
    double lo = response_of(*run[0], r), hi = lo;
    for (const auto* p : run) {
      lo = std::min(lo, response_of(*p, r));
      hi = std::max(hi, response_of(*p, r));
    }
    const double tolerance = tolerance_fraction * (hi - lo);
    for (std::size_t k = 1; k < run.size(); ++k) {
      const HoldPoint &a = *run[k - 1], &b = *run[k];
      const double step = b.command_kPa - a.command_kPa;
      if (up ? step < 0 : step > 0)
        throw InputError(file, describe(b),
                         std::string("an ") + to_string(b.branch) + " staircase whose command " +
                             (up ? "rises" : "falls") + " (it goes from " + std::to_string(a.command_kPa) + " to " +
                             std::to_string(b.command_kPa) + " kPa)");
      const double moved = response_of(b, r) - response_of(a, r);
      if (step != 0 && (up ? moved < -tolerance : moved > tolerance)) {
        std::ostringstream s;
        s.precision(4);  // significant digits: readable for kPa and for a sensor in mm alike
        s << "a monotone " << to_string(r) << " along the " << to_string(b.branch) << " staircase of " << what
          << ": it " << (up ? "fell" : "rose") << " from " << response_of(a, r) << " to " << response_of(b, r)
          << " while the command went from " << a.command_kPa << " to " << b.command_kPa
          << " kPa (non-monotone sweep: check for leaks, a sticking regulator or a loose sensor)";
        throw InputError(file, describe(b), s.str());
      }
    }
  }
}

void check_response_moves(std::span<const HoldPoint> pts, MeasuredSignal r, const std::string& file,
                          const std::string& what) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::size_t n = 0;
  for (const auto& p : pts) {
    const double v = response_of(p, r);
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    ++n;
  }
  if (n == 0) throw InputError(file, what, std::string("readings in the ") + to_string(r) + " column");
  if (!(hi - lo > 1e-9 * std::max(1.0, std::abs(hi)))) {
    std::ostringstream s;
    s << "a " << to_string(r) << " that moves with the command; it never moved (all " << n << " readings are " << lo
      << "): check its wiring, supply and scaling";
    throw InputError(file, what, s.str());
  }
}

RegulatorCheck check_regulator(const LineFit& both, double tolerance_kPa) noexcept {
  RegulatorCheck c;
  c.tolerance_kPa = tolerance_kPa;
  for (double x : {both.x_min, both.x_max}) {
    const double d = std::abs(both.at(x) - x);
    if (d >= c.worst_deviation_kPa) {
      c.worst_deviation_kPa = d;
      c.at_command_kPa = x;
    }
  }
  return c;
}

}  // namespace palprig
