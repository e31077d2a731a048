#pragma once
// One registration function per capability; cli/main.cpp calls them all. Each subcommand is a
// thin layer: parse arguments, call one library function, print, return an exit code.
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

namespace palprig::cli {

// Exit codes shared by every subcommand.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFault = 1;     // the rig faulted while running (channels vented)
inline constexpr int kExitBadInput = 2;  // a file or argument was refused before anything moved

// End a subcommand with an exit code (CLI11 callbacks return void; main returns this code).
[[noreturn]] inline void finish(int exit_code) { throw CLI::RuntimeError(exit_code); }

// "1 trial", "32 trials": a count with its noun for the commands' lines.
inline std::string counted(long long n, const std::string& one, const std::string& many) {
  return std::to_string(n) + ' ' + (n == 1 ? one : many);
}

// The git commit the program was built from ("1a2b3c4d5e6f", "-dirty" added for uncommitted
// changes, "unknown" outside a clone): build/generated/palprig_git_commit.cpp, written at build time.
const char* git_commit() noexcept;

// Where the shipped data (scenes, rigs, traces) is taken from: the first existing place of
// cli/data_files.hpp's data_places() ($PALPRIG_DATA_DIR, the installed share/palprig, the source tree).
std::filesystem::path data_dir();

}  // namespace palprig::cli

// Registration functions, each defined in its own cli/*_command.cpp. The process context
// (data_dir) is cli/process_context.cpp; SIGINT/SIGTERM reach a run through
// runtime/run_control.hpp's process_run_control().
void register_run_command(CLI::App& app);
void register_demo_command(CLI::App& app);
void register_telemetry_command(CLI::App& app);
void register_stats_command(CLI::App& app);
void register_experiment_command(CLI::App& app);
void register_export_command(CLI::App& app);
void register_sim_rig_command(CLI::App& app);
void register_calibrate_command(CLI::App& app);
void register_scene_command(CLI::App& app);
// The window: gui_command.cpp, or gui_command_absent.cpp (a `gui` that says the build has none).
void register_gui_command(CLI::App& app);
void register_rt_check_command(CLI::App& app);
void register_store_command(CLI::App& app);
// palprig check: load files through their readers (check_command.cpp; needs inputs/, so a rig command).
void register_check_command(CLI::App& app);
// Tracked fingers: the OpenIGTLink replay server, the tracker's calibration, the load cells.
void register_igtl_replay_command(CLI::App& app);
void register_tracking_command(CLI::App& app);
void register_load_cell_command(CLI::App& app);
// The fingertip finite-element model (fe_command.cpp and fe_*_command.cpp; needs GetFEM, so a rig command).
void register_fe_command(CLI::App& app);
// palprig data list / data dir: the shipped files found by name (data_command.cpp, data_files.cpp).
void register_data_command(CLI::App& app);
// Training programmes (train_command.cpp): enrol, next, status, benchmark.
void register_train_command(CLI::App& app);
// Every command that needs the rig stack: rig_commands.cpp, or rig_commands_absent.cpp in the
// analyst-only build (-DPALPRIG_RIG=OFF).
void register_rig_commands(CLI::App& app);
