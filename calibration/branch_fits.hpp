#pragma once
// Paper 002 fig. 8: a line per branch of the staircase (inflation, deflation, both together)
// with R^2, for each actuator and for all of them pooled, plus what a lab engineer checks
// around it: the gap between the branches (the hysteresis), the spread between repeats (the
// paper's 2.82 % of reading), staircases that run the wrong way, a sensor that never moved,
// and a regulator whose monitor is off the commanded line.
#include <optional>
#include <span>
#include <string>

#include "calibration/line_fit.hpp"
#include "calibration/sweep_csv.hpp"

namespace palprig {

// What a branch fit is fitted to: the regulator's monitor reading or the external sensor.
enum class MeasuredSignal { monitor, sensor };
const char* to_string(MeasuredSignal r) noexcept;
double response_of(const HoldPoint& p, MeasuredSignal r) noexcept;

struct BranchFits {
  LineFit inflation, deflation, both;  // response against the commanded pressure
  double gap = 0;                      // mean over levels of (deflation - inflation), response units
  double repeat_sd_percent = 0;        // mean over levels of SD across repeats / |mean|, NaN with one repeat
  std::size_t levels = 0, repeats = 0;
};

// Staircase points only (segment staircase, branch inflation or deflation), one channel or
// pooled. Throws InputError naming `what` when a branch is missing or a fit is degenerate.
BranchFits fit_branches(std::span<const HoldPoint> staircase, MeasuredSignal response, const std::string& file,
                        const std::string& what);

// Every repeat's inflation branch must rise with the command and its deflation branch fall;
// a reading may step back by at most `tolerance_fraction` of the branch's span (noise).
void check_staircase_monotone(std::span<const HoldPoint> staircase, MeasuredSignal response, double tolerance_fraction,
                              const std::string& file, const std::string& what);

// Refuses a response that stays constant over the whole record (a sensor not wired, a
// regulator without supply).
void check_response_moves(std::span<const HoldPoint> points, MeasuredSignal response, const std::string& file,
                          const std::string& what);

struct RegulatorCheck {
  double worst_deviation_kPa = 0;  // |fitted monitor - command| at the worse end of the range
  double at_command_kPa = 0;
  double tolerance_kPa = 0;
  bool passed() const noexcept { return worst_deviation_kPa <= tolerance_kPa; }
};
// The commanded-vs-monitored line (both branches) compared with the identity.
RegulatorCheck check_regulator(const LineFit& both, double tolerance_kPa) noexcept;

}  // namespace palprig
