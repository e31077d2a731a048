#pragma once
// What the `palprig fe` subcommands share: the analysis options (plane strain or stress, element
// size), the progress line, the inputs' hash, and writing their tables and figures.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mechanics/contact_problems.hpp"

namespace palprig::cli {

struct FeAnalysisArgs {
  std::string plane = "strain";  // strain | stress
  double element_mm = 1.0;
};
void add_fe_analysis_options(CLI::App* sub, FeAnalysisArgs& args);
mechanics::SolveOptions solve_options(const FeAnalysisArgs& args);
std::string plane_text(const FeAnalysisArgs& args);  // "plane strain" | "plane stress"

// --loading press-first|together (fe actuator, fe stress-model), and the order it names.
void add_fe_loading_option(CLI::App* sub, std::string& loading);
mechanics::ActuatorLoading actuator_loading(const std::string& loading);

// The progress line on standard error while a solve runs: the step, what it reached, the time
// so far and an estimate of what is left, at most once a second (and for the last step).
class FeProgress {
 public:
  explicit FeProgress(std::string command) : command_(std::move(command)) {}
  void operator()(const mechanics::StepProgress& p);

 private:
  std::string command_;
  std::chrono::steady_clock::time_point last_{};
  bool shown_ = false;
};

// A hash of the input files' bytes and of the settings that change the result (64-bit FNV-1a,
// 16 hex digits): the cache key of `fe table` and the record in result files. Hand-written:
// a cache key, not a security property, and the standard library's std::hash is not promised
// to stay the same between runs.
std::string fe_inputs_hash(const std::vector<std::filesystem::path>& files, const std::string& settings);

// A comma-separated list of numbers ("0,10,20"); throws InputError naming `flag`.
std::vector<double> number_list(const std::string& text, const std::string& flag, double lo, double hi);

// Write text through the checked writer and name the file on standard output ("  wrote FILE").
void write_output(const std::filesystem::path& path, const std::string& text);
// Print the figures' files as "  plot: FILE".
void print_plots(const std::vector<std::filesystem::path>& files);
// printf-style formatting onto std::cout (the command line's checked standard output,
// cli/standard_output.hpp; std::printf would bypass it and come out of order).
[[gnu::format(printf, 1, 2)]] void print_out(const char* format, ...);

}  // namespace palprig::cli
