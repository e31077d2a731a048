// The commands that need the rig stack (controller, rigs, inputs, experiments, calibration).
// The analyst-only build compiles rig_commands_absent.cpp instead.
#include "cli/commands.hpp"

void register_rig_commands(CLI::App& app) {
  register_run_command(app);
  register_demo_command(app);
  register_telemetry_command(app);
  register_experiment_command(app);
  register_sim_rig_command(app);
  register_calibrate_command(app);
  register_rt_check_command(app);
  register_check_command(app);
  register_igtl_replay_command(app);
  register_tracking_command(app);
  register_load_cell_command(app);
  register_fe_command(app);
  register_train_command(app);
}
