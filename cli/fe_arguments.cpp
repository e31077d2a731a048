#include "cli/fe_arguments.hpp"

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "io/checked_output.hpp"
#include "models/decimal_number.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig::cli {

void add_fe_analysis_options(CLI::App* sub, FeAnalysisArgs& args) {
  sub->add_option("--plane", args.plane,
                  "2D assumption: strain (a long finger, thick tissue) or stress (paper 002's CPS4R)")
      ->default_val("strain")
      ->check(CLI::IsMember({"strain", "stress"}));
  sub->add_option("--element-mm", args.element_mm, "Element size at the contact (nine-node elements)")
      ->default_val(1.0)
      ->check(CLI::Range(0.2, 3.0));
}

mechanics::SolveOptions solve_options(const FeAnalysisArgs& args) {
  mechanics::SolveOptions o;
  o.plane = args.plane == "stress" ? mechanics::PlaneMode::plane_stress : mechanics::PlaneMode::plane_strain;
  o.element_mm = args.element_mm;
  return o;
}

std::string plane_text(const FeAnalysisArgs& args) { return args.plane == "stress" ? "plane stress" : "plane strain"; }

void FeProgress::operator()(const mechanics::StepProgress& p) {
  const auto now = std::chrono::steady_clock::now();
  const bool last = p.step >= p.steps;
  if (shown_ && !last && now - last_ < std::chrono::seconds(1)) return;
  shown_ = true;
  last_ = now;
  char line[256];
  std::snprintf(line, sizeof line, "palprig %s: step %d of %d (%s), %.0f s, about %.0f s left\n", command_.c_str(),
                p.step, p.steps, p.what.c_str(), p.elapsed_s, p.remaining_s);
  std::cerr << line << std::flush;
}

void add_fe_loading_option(CLI::App* sub, std::string& loading) {
  sub->add_option("--loading", loading,
                  "press-first: the finger pressed --press-mm, then the air raised; together: the press rising "
                  "with the air (--press-mm at the highest pressure), paper 002's 'at the same time'")
      ->check(CLI::IsMember({"press-first", "together"}))
      ->default_val("press-first");
}

mechanics::ActuatorLoading actuator_loading(const std::string& loading) {
  return loading == "together" ? mechanics::ActuatorLoading::together : mechanics::ActuatorLoading::press_first;
}

std::string fe_inputs_hash(const std::vector<std::filesystem::path>& files, const std::string& settings) {
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&](const std::string& bytes) {
    for (unsigned char c : bytes) {
      h ^= c;
      h *= 1099511628211ull;
    }
    h ^= 0xff;  // a separator, so that moving bytes between parts changes the hash
    h *= 1099511628211ull;
  };
  for (const auto& f : files) mix(read_regular_file(f, std::uintmax_t{16} * 1024 * 1024, "an input file"));
  mix(settings);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

std::vector<double> number_list(const std::string& text, const std::string& flag, double lo, double hi) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    double v = 0;
    if (parse_decimal(cell, v) != DecimalCell::number || v < lo || v > hi) {
      std::ostringstream range;
      range << "numbers in " << lo << ".." << hi;
      throw InputError(flag, "'" + cell + "'", range.str());
    }
    out.push_back(v);
  }
  if (out.empty()) throw InputError(flag, "(empty)", "a comma-separated list of numbers");
  return out;
}

void write_output(const std::filesystem::path& path, const std::string& text) {
  write_file_checked(path, text);
  std::cout << "  wrote " << path.string() << "\n";
}

void print_out(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list again;
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string text(n > 0 ? std::size_t(n) : 0, '\0');
  if (n > 0) std::vsnprintf(text.data(), text.size() + 1, format, again);
  va_end(again);
  std::cout << text;
}

void print_plots(const std::vector<std::filesystem::path>& files) {
  for (const auto& f : files) std::cout << "  plot: " << f.string() << "\n";
}

}  // namespace palprig::cli
