// palprig calibrate sweep|fit|evaluate: the calibration workflow of a rig (calibration/README.md).
// Each subcommand lives in its own file (cli/calibrate_*_command.cpp); this one groups them.
#include <CLI/CLI.hpp>

#include "cli/commands.hpp"

void register_calibrate_sweep(CLI::App* cal);
void register_calibrate_fit(CLI::App* cal);
void register_calibrate_evaluate(CLI::App* cal);

void register_calibrate_command(CLI::App& app) {
  CLI::App* cal = app.add_subcommand("calibrate", "Calibrate a rig: sweep, fit the models, evaluate the compensation");
  cal->require_subcommand(1);
  register_calibrate_sweep(cal);
  register_calibrate_fit(cal);
  register_calibrate_evaluate(cal);
}
