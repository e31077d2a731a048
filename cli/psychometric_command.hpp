#pragma once
// `palprig stats psychometric`: psychometric function fits of a CSV or a trial database.
#include <CLI/CLI.hpp>

void register_psychometric_command(CLI::App& stats_app);
