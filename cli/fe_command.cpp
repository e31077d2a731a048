// palprig fe indent|actuator|stress-model|table: paper 002's finite-element model of the
// fingertip (mechanics/, docs/finite-element.md). Each subcommand lives in its own file
// (cli/fe_*_command.cpp); this one groups them.
#include <CLI/CLI.hpp>

#include "cli/commands.hpp"

void register_fe_indent(CLI::App* fe);
void register_fe_actuator(CLI::App* fe);
void register_fe_stress_model(CLI::App* fe);
void register_fe_table(CLI::App* fe);

void register_fe_command(CLI::App& app) {
  CLI::App* fe = app.add_subcommand(
      "fe", "The fingertip finite-element model: indentation, the actuator, the stress model, the table");
  fe->require_subcommand(1);
  register_fe_indent(fe);
  register_fe_actuator(fe);
  register_fe_stress_model(fe);
  register_fe_table(fe);
}
