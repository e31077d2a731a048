#include "mechanics/fe_report.hpp"

#include <cstdio>

namespace palprig::mechanics {

namespace {

std::string row(const char* format, double a, double b, double c, double d, double e, double f, double g = 0) {
  char line[256];
  std::snprintf(line, sizeof line, format, a, b, c, d, e, f, g);
  return line;
}

}  // namespace

std::string steps_csv(const ContactRun& run, const std::string& load_column) {
  std::string out =
      load_column + ",peak_kPa,node_peak_kPa,peak_at_mm,force_N_per_m,contact_length_mm,newton_iterations\n";
  for (const ContactStep& s : run.steps)
    out += row("%.4g,%.4f,%.4f,%.3f,%.4f,%.3f,%.0f\n", s.load, s.peak_kPa, s.node_peak_kPa, s.peak_s_mm,
               s.force_N_per_m, s.contact_length_mm, double(s.newton_iterations));
  return out;
}

std::string profiles_csv(const ContactRun& run, const std::string& load_column) {
  std::string out = load_column + ",s_mm,x_mm,y_mm,stress_kPa,stress_1mm_kPa\n";
  for (const ContactStep& s : run.steps)
    for (const ContactNode& n : s.profile)
      out += row("%.4g,%.4f,%.4f,%.4f,%.4f,%.4f\n", s.load, n.s_mm, n.x_mm, n.y_mm, n.pressure_kPa,
                 averaged_stress_kPa(s.profile, n.s_mm, kStressAveragingLength_mm / 2));
  return out;
}

}  // namespace palprig::mechanics
